// A simulated building that replays real experience (docs/simulation.md, "Replay world"): an
// attempt at time t on an edge is answered by a logged attempt of the same edge near the same
// local time of week, e.g. from the Witham Wharf logs. To keep the logs' bursts of failures, all
// draws of one simulated day prefer one source week, chosen at random per day.
//
//   auto log = read_witham_logs("../shared/data/witham_wharf");
//   ReplayWorld world(map, *log, zone, ReplayOptions{.log_zone = *TimeZone::named("Europe/London")});
//   EdgeSample s = world.sample_edge(edge, t, rng);
//   const LoggedAttempt* a = world.draw(edge, t, rng);  // which logged attempt (null: no log)
//
// Search: attempts whose time of week lies within ±window of t's; if the day's week has some, one
// of them, else one of any week; with none at all the window doubles until it covers the week.
// Edges without any logged attempt use the prior, a ParametricWorld without effects.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "rondo/core/timezone.h"
#include "rondo/core/traversal.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/edge_world.h"
#include "rondo/sim/parametric_world.h"

namespace rondo::sim {

struct LoggedAttempt {
  Time start{};
  Duration duration{0};
  bool success = false;
  Duration time_of_week{0};  // local to the log's zone, in [0, 7 days)
  std::int64_t week = 0;     // weeks since the Monday 1970-01-05, local to the log's zone
};

struct ReplayOptions {
  Duration window = minutes(30);          // half-width of the first search window
  TimeZone log_zone = TimeZone::utc();    // where the logged robot lived (Europe/London for Witham)
  ParametricSpec prior{.failure_probability = 0.05};  // for edges without a log; no bursts
};

class ReplayWorld final : public EdgeWorld {
 public:
  // Log records are matched to map edges by edge id, else by (from, to) node names; records that
  // match no edge are counted in unmatched_records() and otherwise ignored.
  ReplayWorld(const map::TopoMap& map, const std::vector<Traversal>& log, TimeZone zone, ReplayOptions options);

  EdgeSample sample_edge(map::EdgeIndex edge, Time start, Rng& rng) override;
  // The logged attempt replayed for an attempt at `start`; null when the edge has no log.
  const LoggedAttempt* draw(map::EdgeIndex edge, Time start, Rng& rng);
  // The edge's logged attempts whose time of week is within ±half_width of `time_of_week`
  // (circularly over the week), in time-of-week order.
  std::vector<const LoggedAttempt*> near(map::EdgeIndex edge, Duration time_of_week, Duration half_width) const;
  // The source week chosen for the local date of `t` (drawn on first use).
  std::int64_t week_for_day(Time t, Rng& rng);

  const std::vector<LoggedAttempt>& attempts(map::EdgeIndex edge) const { return by_edge_.at(edge); }
  const std::vector<std::int64_t>& weeks() const { return weeks_; }
  std::size_t unmatched_records() const { return unmatched_; }

 private:
  TimeZone zone_;
  ReplayOptions options_;
  ParametricWorld prior_;
  std::vector<std::vector<LoggedAttempt>> by_edge_;  // per edge, sorted by time of week
  std::vector<std::int64_t> weeks_;                  // distinct source weeks, ascending
  std::map<std::int64_t, std::int64_t> week_of_day_; // simulated local day -> source week
  std::size_t unmatched_ = 0;
};

// Whole weeks since Monday 1970-01-05 of the local date of t.
std::int64_t week_number(const TimeZone& zone, Time t);

}  // namespace rondo::sim
