// RockDEM engine: xoshiro256** (Blackman & Vigna 2018, "Scrambled linear pseudorandom
// number generators"), seeded through splitmix64 (Steele, Lea & Flood 2014). Both are
// public-domain algorithms; this is our own transcription of them.
#include "dem/Random.h"

namespace dem {

namespace {

std::uint64_t rotateLeft(std::uint64_t x, int k)
{
  return (x << k) | (x >> (64 - k));
}

/// One step of splitmix64: advances `state` and returns the next output.
std::uint64_t splitmix64(std::uint64_t& state)
{
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

} // namespace

void Random::reseed(std::uint64_t seed)
{
  // splitmix64 never yields four zero words in a row, so the xoshiro state is never
  // the all-zero state (the one state xoshiro cannot leave).
  std::uint64_t sm = seed;
  for (auto& word : s_) {
    word = splitmix64(sm);
  }
}

std::uint64_t Random::next()
{
  const std::uint64_t result = rotateLeft(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotateLeft(s_[3], 45);
  return result;
}

} // namespace dem
