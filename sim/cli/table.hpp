// A plain text table for terminal output: columns padded to their widest cell.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace bimloc::cli {

// A terminal's width: every table a command prints fits in it (print), unless asked wide.
inline constexpr std::size_t kTableColumns = 100;

class Table {
 public:
  explicit Table(std::vector<std::string> header) : rows_{std::move(header)} {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  // Within `max_width` columns where it can be: the columns after the first split into blocks,
  // one under the other, each repeating the first column. (A single column wider than that is
  // printed whole.)
  void print(std::ostream& out, std::size_t max_width = kTableColumns) const;
  void printWide(std::ostream& out) const;  // every row on one line, however wide

 private:
  std::vector<std::size_t> widths() const;  // of each column, the widest cell
  std::vector<std::vector<std::string>> rows_;
};

std::string fixed(double value, int decimals);

// `text` broken at spaces into lines of at most `width` columns (a longer word on a line of
// its own), each ended by '\n'.
std::string wrapText(const std::string& text, std::size_t width);

}  // namespace bimloc::cli
