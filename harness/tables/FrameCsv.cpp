#include "harness/tables/FrameCsv.h"

#include <fstream>
#include <ostream>
#include <sstream>
#include <string>

#include "core/Errors.h"
#include "harness/tables/CsvText.h"

namespace cdb {

namespace {
const std::string& header() {
  static const std::string text = [] {
    std::string h;
    for (const auto& column : kFrameColumns) {
      if (!h.empty()) h += ',';
      h += column.name;
    }
    return h;
  }();
  return text;
}

// Throws std::logic_error (from std::sto*) when the text is not a number.
void parseField(FrameRecord& r, const FrameField& field, const std::string& text) {
  std::visit(
      [&](auto member) {
        auto& value = r.*member;
        using T = std::remove_reference_t<decltype(value)>;
        if constexpr (std::is_same_v<T, std::string>)
          value = text;
        else if constexpr (std::is_same_v<T, int>)
          value = std::stoi(text);
        else if constexpr (std::is_same_v<T, double>)
          value = std::stod(text);
        else
          value = std::stoull(text);
      },
      field);
}
}  // namespace

void writeFrameCsvHeader(std::ostream& out) { out << header() << '\n'; }

void writeFrameCsvRow(std::ostream& out, const FrameRecord& r) {
  const char* separator = "";
  for (const auto& column : kFrameColumns) {
    out << separator;
    std::visit([&](auto member) { out << r.*member; }, column.field);
    separator = ",";
  }
  out << '\n';
}

std::vector<FrameRecord> readFrameCsv(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot open frames file");
  std::string line;
  if (!std::getline(in, line) || line != header())
    throw InputError(file.string() + ":1: expected the frames.csv header");
  std::vector<FrameRecord> rows;
  int lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty()) continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (f.size() != kFrameColumns.size())
      throw InputError(file.string() + ":" + std::to_string(lineNo) + ": expected " +
                       std::to_string(kFrameColumns.size()) + " columns, got " +
                       std::to_string(f.size()));
    try {
      FrameRecord r;
      for (std::size_t i = 0; i < kFrameColumns.size(); ++i)
        parseField(r, kFrameColumns[i].field, f[i]);
      rows.push_back(std::move(r));
    } catch (const std::logic_error&) {
      throw InputError(file.string() + ":" + std::to_string(lineNo) + ": expected numbers");
    }
  }
  return rows;
}

void writeFrameColumnsCsv(std::ostream& out) {
  out << "column,kind,description\n";
  for (const auto& column : kFrameColumns)
    out << column.name << ',' << kindOf(column.field) << ',' << csvQuoted(column.description) << '\n';
}

}  // namespace cdb
