#include "rondo/sim/rng.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <vector>

namespace rondo::sim {
namespace {

// Computed independently from the published xoshiro256** and splitmix64 definitions.
TEST(Rng, MatchesTheReferenceSequence) {
  Rng rng(42);
  EXPECT_EQ(rng.next(), 0x15780b2e0c2ec716ULL);
  EXPECT_EQ(rng.next(), 0x6104d9866d113a7eULL);
  EXPECT_EQ(rng.next(), 0xae17533239e499a1ULL);
  EXPECT_EQ(rng.next(), 0xecb8ad4703b360a1ULL);
  EXPECT_DOUBLE_EQ(rng.uniform(), 0.9918039142821028);
  Rng zero(0);
  EXPECT_EQ(zero.next(), 0x99ec5f36cb75f2b4ULL);
  EXPECT_EQ(zero.next(), 0xbf6e1f784956452aULL);
}

TEST(Rng, SameSeedSameNumbersDifferentSeedDifferent) {
  Rng a(7), b(7), c(8);
  int same_as_c = 0;
  for (int i = 0; i < 100; ++i) {
    const double x = a.normal();
    EXPECT_EQ(x, b.normal());
    if (x == c.normal()) ++same_as_c;
  }
  EXPECT_EQ(same_as_c, 0);
}

RC_GTEST_PROP(Rng, DrawsStayInTheirRanges, (std::uint64_t seed, std::uint64_t n)) {
  Rng rng(seed);
  for (int i = 0; i < 50; ++i) {
    const double u = rng.uniform();
    RC_ASSERT(u >= 0.0);
    RC_ASSERT(u < 1.0);
    const std::uint64_t k = rng.uniform_int(n);
    RC_ASSERT((n == 0 ? k == 0 : k < n));
    RC_ASSERT(rng.exponential(3.0) >= 0.0);
    RC_ASSERT(rng.lognormal(0.0, 1.0) > 0.0);
    RC_ASSERT(rng.pareto(1.5) >= 1.0);
    const double v = rng.uniform(2.0, 5.0);
    RC_ASSERT(v >= 2.0);
    RC_ASSERT(v < 5.0);
  }
  RC_ASSERT(!rng.bernoulli(0.0));
  RC_ASSERT(rng.bernoulli(1.0));
}

// Moments over many draws against the distributions' formulas (tolerances are > 6 standard errors).
TEST(Rng, DistributionsHaveTheirMoments) {
  Rng rng(3);
  const int n = 200'000;
  double sum_n = 0, sum_n2 = 0, sum_ln = 0, sum_exp = 0, hits = 0;
  std::vector<int> buckets(6, 0);
  for (int i = 0; i < n; ++i) {
    const double z = rng.normal();
    sum_n += z;
    sum_n2 += z * z;
    sum_ln += rng.lognormal(-0.125, 0.5);  // mean exp(-0.125 + 0.125) = 1
    sum_exp += rng.exponential(4.0);
    hits += rng.bernoulli(0.3) ? 1 : 0;
    ++buckets[rng.uniform_int(6)];
  }
  EXPECT_NEAR(sum_n / n, 0.0, 0.015);
  EXPECT_NEAR(sum_n2 / n, 1.0, 0.02);
  EXPECT_NEAR(sum_ln / n, 1.0, 0.01);
  EXPECT_NEAR(sum_exp / n, 4.0, 0.06);
  EXPECT_NEAR(hits / n, 0.3, 0.007);
  for (int b : buckets) EXPECT_NEAR(b, n / 6.0, 600);
}

TEST(Rng, ForksAreReproducibleAndDistinct) {
  Rng a(11), b(11);
  Rng fa = a.fork(1), fb = b.fork(1);
  Rng a2(11);
  Rng other = a2.fork(2);
  const std::uint64_t x = fa.next();
  EXPECT_EQ(x, fb.next());
  EXPECT_NE(x, other.next());
}

}  // namespace
}  // namespace rondo::sim
