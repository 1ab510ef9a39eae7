#include "rondo/sim/action_model.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

namespace rondo::sim {
namespace {

TEST(ActionModel, MeanDurationIsTheExpectedOneAndRatesHold) {
  const ActionModel model({.sigma = 0.3, .failure_probability = 0.1, .overrun_probability = 0.0}, {});
  Rng rng(5);
  const int n = 50'000;
  double sum = 0;
  int failures = 0;
  for (int i = 0; i < n; ++i) {
    const ActionSample s = model.sample(Action{"anything", {}}, minutes(10), rng);
    if (s.success) {
      sum += to_seconds(s.duration);
    } else {
      ++failures;
    }
  }
  EXPECT_NEAR(sum / (n - failures), 600.0, 6.0);
  EXPECT_NEAR(static_cast<double>(failures) / n, 0.1, 0.01);
}

TEST(ActionModel, OverrunsMultiplyTheDuration) {
  const ActionModel model({.sigma = 0.0, .failure_probability = 0.0, .overrun_probability = 0.25, .overrun_factor = 3.0},
                          {});
  Rng rng(6);
  int overruns = 0;
  for (int i = 0; i < 4000; ++i) {
    const Duration d = model.sample(Action{"x", {}}, minutes(1), rng).duration;
    EXPECT_TRUE(d == minutes(1) || d == minutes(3)) << format_duration(d);
    overruns += d == minutes(3) ? 1 : 0;
  }
  EXPECT_NEAR(overruns / 4000.0, 0.25, 0.03);
}

TEST(ActionModel, NamedProfilesOverrideTheFallback) {
  const ActionModel model({.failure_probability = 0.0}, {{"talk", {.sigma = 0.0, .non_interruptible = minutes(2)}}});
  Rng rng(1);
  EXPECT_EQ(model.sample(Action{"talk", {}}, minutes(5), rng).non_interruptible, minutes(2));
  EXPECT_EQ(model.sample(Action{"look", {}}, minutes(5), rng).non_interruptible, Duration{0});
}

RC_GTEST_PROP(ActionModel, NonInterruptibleSpanNeverOutlastsTheAction,
              (std::uint64_t seed, std::uint32_t expected_s, std::uint32_t span_s)) {
  const ActionModel model({.sigma = 1.0, .failure_probability = 0.3, .non_interruptible = seconds(span_s % 3600)}, {});
  Rng rng(seed);
  const ActionSample s = model.sample(Action{"a", {}}, seconds(expected_s % 7200), rng);
  RC_ASSERT(s.duration >= Duration{0});
  RC_ASSERT(s.non_interruptible >= Duration{0});
  RC_ASSERT(s.non_interruptible <= s.duration);
  if (expected_s % 7200 == 0) RC_ASSERT(s.duration == Duration{0});
}

}  // namespace
}  // namespace rondo::sim
