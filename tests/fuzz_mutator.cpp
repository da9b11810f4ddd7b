#include "fuzz_mutator.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <vector>

namespace bimloc::test {

std::uint32_t fuzzSeed(std::uint32_t fixed, std::uint32_t offset) {
  const char* value = std::getenv("BIMLOC_FUZZ_SEED");
  return value ? static_cast<std::uint32_t>(std::strtoul(value, nullptr, 10)) + offset : fixed;
}

int fuzzCases(int count) {
  const char* value = std::getenv("BIMLOC_FUZZ_SCALE");
  return count * (value ? std::max(1, std::atoi(value)) : 1);
}
namespace {

struct Line {
  std::size_t begin, end;  // [begin, end) in the text, without the '\n'
};

std::vector<Line> splitLines(const std::string& text) {
  std::vector<Line> lines;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    lines.push_back({begin, end});
    begin = end + 1;
  }
  return lines;
}

// Positions [begin, end) of the '#N' references (after the '='), or of the numbers, of a line,
// outside quoted strings.
std::vector<std::pair<std::size_t, std::size_t>> tokens(const std::string& text, const Line& line, bool references) {
  std::vector<std::pair<std::size_t, std::size_t>> found;
  const std::size_t eq = text.find('=', line.begin);
  std::size_t i = references ? (eq < line.end ? eq + 1 : line.end) : line.begin;
  bool quoted = false;
  for (; i < line.end; ++i) {
    const char c = text[i];
    if (c == '\'' || c == '"') quoted = !quoted;  // STEP and YAML strings, JSON strings
    if (quoted) continue;
    const unsigned char previous = i > line.begin ? static_cast<unsigned char>(text[i - 1]) : ' ';
    const bool starts_number = std::isdigit(static_cast<unsigned char>(c)) && !std::isalnum(previous) && previous != '#';
    if (references ? c == '#' : starts_number) {
      std::size_t j = i + 1;
      const auto inNumber = [&](std::size_t k) {
        const char d = text[k];
        if (std::isdigit(static_cast<unsigned char>(d))) return true;
        if (references) return false;
        return d == '.' || d == 'E' || d == 'e' || ((d == '-' || d == '+') && (text[k - 1] == 'E' || text[k - 1] == 'e'));
      };
      while (j < line.end && inNumber(j)) ++j;
      if (j > i + (references ? 1 : 0)) found.emplace_back(i, j);
      i = j - 1;
    }
  }
  return found;
}

std::string badBytes(std::mt19937& rng) {
  static const char control[] = {'\x00', '\x01', '\x1b', '\x7f'};
  std::string bytes;
  const int n = 1 + static_cast<int>(rng() % 3);
  for (int k = 0; k < n; ++k)
    bytes += rng() % 4 == 0 ? control[rng() % 4] : static_cast<char>(0x80 + rng() % 0x80);
  return bytes;
}

}  // namespace

const char* damageName(Damage damage) {
  static const char* names[] = {"truncation", "line deletion", "duplication", "dangling reference",
                                "self reference", "wrong type", "non-finite number", "bad bytes"};
  return names[static_cast<int>(damage)];
}

