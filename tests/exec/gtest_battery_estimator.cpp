// The battery estimator (rondo/exec/battery_estimator.h): it recovers a simulated battery's true
// rates, its uncertainty shrinks with data, its predictions are non-negative and monotone, its
// estimate does not depend on the order of the intervals, and it agrees with batch least squares.
#include "rondo/exec/battery_estimator.h"

#include "battery_memory.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <string>
#include <cmath>
#include <vector>

#include "rondo/sim/battery_model.h"
#include "rondo/sim/rng.h"

namespace rondo::exec {
namespace {

struct Interval {
  double from = 0;
  double to = 0;
  BatteryUse use;
};

// A day of a simulated robot's life as intervals between readings: edges (metres at varying
// speeds, some failed), actions, idle waits and charges, each cut at a reading as the executor
// does, levels from sim::BatteryModel itself (per metre at the edge's end), read to `resolution`.
std::vector<Interval> simulated(const sim::BatteryModel& truth, int count, std::uint64_t seed, double resolution = 0) {
  sim::Rng rng(seed);
  std::vector<Interval> out;
  double level = 0.7;
  const auto read = [&](double v) { return resolution > 0 ? std::round(v / resolution) * resolution : v; };
  // Hours, at the clock's resolution: the simulated battery and the features see the same span.
  const auto span = [&](double low, double high, Duration& d) {
    d = from_seconds(rng.uniform(low, high) * 3600);
    return to_seconds(d) / 3600;
  };
  Duration d{0};
  for (int i = 0; i < count; ++i) {
    Interval iv{.from = read(level), .to = 0, .use = {}};
    const double kind = rng.uniform();
    if (level < 0.3 || kind < 0.15) {  // a charge
      const double h = span(0.1, 1.0, d);
      level = truth.after(level, sim::BatteryModel::Mode::kCharging, d);
      iv.use.hours_charging = h;
    } else if (kind < 0.65) {  // an edge: 5-40 m at 0.2-0.6 m/s; one in ten fails (time, no metres)
      const double m = rng.uniform(5, 40);
      d = from_seconds(m / rng.uniform(0.2, 0.6));
      const double h = to_seconds(d) / 3600;
      level = truth.after(level, sim::BatteryModel::Mode::kMoving, d);
      iv.use.hours_moving = h;
      if (rng.uniform() > 0.1) {
        level = truth.after_distance(level, m);
        iv.use.metres = m;
      }
    } else if (kind < 0.85) {
      const double h = span(0.01, 0.3, d);
      level = truth.after(level, sim::BatteryModel::Mode::kActing, d);
      iv.use.hours_acting = h;
    } else {
      const double h = span(0.05, 2.0, d);
      level = truth.after(level, sim::BatteryModel::Mode::kIdle, d);
      iv.use.hours_idle = h;
    }
    iv.to = read(level);
    out.push_back(iv);
  }
  return out;
}

const sim::BatteryModel kTruth{.initial = 1.0, .moving_per_hour = 0.3, .acting_per_hour = 0.15, .idle_per_hour = 0.02,
                               .charging_per_hour = 0.4, .per_metre = 0.0004};

TEST(BatteryEstimator, RecoversTheTrueRatesOfASimulatedBattery) {
  BatteryEstimator e;
  for (const Interval& iv : simulated(kTruth, 600, 11, /*resolution=*/0.001)) e.observe(iv.from, iv.to, iv.use);
  const BatteryRates r = e.rates();
  EXPECT_NEAR(r.per_metre, 0.0004, 0.00004);
  EXPECT_NEAR(r.moving_per_hour, 0.3, 0.05);
  EXPECT_NEAR(r.acting_per_hour, 0.15, 0.01);
  EXPECT_NEAR(r.idle_per_hour, 0.02, 0.005);
  EXPECT_NEAR(r.charging_per_hour, 0.4, 0.01);
  // The standard errors say how far off the estimates may be: each rate is within 4 of them.
  const BatteryRates se = e.standard_errors();
  EXPECT_LT(std::abs(r.per_metre - 0.0004), 4 * se.per_metre);
  EXPECT_LT(std::abs(r.moving_per_hour - 0.3), 4 * se.moving_per_hour);
  EXPECT_LT(std::abs(r.charging_per_hour - 0.4), 4 * se.charging_per_hour);
  // A plan of 500 m in 30 min of driving and 20 min of acting.
  const BatteryUse plan{.metres = 500, .hours_moving = 0.5, .hours_acting = 1.0 / 3};
  const double truth = 0.0004 * 500 + 0.3 * 0.5 + 0.15 / 3;
  EXPECT_NEAR(e.predict(plan).mean, truth, 0.01);
  EXPECT_NEAR(e.hours_to_charge(0.2, 0.6), 1.0, 0.05);
}

TEST(BatteryEstimator, ReadingsAtAClampAreNotLearnedFrom) {
  BatteryEstimator e;
  EXPECT_FALSE(e.observe(0.9, 1.0, {.hours_charging = 2}));  // full: the charge stopped before the end
  EXPECT_FALSE(e.observe(0.05, 0.0, {.hours_moving = 1}));   // empty
  EXPECT_FALSE(e.observe(0.5, 0.5, {}));                     // nothing happened
  EXPECT_TRUE(e.observe(0.5, 0.45, {.metres = 20, .hours_moving = 0.1}));
  EXPECT_EQ(e.observations(), 1u);
}

TEST(BatteryEstimator, TheUncertaintyShrinksWithData) {
  const std::vector<Interval> data = simulated(kTruth, 800, 5, 0.001);
  const BatteryUse plan{.metres = 800, .hours_moving = 1, .hours_acting = 2, .hours_idle = 3};
  BatteryEstimator e;
  double before = e.predict(plan).standard_error;
  for (std::size_t n : {10u, 50u, 200u, 800u}) {
    BatteryEstimator fresh;
    for (std::size_t i = 0; i < n; ++i) fresh.observe(data[i].from, data[i].to, data[i].use);
    const double now = fresh.predict(plan).standard_error;
    EXPECT_LT(now, before) << n << " intervals";
    before = now;
  }
  EXPECT_LT(before, 0.01);
}

// The obvious reference: the prior as pseudo-observations and every interval as a row, the
// normal equations built from the whole design matrix and solved by Gauss-Jordan elimination.
std::vector<double> batch_least_squares(const BatteryPrior& prior, const std::vector<Interval>& data) {
  std::vector<std::vector<double>> rows;
  std::vector<double> ys;
  const double mean[] = {prior.mean.per_metre, prior.mean.moving_per_hour, prior.mean.acting_per_hour,
                         prior.mean.idle_per_hour, prior.mean.charging_per_hour};
  const double sd[] = {prior.sd.per_metre, prior.sd.moving_per_hour, prior.sd.acting_per_hour, prior.sd.idle_per_hour,
                       prior.sd.charging_per_hour};
  for (std::size_t i = 0; i < 5; ++i) {
    std::vector<double> row(5, 0.0);
    row[i] = prior.noise_sd / sd[i];
    rows.push_back(row);
    ys.push_back(row[i] * mean[i]);
  }
  for (const Interval& iv : data) {
    rows.push_back({iv.use.metres, iv.use.hours_moving, iv.use.hours_acting, iv.use.hours_idle, -iv.use.hours_charging});
    ys.push_back(iv.from - iv.to);
  }
  std::vector<std::vector<double>> m(5, std::vector<double>(6, 0.0));
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t i = 0; i < 5; ++i) {
      for (std::size_t j = 0; j < 5; ++j) m[i][j] += rows[r][i] * rows[r][j];
      m[i][5] += rows[r][i] * ys[r];
    }
  for (std::size_t c = 0; c < 5; ++c) {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < 5; ++r)
      if (std::abs(m[r][c]) > std::abs(m[p][c])) p = r;
    std::swap(m[c], m[p]);
    for (std::size_t r = 0; r < 5; ++r) {
      if (r == c) continue;
      const double f = m[r][c] / m[c][c];
      for (std::size_t k = c; k < 6; ++k) m[r][k] -= f * m[c][k];
    }
  }
  std::vector<double> theta(5);
  for (std::size_t i = 0; i < 5; ++i) theta[i] = m[i][5] / m[i][i];
  return theta;
}

