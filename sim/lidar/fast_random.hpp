// A small, fast, seedable random source for the per-return noise of the lidar model: the
// standard library's normal distribution over mt19937_64 cost as much as a ray cast.
// xoshiro256+ (Blackman & Vigna) for uniforms, Box-Muller for normals (both values used).
#pragma once

#include <cmath>
#include <cstdint>

namespace bimloc::sim {

class FastRandom {
 public:
  explicit FastRandom(std::uint64_t seed) {
    for (auto& s : state_) s = splitmix(seed);  // the recommended way to fill xoshiro's state
  }

  // Uniform in [0, 1).
  double uniform() {
    const std::uint64_t result = state_[0] + state_[3];
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0], state_[3] ^= state_[1], state_[1] ^= state_[2], state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = (state_[3] << 45) | (state_[3] >> 19);
    return static_cast<double>(result >> 11) * 0x1.0p-53;
  }

  // Standard normal.
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - uniform();  // (0, 1]: log stays finite
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * M_PI * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * M_PI * u2);
  }

 private:
  static std::uint64_t splitmix(std::uint64_t& x) {
    std::uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  std::uint64_t state_[4];
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace bimloc::sim
