#include "harness/tables/TableWriters.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <fmt/ranges.h>

#include "harness/tables/CsvText.h"

namespace cdb {

namespace {

std::string text(const TableCell& cell, int decimals) {
  return std::visit(
      [decimals](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>)
          return "";
        else if constexpr (std::is_same_v<T, std::string>)
          return v;
        else if constexpr (std::is_same_v<T, double>)
          return fmt::format("{:.{}f}", v, decimals);
        else
          return fmt::format("{}", v);
      },
      cell);
}

bool isNumber(const TableCell& cell) {
  return std::holds_alternative<double>(cell) || std::holds_alternative<std::uint64_t>(cell);
}

// Per column: whether it holds a number (right-aligned).
std::vector<bool> numberColumns(const Table& table) {
  std::vector<bool> numeric(table.header.size(), false);
  for (const auto& row : table.rows)
    for (std::size_t c = 0; c < row.size() && c < numeric.size(); ++c)
      numeric[c] = numeric[c] || isNumber(row[c]);
  return numeric;
}

}  // namespace

void ConsoleTableWriter::write(std::ostream& out, const std::vector<Table>& tables) const {
  // Cell texts of every table, and per column the widest cell of all tables with the same header,
  // so that tables printed one under the other (averages, maxima) line up.
  std::vector<std::vector<std::vector<std::string>>> texts;
  for (const Table& table : tables) {
    auto& cells = texts.emplace_back();
    for (const auto& row : table.rows) {
      auto& line = cells.emplace_back();
      for (std::size_t c = 0; c < table.header.size(); ++c)
        line.push_back(c < row.size() ? text(row[c], decimals_) : "");
    }
  }
  const auto widths = [&](const Table& table) {
    std::vector<std::size_t> width;
    for (const auto& h : table.header) width.push_back(h.size());
    for (std::size_t t = 0; t < tables.size(); ++t) {
      if (tables[t].header != table.header) continue;
      for (const auto& line : texts[t])
        for (std::size_t c = 0; c < width.size(); ++c) width[c] = std::max(width[c], line[c].size());
    }
    return width;
  };

  for (std::size_t t = 0; t < tables.size(); ++t) {
    const Table& table = tables[t];
    const std::size_t n = table.header.size();
    const auto width = widths(table);
    const auto numeric = numberColumns(table);
    const auto line = [&](const std::vector<std::string>& values) {
      std::string s;
      for (std::size_t c = 0; c < n; ++c) {
        if (c > 0) s += "   ";
        s += numeric[c] ? fmt::format("{:>{}}", values[c], width[c])
                        : fmt::format("{:<{}}", values[c], width[c]);
      }
      // A left-aligned last column would end in spaces.
      s.erase(s.find_last_not_of(' ') + 1);
      return s;
    };
    std::size_t total = 0;
    for (std::size_t c = 0; c < n; ++c) total += width[c] + (c > 0 ? 3 : 0);
    const std::string rule(total, '-');
    if (t > 0) out << '\n';
    if (!table.title.empty()) fmt::print(out, "{}\n", table.title);
    fmt::print(out, "{}\n{}\n{}\n", rule, line(table.header), rule);
    for (const auto& values : texts[t]) fmt::print(out, "{}\n", line(values));
    for (const auto& note : table.notes) fmt::print(out, "{}\n", note);
  }
}

void MarkdownTableWriter::write(std::ostream& out, const std::vector<Table>& tables) const {
  bool first = true;
  for (const Table& table : tables) {
    if (!first) out << '\n';
    first = false;
    if (!table.title.empty()) fmt::print(out, "## {}\n\n", table.title);
    const auto numeric = numberColumns(table);
    fmt::print(out, "| {} |\n|", fmt::join(table.header, " | "));
    for (std::size_t c = 0; c < table.header.size(); ++c) out << (numeric[c] ? "---:|" : "---|");
    out << '\n';
    for (const auto& row : table.rows) {
      std::vector<std::string> values;
      for (std::size_t c = 0; c < table.header.size(); ++c)
        values.push_back(c < row.size() ? text(row[c], decimals_) : "");
      fmt::print(out, "| {} |\n", fmt::join(values, " | "));
    }
    for (const auto& note : table.notes) fmt::print(out, "\n{}\n", note);
  }
}

void CsvTableWriter::write(std::ostream& out, const std::vector<Table>& tables) const {
  if (tables.empty()) return;
  const auto field = [](const std::string& s) {
    return s.find_first_of(",\"\r\n") == std::string::npos ? s : csvQuoted(s);
  };
  const auto& header = tables.front().header;
  std::vector<std::string> names{field(keyColumn_)};
  for (const auto& h : header) names.push_back(field(h));
  fmt::print(out, "{}\n", fmt::join(names, ","));
  for (const Table& table : tables) {
    if (table.header != header)
      throw std::invalid_argument("CsvTableWriter: tables '" + tables.front().key + "' and '" +
                                  table.key + "' have different headers");
    for (const auto& row : table.rows) {
      std::vector<std::string> values{field(table.key)};
      for (std::size_t c = 0; c < header.size(); ++c)
        values.push_back(field(c < row.size() ? text(row[c], decimals_) : ""));
      fmt::print(out, "{}\n", fmt::join(values, ","));
    }
  }
}

}  // namespace cdb
