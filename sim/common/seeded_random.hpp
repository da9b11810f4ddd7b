// Reproducible randomness for the bench: the same seed gives the same run on every machine
// (std::uniform_real_distribution is not specified bit for bit, so we map the bits ourselves),
// and each use draws from its own stream so adding draws in one place does not shift another.
#pragma once

#include <cstdint>
#include <random>

namespace bimloc::sim {

enum class RandomStream : std::uint64_t { Gait = 1, Walk = 2, Start = 3, SiteWalls = 4, SiteDoors = 5, SitePartitions = 6, SiteClutter = 7, SitePeople = 8, SiteSensor = 9 };

class SeededRandom {
 public:
  SeededRandom(std::uint64_t seed, RandomStream stream) : engine_(mix(seed ^ mix(static_cast<std::uint64_t>(stream)))) {}
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  static std::uint64_t mix(std::uint64_t z) {  // SplitMix64's finaliser
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::mt19937_64 engine_;
};

}  // namespace bimloc::sim
