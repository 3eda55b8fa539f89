#pragma once
// harness/tables/: the text a run leaves for people and tools. FrameRecord is a row of frames.csv
// and kFrameColumns its columns, FrameCsv writes and reads the file; TableWriters (this file)
// prints a Table to the console, as Markdown and as CSV, and RunTables makes a finished run's
// average and maximum tables; StrategyListCsv is `cdbench strategies --csv`; CsvText quotes a
// CSV field.
//
// One table, three forms: the console (columns aligned between rules of dashes, as Google
// Benchmark's console reporter prints), Markdown and CSV. A Table holds text and numbers; each
// writer decides how a number reads and pads with fmt's width and alignment specifiers, so the
// three forms cannot disagree on what a table says.
#include <cstdint>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

namespace cdb {

// A blank, a text, a time (or any real number) or a count.
using TableCell = std::variant<std::monostate, std::string, double, std::uint64_t>;

struct Table {
  std::string title;                       // the line above it (a heading in Markdown)
  std::string key;                         // what the table is among several ("average")
  std::vector<std::string> header;         // column 0 names the rows
  std::vector<std::vector<TableCell>> rows;  // each as long as the header
  std::vector<std::string> notes;          // lines below it; not in the CSV
};

class TableWriter {
 public:
  virtual ~TableWriter() = default;
  virtual void write(std::ostream& out, const std::vector<Table>& tables) const = 0;
};

// Each table: its title, a rule, the header, a rule, the rows, its notes. A column holding a
// number is right-aligned (its header too), the others left-aligned; every column is as wide as
// its widest cell. Reals with `decimals` decimals.
class ConsoleTableWriter final : public TableWriter {
 public:
  explicit ConsoleTableWriter(int decimals = 2) : decimals_(decimals) {}
  void write(std::ostream& out, const std::vector<Table>& tables) const override;

 private:
  int decimals_;
};

// Each table: "## title", a pipe table (number columns right-aligned), its notes as paragraphs.
class MarkdownTableWriter final : public TableWriter {
 public:
  explicit MarkdownTableWriter(int decimals = 2) : decimals_(decimals) {}
  void write(std::ostream& out, const std::vector<Table>& tables) const override;

 private:
  int decimals_;
};

// One header, `keyColumn` followed by the tables' header (every table must have the same one:
// std::invalid_argument otherwise), then each table's rows after its key. Titles and notes are
// left out; text is quoted where RFC 4180 needs it. Reals with `decimals` decimals.
class CsvTableWriter final : public TableWriter {
 public:
  explicit CsvTableWriter(std::string keyColumn, int decimals = 4)
      : keyColumn_(std::move(keyColumn)), decimals_(decimals) {}
  void write(std::ostream& out, const std::vector<Table>& tables) const override;

 private:
  std::string keyColumn_;
  int decimals_;
};

}  // namespace cdb
