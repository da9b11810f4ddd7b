#include "sim/cli/help_format.hpp"

#include "sim/cli/table.hpp"

#include <algorithm>
#include <sstream>

namespace bimloc::cli {
namespace {

// What a description has left of the terminal beside the option and subcommand names.
std::size_t descriptionWidth(std::size_t column_width) {
  return kTableColumns > column_width + 20 ? kTableColumns - column_width : 20;
}

}  // namespace

std::string wrapLines(const std::string& text, std::size_t width) {
  // The descriptions are written broken at about 110 columns: a line that goes on a paragraph
  // (not empty, not indented) joins it, and the paragraph is broken again at `width`.
  std::string out, paragraph;
  const auto flush = [&] {
    if (!paragraph.empty()) out += wrapText(paragraph, width);
    paragraph.clear();
  };
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line.front() == ' ') {
      flush();
      out += line + "\n";
    } else {
      paragraph += (paragraph.empty() ? "" : " ") + line;
    }
  }
  flush();
  if (!out.empty() && out.back() == '\n' && (text.empty() || text.back() != '\n')) out.pop_back();
  return out;
}

std::string firstSentence(const std::string& text) {
  std::string joined = text.substr(0, text.find("\n\n"));  // the first paragraph
  std::replace(joined.begin(), joined.end(), '\n', ' ');
  std::size_t stop = joined.find(". ");
  while (stop != std::string::npos && stop > 0 && joined[stop - 1] == '.') stop = joined.find(". ", stop + 1);  // "..." goes on
  return stop == std::string::npos ? joined : joined.substr(0, stop + 1);
}

std::string HelpFormatter::make_description(const CLI::App* app) const {
  return wrapLines(CLI::Formatter::make_description(app), kTableColumns);
}

std::string HelpFormatter::make_option_desc(const CLI::Option* opt) const {
  return wrapLines(opt->get_description(), descriptionWidth(get_column_width()));
}

std::string HelpFormatter::make_subcommand(const CLI::App* sub) const {
  std::stringstream out;
  const auto summary = summaries_.find(sub->get_name());
  const std::string line = summary != summaries_.end() ? summary->second : firstSentence(sub->get_description());
  CLI::detail::format_help(out, sub->get_display_name(true), wrapLines(line, descriptionWidth(get_column_width())),
                           get_column_width());
  return out.str();
}

}  // namespace bimloc::cli
