#include "step_references.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace bimloc::bim::detail {
namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
bool isLetter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
bool isWordChar(char c) { return isLetter(c) || isDigit(c) || c == '_' || c == '.' || c == '+' || c == '-'; }

// A bare argument that is no enumeration (.X.) and no typed value's name: it must be a finite
// number. 'NaN', 'inf' and '1.E999' are not (IFC++ would read them as such).
bool isFiniteNumber(const char* begin, const char* end) {
  if (begin < end && *begin == '+') ++begin;
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

// Text for a message: bytes outside printable ASCII as \xNN (a message must stay valid UTF-8).
std::string printable(const char* begin, const char* end) {
  std::string out;
  for (const char* c = begin; c < end; ++c) {
    const auto byte = static_cast<unsigned char>(*c);
    if (byte >= 0x20 && byte < 0x7f) {
      out += *c;
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", byte);
      out += hex;
    }
  }
  return out;
}

std::string trimmed(const char* begin, const char* end) {
  while (begin < end && isBlank(*begin)) ++begin;
  while (end > begin && isBlank(end[-1])) --end;
  return printable(begin, std::min(end, begin + 60)) + (end - begin > 60 ? "..." : "");
}

}  // namespace

StepScan scanStep(const std::string& text) {
  // The characters that change the scanner's state; everything else is skipped in a tight loop.
  static const std::array<unsigned char, 256> kind = [] {
    std::array<unsigned char, 256> k{};
    for (int c = 0; c < 256; ++c) k[c] = isWordChar(static_cast<char>(c)) ? 2 : c >= 0x80 ? 3 : 0;
    for (unsigned char c : std::string("'\"/;#\n")) k[c] = 1;
    return k;
  }();
  StepScan scan;
  const char* p = text.data();
  const char* const end = p + text.size();
  int line = 1;
  const auto skipQuoted = [&](char quote) {  // '' (or "") inside is an escaped quote
    for (++p; p < end; ++p) {
      if (*p == '\n') ++line;
      if (*p == quote) {
        if (p + 1 < end && p[1] == quote) ++p;
        else break;
      }
    }
    ++p;
  };
  StepInstance* current = nullptr;  // the instance whose arguments we are in
  bool in_data = false;
  const char* statement = p;  // where the current statement started
  int statement_line = 1;
  const auto close = [&] {
    if (!current) {
      const std::string s = trimmed(statement, p);
      if (s == "DATA") in_data = true;
      else if (s == "ENDSEC") in_data = false;
      else if (in_data && !s.empty()) {
        const char* first = statement;  // the statement's line is that of its first character
        while (first < p && isBlank(*first)) ++first;
        scan.malformed.push_back("line " + std::to_string(statement_line + std::count(statement, first, '\n')) + ": not an entity instance: '" +
                                 s + "'");
      }
    }
    current = nullptr;
  };
  while (p < end) {
    const unsigned char k = kind[static_cast<unsigned char>(*p)];
    if (k == 0) {
      ++p;
      continue;
    }
    const char c = *p;
    if (k == 2) {  // a word: an entity type, an enumeration, a typed value's name or a number
      const char* w = p;
      while (p < end && isWordChar(*p)) ++p;
      if (!current) continue;
      if (current->type.empty() && isLetter(*w)) {
        while (p < end && *p != '(' && !isBlank(*p) && *p != ';') ++p;  // bad bytes stay in the name
        current->type = printable(w, std::min(p, w + 60));
        continue;
      }
      if (p - w >= 2 && *w == '.' && p[-1] == '.') continue;  // .ENUM.
      const char* n = p;
      while (n < end && isBlank(*n)) ++n;
      if (n < end && *n == '(') continue;  // IFCLABEL('...')
      if (current->problem.empty() && !isFiniteNumber(w, p))
        current->problem = "holds '" + printable(w, std::min(p, w + 40)) + "', which is no finite number";
    } else if (k == 3) {  // STEP is 7-bit text: such a byte belongs in a string only
      if (current && current->problem.empty()) current->problem = "holds the byte " + printable(p, p + 1) + " outside a string";
      ++p;
    } else if (c == '\n') {
      ++line;
      ++p;
    } else if (c == '\'' || c == '"') {
      skipQuoted(c);
    } else if (c == '/') {
      if (p + 1 < end && p[1] == '*') {
        const char* q = std::search(p + 2, end, "*/", "*/" + 2);
        line += static_cast<int>(std::count(p, q, '\n'));
        p = q == end ? end : q + 2;
      } else {
        ++p;
      }
    } else if (c == ';') {
      close();
      statement = ++p;
      statement_line = line;
    } else {  // '#'
      const char* q = p + 1;
      if (q >= end || !isDigit(*q)) {
        ++p;
        continue;
      }
      long long id = 0;
      while (q < end && isDigit(*q)) {
        if (id < (1LL << 40)) id = 10 * id + (*q - '0');
        ++q;
      }
      // An instance: '#N =' first in its statement (after blanks and comments only).
      const char* s = statement;
      while (s < p) {
        if (isBlank(*s)) {
          ++s;
        } else if (s + 1 < p && s[0] == '/' && s[1] == '*') {
          const char* t = std::search(s + 2, p, "*/", "*/" + 2);
          s = t == p ? p + 1 : t + 2;  // an unclosed comment: not an instance
        } else {
          break;
        }
      }
      const char* e = q;
      while (e < end && isBlank(*e)) ++e;
      if (s == p && e < end && *e == '=' && id <= 0x7fffffff && !current) {
        StepInstance instance;
        instance.id = static_cast<int>(id);
        instance.line = line;
        scan.instances.push_back(std::move(instance));
        current = &scan.instances.back();
        p = e + 1;
      } else {
        if (current) current->refs.push_back(static_cast<int>(std::min<long long>(id, 0x7fffffff)));
        p = q;
      }
    }
  }
  close();
  std::stable_sort(scan.instances.begin(), scan.instances.end(),
                   [](const StepInstance& a, const StepInstance& b) { return a.id < b.id; });
  return scan;
}

std::vector<std::pair<int, int>> stepReferenceCounts(const std::string& text) {
  std::vector<std::pair<int, int>> counts;
  for (const auto& instance : scanStep(text).instances)
    if (!instance.refs.empty()) counts.emplace_back(instance.id, static_cast<int>(instance.refs.size()));
  return counts;
}

}  // namespace bimloc::bim::detail