std::vector<double> as_list(const BatteryRates& r) {
  return {r.per_metre, r.moving_per_hour, r.acting_per_hour, r.idle_per_hour, r.charging_per_hour};
}

TEST(BatteryEstimator, AgreesWithBatchLeastSquaresOnSmallInputs) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<Interval> data = simulated(kTruth, 3 + static_cast<int>(seed % 12), seed, 0.01);
    BatteryEstimator e;
    std::vector<Interval> learned;
    for (const Interval& iv : data)
      if (e.observe(iv.from, iv.to, iv.use)) learned.push_back(iv);
    const std::vector<double> want = batch_least_squares(BatteryPrior{}, learned);
    const std::vector<double> got = as_list(e.rates());
    for (std::size_t i = 0; i < 5; ++i)
      EXPECT_NEAR(got[i], std::max(want[i], 0.0), 1e-9 + 1e-7 * std::abs(want[i])) << "seed " << seed << " rate " << i;
  }
}

BatteryUse any_use() {
  return {.metres = *rc::gen::inRange(0, 500) * 1.0,
          .hours_moving = *rc::gen::inRange(0, 100) / 100.0,
          .hours_acting = *rc::gen::inRange(0, 100) / 100.0,
          .hours_idle = *rc::gen::inRange(0, 100) / 100.0,
          .hours_charging = 0};
}