Mutation Mutator::step(const std::string& text) {
  const std::vector<Line> all = splitLines(text);
  std::vector<Line> instances;
  for (const auto& l : all)
    if (l.end > l.begin + 1 && text[l.begin] == '#' && std::isdigit(static_cast<unsigned char>(text[l.begin + 1])))
      instances.push_back(l);
  Mutation m;
  m.damage = static_cast<Damage>(below(8));
  for (int attempt = 0; attempt < 50; ++attempt) {
    const Line& line = instances[below(instances.size())];
    const std::size_t line_index = static_cast<std::size_t>(std::lower_bound(all.begin(), all.end(), line, [](const Line& a, const Line& b) { return a.begin < b.begin; }) - all.begin());
    const std::string at = "line " + std::to_string(line_index + 1);
    const std::string id = text.substr(line.begin, text.find('=', line.begin) - line.begin);
    switch (m.damage) {
      case Damage::kTruncation: {
        const std::size_t cut = below(text.size());
        m.text = text.substr(0, cut), m.where = "at byte " + std::to_string(cut);
        return m;
      }
      case Damage::kLineDeletion:
        m.text = text.substr(0, line.begin) + text.substr(std::min(text.size(), line.end + 1)), m.where = at;
        return m;
      case Damage::kDuplication:
        m.text = text.substr(0, line.end + 1) + text.substr(line.begin, line.end - line.begin) + "\n" +
                 text.substr(std::min(text.size(), line.end + 1));
        m.where = at;
        return m;
      case Damage::kDanglingRef:
      case Damage::kSelfRef:
      case Damage::kWrongType: {
        const auto refs = tokens(text, line, true);
        if (refs.empty()) continue;
        const auto [b, e] = refs[below(refs.size())];
        std::string to = m.damage == Damage::kDanglingRef ? "#99999999" : id;
        if (m.damage == Damage::kWrongType) {
          const Line& other = instances[below(instances.size())];
          const auto type = [&](const Line& l) {
            const std::size_t eq = text.find('=', l.begin);
            return text.substr(eq + 1, text.find('(', eq) - eq - 1);
          };
          if (type(other) == type(line)) continue;
          to = text.substr(other.begin, text.find('=', other.begin) - other.begin);
        }
        while (!to.empty() && to.back() == ' ') to.pop_back();
        m.text = text.substr(0, b) + to + text.substr(e);
        m.where = at + ": " + text.substr(b, e - b) + " -> " + to;
        return m;
      }
      case Damage::kNonFinite: {
        const auto numbers = tokens(text, line, false);
        if (numbers.empty()) continue;
        const auto [b, e] = numbers[below(numbers.size())];
        static const char* values[] = {"NaN", "1.E999", "-1.E999", "INF"};
        const std::string to = values[below(4)];
        m.text = text.substr(0, b) + to + text.substr(e);
        m.where = at + ": " + text.substr(b, e - b) + " -> " + to;
        return m;
      }
      case Damage::kBadBytes: {
        const std::size_t pos = line.begin + below(line.end - line.begin + 1);
        m.text = text.substr(0, pos) + badBytes(rng_) + text.substr(pos);
        m.where = at + " at column " + std::to_string(pos - line.begin);
        return m;
      }
    }
  }
  m.damage = Damage::kTruncation;  // no line had what the damage needs: cut instead
  m.text = text.substr(0, text.size() / 2), m.where = "at the middle";
  return m;
}

Mutation Mutator::lines(const std::string& text, bool yaml, std::size_t max_line) {
  const std::vector<Line> all = splitLines(text);
  const std::size_t n = std::min(all.size(), max_line);
  static const Damage kinds[] = {Damage::kTruncation, Damage::kLineDeletion, Damage::kDuplication,
                                 Damage::kNonFinite,  Damage::kBadBytes,     Damage::kSelfRef,
                                 Damage::kWrongType};
  Mutation m;
  m.damage = kinds[below(yaml ? 7 : 5)];
  for (int attempt = 0; attempt < 50; ++attempt) {
    const std::size_t index = below(n);
    const Line& line = all[index];
    const std::string at = "line " + std::to_string(index + 1);
    const std::string before = text.substr(0, line.begin), after = text.substr(std::min(text.size(), line.end + 1));
    const std::string content = text.substr(line.begin, line.end - line.begin);
    switch (m.damage) {
      case Damage::kTruncation: {
        const std::size_t cut = below(text.size());
        m.text = text.substr(0, cut), m.where = "at byte " + std::to_string(cut);
        return m;
      }
      case Damage::kLineDeletion:
        m.text = before + after, m.where = at;
        return m;
      case Damage::kDuplication:
        m.text = before + content + "\n" + content + "\n" + after, m.where = at;
        return m;
      case Damage::kNonFinite: {
        const auto numbers = tokens(text, line, false);
        if (numbers.empty()) continue;
        const auto [b, e] = numbers[below(numbers.size())];
        static const char* values[] = {"nan", ".nan", "inf", "1e999", "-.inf"};
        const std::string to = values[below(5)];
        m.text = text.substr(0, b) + to + text.substr(e), m.where = at + ": " + text.substr(b, e - b) + " -> " + to;
        return m;
      }
      case Damage::kBadBytes: {
        const std::size_t pos = line.begin + below(line.end - line.begin + 1);
        m.text = text.substr(0, pos) + badBytes(rng_) + text.substr(pos), m.where = at;
        return m;
      }
      case Damage::kSelfRef:
      case Damage::kWrongType: {
        const std::size_t colon = content.find(": ");
        if (colon == std::string::npos) continue;
        static const char* others[] = {"{a: 1}", "[1, 2]", "'text'", "~", "-7"};
        const std::string to = m.damage == Damage::kSelfRef ? "&loop [*loop]" : others[below(5)];
        m.text = before + content.substr(0, colon + 2) + to + "\n" + after;
        m.where = at + ": " + content + " -> " + to;
        return m;
      }
      default:
        continue;
    }
  }
  m.damage = Damage::kTruncation;
  m.text = text.substr(0, text.size() / 2), m.where = "at the middle";
  return m;
}

}  // namespace bimloc::test
