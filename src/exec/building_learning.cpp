// What the building learns, and learns again every night: the robots' speeds and the edge models
// (in the fleet's standard time) from the traversal log of the last `refit_window` (with the week from the weekly
// memory, building_weekly.cpp, and the attempt laws under a risk bound), the door models from the door observations,
// and (restored after a restart) the loading times.
#include <fmt/format.h>

#include "attempt_laws.h"
#include "door_models.h"
#include "loading_times.h"
#include "rondo/exec/building.h"
#include "rondo/learn/edge_models.h"
#include "rondo/store/observations.h"
#include "rondo/store/traversal_log.h"

namespace rondo::exec {

Status Building::restore_learning() {
  RONDO_RETURN_IF_ERROR(restore_loading_times());
  return restore_door_models();
}

bool Building::refit() {
  refit_doors();
  // A bounded window: the same cost every night however long the robot has lived.
  store::TraversalQuery window;
  if (options.refit_window) window.from = clock.now() - *options.refit_window;
  auto log = store::find_traversals(store, window);
  if (!log) {
    book.write_error(log.error().message);
    return false;
  }
  if (log->empty()) return false;
  // One set of models for every robot: each attempt in the fleet's standard time.
  speeds = learn::RobotSpeeds::fit(*log);
  if (!speeds.factors().empty()) *log = speeds.standardised(*log);
  const std::vector<learn::EdgeSpec> specs = plan::edge_specs(map);
  // Local time of day; hourly duration bins (a robot's own log has many attempts per edge and
  // hour; sparse bins shrink towards the edge's whole-day table).
  learn::EdgeModelsOptions fit_options;
  fit_options.episode.zone = zone;
  fit_options.episode.duration_bins = options.duration_bins;
  auto fitted = learn::EdgeModels::fit(specs, *log, fit_options);
  if (!fitted) {
    book.write_error(fitted.error().message);
    return false;
  }
  *fitted = with_week(std::move(*fitted));  // building_weekly.cpp
  if (options.risk_alpha) {
    // The chance constraint's travel-time distribution: attempt durations with their own laws.
    plan::AttemptLaws learned = learn_attempt_laws(**fitted, *log);
    store::ObservationQuery q{.what = kStoppedAttempt};
    q.from = window.from;
    if (auto stopped = store::find_observations(store, q))
      learned.stopped = learn_stopped_attempts(map, *log, *stopped);
    else
      book.write_error(stopped.error().message);
    auto laws = std::make_shared<const plan::AttemptLaws>(std::move(learned));
    models->set_attempt_laws(laws);
    offline_models->set_attempt_laws(laws);
  }
  models->set(*fitted);
  if (options.online_model) offline_models->set(*fitted);
  return true;
}

void Building::refit_doors() {
  door_models->refit(clock.now(), options.refit_window);
}

Status Building::restore_door_models() {
  store::ObservationQuery q{.what = "door_open"};
  if (options.refit_window) q.from = clock.now() - *options.refit_window;
  RONDO_ASSIGN_OR_RETURN(const std::vector<store::Observation> seen, store::find_observations(store, q));
  if (seen.empty()) return Status{};
  for (const store::Observation& o : seen) door_models->observe(o.where, o.when, o.value >= 0.5);
  refit_doors();
  return Status{};
}

// The loading times learnt so far, from the store's observations ("load time" at a place, with
// the task that took it): the declared prior of each comes from that task.
Status Building::restore_loading_times() {
  for (const std::string& action : loading->actions()) {
    RONDO_ASSIGN_OR_RETURN(const std::vector<store::Observation> seen,
                           store::find_observations(store, {.what = action + " time"}));
    for (const store::Observation& o : seen) {
      if (!o.text || !book.contains(*o.text)) continue;
      const TaskRecord& r = book.at(*o.text);
      const Duration declared = r.task.duration / static_cast<std::int64_t>(r.action_count());
      loading->observe(action, o.where, declared, from_seconds(o.value), true, o.when);
    }
  }
  return Status{};
}

}  // namespace rondo::exec