RC_GTEST_PROP(BatteryEstimatorProperty, PredictionsAreNonNegativeAndMonotoneInDistanceAndTime, ()) {
  // Any readings at all, even ones no battery would give: the estimate is what it is, and still
  // a plan never charges the battery, and more of a plan never costs less.
  BatteryEstimator e;
  const int n = *rc::gen::inRange(0, 40);
  for (int i = 0; i < n; ++i) {
    BatteryUse u = any_use();
    u.hours_charging = *rc::gen::inRange(0, 3) == 0 ? *rc::gen::inRange(1, 100) / 100.0 : 0.0;
    e.observe(*rc::gen::inRange(1, 100) / 100.0, *rc::gen::inRange(1, 99) / 100.0, u);
  }
  const BatteryUse plan = any_use();
  const BatteryPrediction p = e.predict(plan);
  RC_ASSERT(p.mean >= 0);
  RC_ASSERT(p.standard_error >= 0);
  BatteryUse more = plan;
  more.metres += *rc::gen::inRange(0, 300);
  more.hours_moving += *rc::gen::inRange(0, 50) / 100.0;
  more.hours_acting += *rc::gen::inRange(0, 50) / 100.0;
  more.hours_idle += *rc::gen::inRange(0, 50) / 100.0;
  RC_ASSERT(e.predict(more).mean >= p.mean);
}

RC_GTEST_PROP(BatteryEstimatorProperty, TheEstimateDoesNotDependOnTheOrderOfTheReadings, ()) {
  const auto seed = *rc::gen::inRange<std::uint64_t>(1, 1'000'000);
  std::vector<Interval> data = simulated(kTruth, *rc::gen::inRange(1, 60), seed, 0.001);
  BatteryEstimator forward;
  for (const Interval& iv : data) forward.observe(iv.from, iv.to, iv.use);
  sim::Rng rng(seed + 1);
  for (std::size_t i = data.size(); i > 1; --i) std::swap(data[i - 1], data[rng.uniform_int(i)]);
  BatteryEstimator shuffled;
  for (const Interval& iv : data) shuffled.observe(iv.from, iv.to, iv.use);
  const std::vector<double> a = as_list(forward.rates()), b = as_list(shuffled.rates());
  for (std::size_t i = 0; i < 5; ++i) RC_ASSERT(std::abs(a[i] - b[i]) <= 1e-9 + 1e-9 * std::abs(a[i]));
  RC_ASSERT(std::abs(forward.noise_sd() - shuffled.noise_sd()) <= 1e-9);
}

