// Loading and unloading times, learned per action and place (the person who works there) from the
// executor's own experience, with the learning module's online duration model
// (learn::OnlineStaticDuration), as travel times are learned per edge. The person's confirmation
// ends the action, so its duration is how long that person takes.
//
//   LoadingTimes times;
//   times.observe("load", "A-110-Desk", minutes(1), seconds(95), /*success=*/true, now);
//   Duration d = times.expected("load", "A-110-Desk", minutes(1));   // between 1 min and 95 s
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/exec/executor_types.h"
#include "rondo/learn/quantile_table.h"
#include "rondo/learn/static_model.h"

namespace rondo::exec {

class LoadingTimes {
 public:
  static constexpr double kPriorCount = 2;  // the declared duration counts as this many samples

  explicit LoadingTimes(std::vector<std::string> actions = {"load", "unload"}) : actions_(std::move(actions)) {}
  bool learns(const std::string& action) const;
  const std::vector<std::string>& actions() const { return actions_; }
  // One run of `action` at `place` that took `took`; `declared` is what the task said it would
  // take (the prior, the first time this action is seen at this place).
  void observe(const std::string& action, const std::string& place, Duration declared, Duration took, bool success,
               Time at);
  // A run the action monitor stopped after `took`: the person had not finished (a lower bound of
  // their time, learned as learn::OnlineStaticDuration::observe_stopped: it raises the estimate).
  void observe_stopped(const std::string& action, const std::string& place, Duration declared, Duration took, Time at);
  // The expected duration of `action` at `place`; `declared` when nothing is known there.
  Duration expected(const std::string& action, const std::string& place, Duration declared) const;
  // How long `action` at `place` takes at its q-quantile: the expected time there times the
  // q-quantile of how much longer than expected people took, pooled over every action and place
  // (each person has a time of their own, but how far they stray from it is alike, and one
  // person's few runs would not show it). Nothing until kRatioSamples runs are known.
  static constexpr std::size_t kRatioSamples = 10;
  std::optional<Duration> quantile(const std::string& action, const std::string& place, Duration declared,
                                   double q) const;

  std::vector<LearnedActionTime> entries() const;  // by action, then place

 private:
  learn::OnlineStaticDuration& model(const std::string& action, const std::string& place, Duration declared);

  void add_ratio(double ratio);

  std::vector<std::string> actions_;
  std::map<std::pair<std::string, std::string>, learn::OnlineStaticDuration> models_;
  static constexpr std::size_t kRatioWindow = 500;
  std::vector<double> ratios_;  // took / expected before the run, a ring of the last kRatioWindow
  std::size_t ratios_seen_ = 0;
  learn::QuantileTable ratio_quantiles_;
};

}  // namespace rondo::exec
