// The model's random stream: xoshiro256** seeded through splitmix64.
#include "dem/Random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>

TEST(Random, SeedingIsSplitmix64)
{
  // Reference: the first four outputs of splitmix64 (Steele, Lea & Flood 2014; Vigna's
  // public-domain splitmix64.c) started from state 0.
  const dem::Random r(0);
  const std::array<std::uint64_t, 4> expected{ { 0xe220a8397b1dcdafull, 0x6e789e6aa1b965f4ull,
                                                 0x06c45d188009454full, 0xf88bb8a8724c81ecull } };
  EXPECT_EQ(r.state(), expected);
}

TEST(Random, Xoshiro256StarStarReferenceSequence)
{
  // Reference: xoshiro256** (Blackman & Vigna 2018) from state {1, 2, 3, 4}. By hand:
  // output 1 = rotl(2 * 5, 7) * 9 = 1280 * 9 = 11520; the update then makes s1 = 2^2^2 = 0,
  // so output 2 = rotl(0, 7) * 9 = 0. Outputs 3 and 4 are the published test values.
  dem::Random r;
  r.setState({ { 1, 2, 3, 4 } });
  EXPECT_EQ(r.next(), 11520u);
  EXPECT_EQ(r.next(), 0u);
  EXPECT_EQ(r.next(), 1509978240u);
  EXPECT_EQ(r.next(), 1215971899390074240u);
}

TEST(Random, FirstOutputsForSeedOneAreStable)
{
  // Regression values, computed once with this implementation (seed 1).
  dem::Random r(1);
  EXPECT_EQ(r.next(), 0xb3f2af6d0fc710c5ull);
  EXPECT_EQ(r.next(), 0x853b559647364ceaull);
  EXPECT_EQ(r.next(), 0x92f89756082a4514ull);
  EXPECT_EQ(r.next(), 0x642e1c7bc266a3a7ull);
  dem::Random u(12345);
  EXPECT_EQ(u.uniform(), 0.74380816315658937);
  EXPECT_EQ(u.uniform(), 0.13004553462783452);
}

TEST(Random, SameSeedSameStreamDifferentSeedDifferentStream)
{
  dem::Random a(42), b(42), c(43);
  bool differs = false;
  for (int i = 0; i < 1000; ++i) {
    const std::uint64_t x = a.next();
    EXPECT_EQ(x, b.next());
    differs = differs || (x != c.next());
  }
  EXPECT_TRUE(differs);
}

TEST(Random, ReseedAndStateRoundTripContinueTheStream)
{
  dem::Random a(7);
  a.next();
  dem::Random b;
  b.setState(a.state());
  EXPECT_TRUE(a == b);
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(a.next(), b.next());
  }
  a.reseed(7);
  const dem::Random fresh(7);
  EXPECT_TRUE(a == fresh);
}

TEST(Random, UniformLiesInTheHalfOpenUnitInterval)
{
  // The largest 53-bit value maps below 1.
  EXPECT_LT(static_cast<double>(~0ull >> 11) * 0x1.0p-53, 1.0);
  dem::Random r(2024);
  const int n = 1000000;
  double sum = 0.0, sumSquares = 0.0, lowest = 1.0, highest = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sumSquares += u * u;
    lowest = std::min(lowest, u);
    highest = std::max(highest, u);
  }
  // Uniform on [0, 1): mean 1/2, variance 1/12; the standard error of the mean is
  // sqrt(1/12 / n) = 2.9e-4, so 2e-3 is about 7 standard errors.
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.5, 2e-3);
  EXPECT_NEAR(sumSquares / n - mean * mean, 1.0 / 12.0, 2e-3);
  EXPECT_LT(lowest, 1e-4);
  EXPECT_GT(highest, 1.0 - 1e-4);
}

TEST(Random, UniformInARange)
{
  dem::Random r(5);
  for (int i = 0; i < 10000; ++i) {
    const double x = r.uniform(-3.0, 2.0);
    ASSERT_GE(x, -3.0);
    ASSERT_LT(x, 2.0);
  }
}