// What it learned, stored as text and read back into a fresh estimator (a restart): the same
// rates, standard errors and predictions, to the bit.
TEST(BatteryEstimator, ItsStateStoredAsTextGoesOnExactlyWhereItWas) {
  BatteryEstimator learned;
  for (const Interval& iv : simulated(kTruth, 200, 7, /*resolution=*/0.001)) learned.observe(iv.from, iv.to, iv.use);
  const std::string text = encode_battery_state(learned.state());
  const Result<BatteryEstimator::State> state = decode_battery_state(text);
  ASSERT_TRUE(state.ok()) << state.error().message;
  BatteryEstimator again;
  ASSERT_TRUE(again.restore(*state));
  EXPECT_EQ(again.observations(), learned.observations());
  const BatteryUse plan{.metres = 500, .hours_moving = 0.5, .hours_acting = 1.0 / 3, .hours_idle = 2};
  EXPECT_EQ(again.predict(plan).mean, learned.predict(plan).mean);
  EXPECT_EQ(again.predict(plan).standard_error, learned.predict(plan).standard_error);
  EXPECT_EQ(again.rates().charging_per_hour, learned.rates().charging_per_hour);
  EXPECT_EQ(again.noise_sd(), learned.noise_sd());
  // ... and both learn on alike.
  for (const Interval& iv : simulated(kTruth, 50, 8, 0.001)) {
    learned.observe(iv.from, iv.to, iv.use);
    again.observe(iv.from, iv.to, iv.use);
  }
  EXPECT_EQ(again.predict(plan).mean, learned.predict(plan).mean);
}

// A stored value that is not one: an error that says what is wrong, or (numbers that cannot be an
// estimate) refused by restore(), which leaves the estimator as it was.
TEST(BatteryEstimator, AStoredStateThatIsNotOneIsRefusedSayingWhy) {
  BatteryEstimator learned;
  for (const Interval& iv : simulated(kTruth, 20, 3)) learned.observe(iv.from, iv.to, iv.use);
  const std::string good = encode_battery_state(learned.state());
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{not json", "the battery estimate"},
      {"[1, 2]", "must be an object"},
      {with("\"version\":1", "\"version\":2"), "version 2 is not one this rondo reads (1)"},
      {with("\"b\":[", "\"b\":[1,"), "b: must hold 5 numbers, not 6"},
      {with("\"n\":", "\"count\":"), "count"},
      {with("\"yy\":", "\"yy\":\"x\",\"zz\":"), "zz"},
      {"", "the battery estimate"},
  };
  for (const auto& [text, says] : cases) {
    const Result<BatteryEstimator::State> s = decode_battery_state(text);
    ASSERT_FALSE(s.ok()) << text;
    EXPECT_NE(s.error().message.find(says), std::string::npos) << text << " -> " << s.error().message;
  }
  BatteryEstimator::State bad = learned.state();
  bad.a[0][0] = -1;
  BatteryEstimator fresh;
  const BatteryUse plan{.metres = 100, .hours_moving = 0.1};
  const double before = fresh.predict(plan).mean;
  EXPECT_FALSE(fresh.restore(bad));
  bad = learned.state();
  bad.a[1][2] += 1e-3;  // not symmetric
  EXPECT_FALSE(fresh.restore(bad));
  bad = learned.state();
  bad.yy = std::nan("");
  EXPECT_FALSE(fresh.restore(bad));
  EXPECT_EQ(fresh.predict(plan).mean, before);
  EXPECT_EQ(fresh.observations(), 0u);
}

}  // namespace
}  // namespace rondo::exec
