#include "step_references.hpp"

#include <algorithm>
#include <array>

namespace bimloc::bim::detail {
namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

}  // namespace

std::vector<std::pair<int, int>> stepReferenceCounts(const std::string& text) {
  // The characters that change the scanner's state; everything else is skipped in a tight loop.
  static const std::array<bool, 256> special = [] {
    std::array<bool, 256> s{};
    for (unsigned char c : std::string("'/;#")) s[c] = true;
    return s;
  }();
  std::vector<std::pair<int, int>> counts;
  const char* p = text.data();
  const char* const end = p + text.size();
  const auto number = [&](const char*& q) {
    long long v = 0;
    while (q < end && isDigit(*q)) {
      if (v < (1LL << 40)) v = 10 * v + (*q - '0');
      ++q;
    }
    return v;
  };
  int current = -1, refs = 0;  // the instance whose arguments we are in (-1: none), its count
  const auto close = [&] {
    if (current >= 0 && refs > 0) counts.emplace_back(current, refs);
    current = -1, refs = 0;
  };
  const char* statement = p;  // where the current statement started
  while (p < end) {
    if (!special[static_cast<unsigned char>(*p)]) {
      ++p;
      continue;
    }
    const char c = *p;
    if (c == '\'') {  // a string: '' is an escaped quote
      for (++p; p < end; ++p)
        if (*p == '\'') {
          if (p + 1 < end && p[1] == '\'') ++p;
          else break;
        }
      ++p;
    } else if (c == '/') {
      if (p + 1 < end && p[1] == '*') {
        const char* q = std::search(p + 2, end, "*/", "*/" + 2);
        p = q == end ? end : q + 2;
      } else {
        ++p;
      }
    } else if (c == ';') {
      close();
      statement = ++p;
    } else {  // '#'
      const char* q = p + 1;
      if (q >= end || !isDigit(*q)) {
        ++p;
        continue;
      }
      const long long id = number(q);
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
      if (s == p && e < end && *e == '=' && id <= 0x7fffffff) {
        close();
        current = static_cast<int>(id);
        p = e + 1;
      } else {
        refs += current >= 0;
        p = q;
      }
    }
  }
  close();
  if (!std::is_sorted(counts.begin(), counts.end()))
    std::sort(counts.begin(), counts.end());
  return counts;
}

}  // namespace bimloc::bim::detail
