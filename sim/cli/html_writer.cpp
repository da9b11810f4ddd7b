#include "sim/cli/html_writer.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace bimloc::cli {
namespace {

// Tag and attribute names are the writer's callers' constants; one that is not a plain name
// is a bug, not input.
void checkName(const std::string& name) {
  const bool plain = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-';
  });
  if (!plain) throw std::logic_error("HtmlWriter: '" + name + "' is not a tag or attribute name");
}

}  // namespace

std::string escapeHtml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  return out;
}

std::string HtmlWriter::tag(const std::string& name, const Attributes& attributes) const {
  checkName(name);
  std::string out = "<" + name;
  for (const auto& [key, value] : attributes) {
    checkName(key);
    out += " " + key + "=\"" + escapeHtml(value) + "\"";
  }
  return out + ">";
}

HtmlWriter& HtmlWriter::open(const std::string& name, const Attributes& attributes) {
  out_ += tag(name, attributes);
  open_.push_back(name);
  return *this;
}

HtmlWriter& HtmlWriter::close() {
  if (open_.empty()) throw std::logic_error("HtmlWriter: close() with no element open");
  out_ += "</" + open_.back() + ">";
  // Block-level ends get a line break: the file stays readable in an editor.
  if (open_.back() != "a" && open_.back() != "span" && open_.back() != "b") out_ += "\n";
  open_.pop_back();
  return *this;
}

HtmlWriter& HtmlWriter::element(const std::string& name, const Attributes& attributes, std::string_view content) {
  return open(name, attributes).text(content).close();
}

HtmlWriter& HtmlWriter::empty(const std::string& name, const Attributes& attributes) {
  out_ += tag(name, attributes);
  return *this;
}

HtmlWriter& HtmlWriter::text(std::string_view content) {
  out_ += escapeHtml(content);
  return *this;
}

HtmlWriter& HtmlWriter::raw(std::string_view markup) {
  out_ += markup;
  return *this;
}

std::string HtmlWriter::document() const {
  if (!open_.empty()) throw std::logic_error("HtmlWriter: <" + open_.back() + "> is still open");
  return "<!DOCTYPE html>\n" + out_;
}

}  // namespace bimloc::cli
