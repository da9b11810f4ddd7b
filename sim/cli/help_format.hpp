// `--help` within a terminal's width (table.hpp: kTableColumns): CLI11 2.1 prints every
// description on one line, however long, and lists each subcommand with its whole description.
// This formatter wraps descriptions at spaces and lists a subcommand by its first sentence
// (`bimloc SUBCOMMAND --help` gives the rest), or by the line `summaries` gives it.
#pragma once

#include <CLI/CLI.hpp>

#include <cstddef>
#include <map>
#include <string>
#include <utility>

namespace bimloc::cli {

class HelpFormatter : public CLI::Formatter {
 public:
  explicit HelpFormatter(std::map<std::string, std::string> summaries = {}) : summaries_(std::move(summaries)) {}
  std::string make_description(const CLI::App* app) const override;
  std::string make_option_desc(const CLI::Option* opt) const override;
  std::string make_subcommand(const CLI::App* sub) const override;

 private:
  std::map<std::string, std::string> summaries_;  // a subcommand's name -> its line in a listing
};

// `text` wrapped to `width` columns: the lines of a paragraph joined and broken again at spaces;
// an empty line, or one that starts with a space (an example, an aligned list), kept as it is.
std::string wrapLines(const std::string& text, std::size_t width);

// The first sentence of `text`'s first paragraph (up to its first ". ", the full stop kept).
std::string firstSentence(const std::string& text);

}  // namespace bimloc::cli
