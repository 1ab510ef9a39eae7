// When doors are open, learned by time of day (and week, when the data say so) from the robot's
// own door observations, with the learning module's binary model (learn::EpisodeBinaryModel, one
// series per door). The executor refits them at the nightly refit and uses them to place the
// retry of a task waiting for its door (docs/executor.md, "Opportunities").
//
//   DoorModels doors(zone);
//   doors.observe("A-120-door", t, /*open=*/false);
//   doors.refit(now, hours(24 * 14));
//   std::optional<double> p = doors.probability("A-120-door", t);   // nothing before the first fit
//   std::optional<Time> at = doors.next_likely_open("A-120-door", now, latest, 0.5);
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/core/timezone.h"
#include "rondo/learn/episode_model.h"

namespace rondo::exec {

class DoorModels {
 public:
  // Observations closer than this to the previous one of the same door count once (the sensor
  // reports a door after every edge attempt near it).
  static constexpr Duration kSameLook = seconds(60);
  static constexpr Duration kStep = minutes(15);  // next_likely_open looks at this grid

  explicit DoorModels(const TimeZone& zone) : zone_(zone) {}

  void observe(const std::string& door, Time when, bool open);
  // A failed attempt at an edge through `door` is weak evidence that the door is shut: it counts
  // for kFailedEdgeWeight of a look, as one "closed" sample for every 1 / kFailedEdgeWeight such
  // failures of the door (the credit is kept per door), and not at all within kSameLook of the
  // door's last sample (a look at the door, which says more, or the last failure's). True when it
  // added a sample. The weight is the share of failed door edges that met a shut door in the
  // simulated buildings (docs/executor.md, "A failed door edge"; bench/door_evidence_bench.cpp).
  static constexpr double kFailedEdgeWeight = 0.5;
  bool observe_failed_edge(const std::string& door, Time when);
  // Fits every door's model on its observations since `now - window` (all of them when none);
  // older observations are forgotten.
  void refit(Time now, std::optional<Duration> window);
  // The learned probability that `door` is open at `t`; nothing when it has no fitted model.
  std::optional<double> probability(const std::string& door, Time t) const;
  // The first time on the 15-minute grid in (from, until] at which `door` is open with at least
  // `threshold`; nothing when there is none or no model.
  std::optional<Time> next_likely_open(const std::string& door, Time from, Time until, double threshold) const;
  std::size_t samples(const std::string& door) const;
  std::vector<std::string> doors() const;  // with a fitted model, in name order

 private:
  TimeZone zone_;
  std::map<std::string, std::vector<learn::BinarySample>> samples_;
  std::map<std::string, double> failed_edge_credit_;
  std::map<std::string, std::shared_ptr<const learn::EpisodeBinaryModel>> models_;
};

}  // namespace rondo::exec
