// A seeded mutator of input files for the fuzz test (issue 10, acceptance): each call makes one
// damage of the kinds a hostile or broken input has, and says what it did and where, so that a
// failing case can be reproduced from the seed and the description alone.
#pragma once

#include <cstdint>
#include <random>
#include <string>

namespace bimloc::test {

// Every fuzz test's seeds and case counts: fixed by default (CI runs the same cases every time);
// BIMLOC_FUZZ_SEED (a base, to which each draw adds its own `offset`) and BIMLOC_FUZZ_SCALE (a
// multiplier of the case counts) explore further by hand.
std::uint32_t fuzzSeed(std::uint32_t fixed, std::uint32_t offset);
int fuzzCases(int count);

enum class Damage {
  kTruncation,     // the text cut at a random byte
  kLineDeletion,   // one line removed
  kDuplication,    // one line repeated (in STEP: an id defined twice)
  kDanglingRef,    // a reference to something that does not exist
  kSelfRef,        // a reference to itself (STEP: the instance's own id; YAML: an alias cycle)
  kWrongType,      // a reference to an entity of another type (YAML: a value of another type)
  kNonFinite,      // a number replaced by NaN, infinity or an overflowing literal
  kBadBytes,       // bytes 0x80-0xFF or control characters inserted in a line
};
const char* damageName(Damage damage);

struct Mutation {
  std::string text;
  Damage damage = Damage::kTruncation;
  std::string where;  // "line 42: #47 -> #47", for the failure message
};

class Mutator {
 public:
  explicit Mutator(std::uint32_t seed) : rng_(seed) {}

  // One damage to the DATA section of a STEP (IFC) file.
  Mutation step(const std::string& text);
  // One damage to a line-based text (YAML, CSV, TUM, JSON, a PCD's header): the lines
  // [0, max_line) are candidates, truncation may cut anywhere.
  Mutation lines(const std::string& text, bool yaml, std::size_t max_line = 1000000);

  std::size_t below(std::size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }

 private:
  std::mt19937 rng_;
};

}  // namespace bimloc::test
