#pragma once
// harness/common/: what the harness' rooms share. AtomicFile (this file) writes a result through a
// temporary file and a rename (run, check, snapshot); BuildCommit is the commit the binary was
// built from and MachineInfo the machine it runs on, both recorded with results (run, merge,
// check, the benchmarks).
//
// Results are written to a temporary file beside the target and renamed over it, so a reader
// (or a resumed run) never sees a half-written file.
#include <filesystem>
#include <string_view>

namespace cdb {

// Throws RunError naming the file when it cannot be written.
void writeFileAtomically(const std::filesystem::path& file, std::string_view content);

}  // namespace cdb
