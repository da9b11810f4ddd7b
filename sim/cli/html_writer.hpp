// A small HTML writer for the pages the bench writes (bimloc compare's index.html): elements
// opened and closed in order, every text and attribute value escaped, so a plan or room name
// can never become markup. Only our own constant CSS and script go in unescaped (raw).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace bimloc::cli {

// & < > " ' as character references: safe in text and in quoted attribute values.
std::string escapeHtml(std::string_view text);

class HtmlWriter {
 public:
  using Attributes = std::vector<std::pair<std::string, std::string>>;

  // <tag a="v" ...>: names are ours (letters, digits, '-'), values are escaped.
  HtmlWriter& open(const std::string& tag, const Attributes& attributes = {});
  // </tag> of the innermost open element.
  HtmlWriter& close();
  // <tag ...>text</tag>.
  HtmlWriter& element(const std::string& tag, const Attributes& attributes, std::string_view text);
  // An element without content or end tag (img, meta).
  HtmlWriter& empty(const std::string& tag, const Attributes& attributes = {});
  HtmlWriter& text(std::string_view text);
  // Our own constant markup (the style sheet, the script): written as is.
  HtmlWriter& raw(std::string_view markup);

  // The document, "<!DOCTYPE html>" first; throws std::logic_error while an element is open.
  std::string document() const;

 private:
  std::string tag(const std::string& name, const Attributes& attributes) const;

  std::string out_;
  std::vector<std::string> open_;
};

}  // namespace bimloc::cli
