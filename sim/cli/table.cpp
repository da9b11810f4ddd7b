#include "sim/cli/table.hpp"

#include <algorithm>
#include <cstdio>

namespace bimloc::cli {
namespace {

// Display width of a UTF-8 string: count the bytes that start a code point.
std::size_t width(const std::string& s) {
  return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

}  // namespace

std::vector<std::size_t> Table::widths() const {
  std::vector<std::size_t> widths;
  for (const auto& row : rows_)
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (widths.size() <= c) widths.push_back(0);
      widths[c] = std::max(widths[c], width(row[c]));
    }
  return widths;
}

void Table::print(std::ostream& out, std::size_t max_width) const {
  const std::vector<std::size_t> widths = this->widths();
  if (widths.empty()) return;
  // Blocks of columns [begin, end), greedily as many as fit beside the first column.
  std::vector<std::pair<std::size_t, std::size_t>> blocks;
  for (std::size_t c = 1; c < widths.size();) {
    std::size_t used = widths[0], end = c;
    while (end < widths.size() && (end == c || used + 2 + widths[end] <= max_width)) used += 2 + widths[end++];
    blocks.emplace_back(c, end);
    c = end;
  }
  if (blocks.size() <= 1) return printWide(out);
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const auto cellsOf = [&](const std::vector<std::string>& row) {
      std::vector<std::string> cells{row.empty() ? std::string() : row[0]};
      for (std::size_t c = blocks[b].first; c < blocks[b].second; ++c) cells.push_back(c < row.size() ? row[c] : "");
      return cells;
    };
    Table part(cellsOf(rows_[0]));
    for (std::size_t r = 1; r < rows_.size(); ++r) part.add(cellsOf(rows_[r]));
    if (b > 0) out << "\n";
    part.printWide(out);
  }
}

void Table::printWide(std::ostream& out) const {
  const std::vector<std::size_t> widths = this->widths();
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const auto& row = rows_[r];
    for (std::size_t c = 0; c < row.size(); ++c) {
      // First column left-aligned (names), the others right-aligned (numbers).
      const std::string pad(widths[c] - width(row[c]), ' ');
      out << (c == 0 ? row[c] + pad : pad + row[c]) << (c + 1 < row.size() ? "  " : "\n");
    }
    if (r == 0) {
      std::size_t total = 0;
      for (auto w : widths) total += w + 2;
      out << std::string(total > 2 ? total - 2 : 0, '-') << "\n";
    }
  }
}

std::string wrapText(const std::string& text, std::size_t max_width) {
  std::string out, line;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t space = std::min(text.find(' ', at), text.size());
    const std::string word = text.substr(at, space - at);
    at = space + 1;
    if (word.empty()) continue;
    if (!line.empty() && width(line) + 1 + width(word) > max_width) out += line + "\n", line.clear();
    line += (line.empty() ? "" : " ") + word;
  }
  return line.empty() ? out : out + line + "\n";
}

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

}  // namespace bimloc::cli
