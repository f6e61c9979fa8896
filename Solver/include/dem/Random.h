// RockDEM engine: a small, portable, serialisable random number generator.
// xoshiro256** (Blackman & Vigna 2018) seeded through splitmix64. Unlike the <random>
// distributions, the numbers it gives are identical on every platform and standard
// library, and its whole state is four 64-bit words that a state file can keep.
#pragma once

#include <array>
#include <cstdint>

namespace dem {

class Random {
public:
  explicit Random(std::uint64_t seed = 1) { reseed(seed); }

  void reseed(std::uint64_t seed);

  /// Next raw 64-bit value.
  std::uint64_t next();
  /// Uniform double in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform double in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  const std::array<std::uint64_t, 4>& state() const { return s_; }
  void setState(const std::array<std::uint64_t, 4>& s) { s_ = s; }

  bool operator==(const Random& o) const { return s_ == o.s_; }

private:
  std::array<std::uint64_t, 4> s_{};
};

} // namespace dem
