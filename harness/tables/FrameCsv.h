#pragma once
// frames.csv: one FrameRecord per line, with a header, columns as kFrameColumns lists them. Read
// back for merging and resuming.
#include <filesystem>
#include <iosfwd>
#include <vector>

#include "harness/tables/FrameRecord.h"

namespace cdb {

void writeFrameCsvHeader(std::ostream& out);
void writeFrameCsvRow(std::ostream& out, const FrameRecord& r);
// Throws InputError naming the file and line for a malformed file.
[[nodiscard]] std::vector<FrameRecord> readFrameCsv(const std::filesystem::path& file);

// `cdbench frame-columns`: column,kind,description, one line per column of frames.csv.
void writeFrameColumnsCsv(std::ostream& out);

}  // namespace cdb
