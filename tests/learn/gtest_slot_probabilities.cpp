// EpisodeEdgeModel::slot_probabilities, the table LiveEdgeModels reads between updates, against
// the slow reference it replaces: first_attempt_probability and offline_probability at every slot
// of the week, exactly equal (the same sums in the same order), with and without the time-of-week
// term, in UTC and across a daylight-saving zone; and a live view answers exactly as the model
// does from the same statistics.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <random>

#include "rondo/learn/edge_models.h"
#include "rondo/learn/episode_model.h"
#include "series.h"

namespace rondo::learn {
namespace {

using testing::monday;

// An edge with a daily rhythm, a Wednesday closure and random failures: `days` of attempts.
std::vector<Attempt> rhythmic_edge(int days, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Attempt> out;
  for (int d = 0; d < days; ++d)
    for (int slot = 0; slot < 72; ++slot) {
      const Time start = monday() + hours(24 * d) + minutes(20 * slot) + seconds(static_cast<int>(u(rng) * 600));
      const double open =
          testing::wednesday_closure((start - monday()).count() / 1000 % (7 * 86400), 0.7 + 0.3 * (slot % 3) / 2.0);
      const bool ok = u(rng) < open;
      out.push_back({start, start + seconds(10), 10.0, ok});
      if (!ok) out.push_back({start + seconds(20), start + seconds(30), 10.0, u(rng) < 0.5});
    }
  return out;
}

RC_GTEST_PROP(SlotProbabilities, EqualTheSlowReferenceAtEverySlot, ()) {
  EpisodeOptions o;
  o.weekly = *rc::gen::element(WeeklyTerm::kOff, WeeklyTerm::kOn);
  if (*rc::gen::arbitrary<bool>()) o.zone = TimeZone::named("Europe/London").value();
  const int days = *rc::gen::inRange(1, 22);
  const auto fit = fit_episode_models({rhythmic_edge(days, *rc::gen::arbitrary<std::uint32_t>())}, o);
  const EpisodeEdgeModel& model = *fit.edges[0];
  const EpisodeStats& live = model.stats();
  const std::vector<double> q = model.slot_probabilities(live, true);
  const std::vector<double> offline = model.slot_probabilities(live, false);
  ASSERT_EQ(q.size(), static_cast<std::size_t>(kWeekSlots));
  // Every slot of a week (at a random second inside it), in a week well after the data.
  const Time week = monday() + hours(24 * 7 * 10) + hours(24 * 7 * *rc::gen::inRange(0, 30));
  const auto inside = seconds(*rc::gen::inRange(0, 900));
  for (int k = 0; k < kWeekSlots; ++k) {
    const Time t = week + minutes(15 * k) + inside;
    const auto w = static_cast<std::size_t>(model.priors()->week_slot(t));
    RC_ASSERT(q[w] == model.first_attempt_probability(t, live));
    RC_ASSERT(offline[w] == model.offline_probability(t, live));
  }
}

TEST(SlotProbabilities, ALiveViewAnswersAsTheModelDoes) {
  const std::vector<Traversal> log = [] {
    std::vector<Traversal> out;
    for (const Attempt& a : rhythmic_edge(14, 3))
      out.push_back({"A_B", "A", "B", a.start, a.end - a.start, a.success, ""});
    return out;
  }();
  const std::vector<EdgeSpec> edges = {{"A_B", 10}, {"B_A", 10}};
  auto models = *EdgeModels::fit(edges, log);
  LiveEdgeModels live(models);
  EpisodePredictor reference(std::shared_ptr<const EpisodeEdgeModel>(models, models->model(0)));
  Time t = monday() + hours(24 * 14 + 9);
  for (int k = 0; k < 20; ++k) {
    const Attempt a{t, t + seconds(10), 10.0, k % 4 != 0};
    live.observe(0, a);
    reference.observe(a);
    for (const Duration later : {seconds(5), Duration{minutes(3)}, Duration{hours(2)}, Duration{hours(30)}}) {
      EXPECT_EQ(live.success_probability(0, a.end + later), reference.probability(a.end + later));
      EXPECT_EQ(live.expected_seconds(0, a.end + later), reference.expected_seconds(a.end + later));
    }
    t += minutes(7);
  }
}

}  // namespace
}  // namespace rondo::learn
