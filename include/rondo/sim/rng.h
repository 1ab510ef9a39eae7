// The simulator's random numbers: a small, portable generator (xoshiro256**, seeded through
// splitmix64) with its own distributions, so that a seed gives the same simulated weeks on every
// machine and standard library. std:: distributions are not used: their output is
// implementation-defined.
//
//   Rng rng(42);
//   double u = rng.uniform();                  // [0, 1)
//   bool fails = rng.bernoulli(0.05);
//   double factor = rng.lognormal(0.0, 0.25);  // median 1, long right tail
//   Duration gap = from_seconds(rng.exponential(600.0));
//
// Contract: the sequence depends only on the seed and the calls made. The integer stream and
// uniform() are bit-exact everywhere; normal(), lognormal() and exponential() use std::log, sqrt
// and exp, which IEEE 754 platforms with a glibc-grade libm agree on (a libm that rounds its log
// differently could change the last bit of a draw).
#pragma once

#include <array>
#include <cstdint>

namespace rondo::sim {

class Rng {
 public:
  explicit Rng(std::uint64_t seed);

  // The next 64 raw bits.
  std::uint64_t next();
  // Uniform in [0, 1), with 53 random bits.
  double uniform();
  // Uniform in [low, high).
  double uniform(double low, double high);
  // Uniform integer in [0, n); 0 when n is 0. Unbiased (rejection sampling).
  std::uint64_t uniform_int(std::uint64_t n);
  // True with probability p (p <= 0 never, p >= 1 always).
  bool bernoulli(double p);
  // Standard normal (Marsaglia's polar method), and with a mean and standard deviation.
  double normal();
  double normal(double mean, double stddev);
  // exp(normal(mu, sigma)): median exp(mu), mean exp(mu + sigma^2 / 2).
  double lognormal(double mu, double sigma);
  // Exponential with the given mean (> 0); 0 when mean <= 0.
  double exponential(double mean);
  // Pareto with minimum 1 and tail index alpha (> 0): P(X > x) = x^-alpha. Heavy tailed.
  double pareto(double alpha);

  // An independent generator for a sub-stream (e.g. one per simulated robot), derived from this
  // generator's next output and `stream`; advances this generator by one step.
  Rng fork(std::uint64_t stream);

 private:
  std::array<std::uint64_t, 4> s_{};
};

// splitmix64: one step of the seeding generator, also a good 64-bit mixing function.
std::uint64_t splitmix64(std::uint64_t& state);

}  // namespace rondo::sim
