// The executor and the battery (docs/executor.md, "Battery"): readings at every robot callback
// and before every command, and the hard threshold: below it the robot goes to charge at the next
// interruptible moment, whatever the schedule says, and starts nothing new until the battery is
// back at the resume level. What is kept about the battery, and the levels it is measured against,
// are Charging's (charging.h); what follows from them (reschedules, trips to the dock, preemption)
// is here.
#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "battery_memory.h"
#include "charging.h"
#include "dispatcher.h"
#include "rondo/exec/executor.h"
#include "rondo/store/robot_state.h"
#include "task_run.h"
#include "text.h"

namespace rondo::exec {

void Executor::read_battery() { charging_->read(); }

bool Executor::charging_as_planned() {
  if (charging_->planned_goes_on()) return true;
  save_battery();
  reschedule({}, "charged as planned");
  return false;
}

void Executor::save_battery() {
  const std::string text = encode_battery_state(charging_->estimator().state());
  if (auto ok = store::set_meta(store_, battery_meta_key(options_.robot_name), text); !ok)
    book_.write_error(ok.error().message);
}

void Executor::restore_battery() {
  const std::string key = battery_meta_key(options_.robot_name);
  const Result<std::optional<std::string>> stored = store::get_meta(store_, key);
  if (!stored.ok()) return book_.write_error(stored.error().message);
  if (!*stored) return;  // nothing learned yet
  std::string why;
  if (Result<BatteryEstimator::State> state = decode_battery_state(**stored); !state.ok())
    why = state.error().message;
  else if (!charging_->restore_estimator(*state))
    why = "its numbers are not an estimate (not finite, or not a positive-definite information matrix)";
  else
    return;
  book_.note_robot(options_.robot_name, EventKind::kBatteryEstimateReset, Outcome::kBattery,
                   fmt::format("the stored battery estimate ({}) could not be read: {}; the estimator starts again "
                               "from its prior",
                               key, why));
}

bool Executor::reoffer_for_battery() {
  const Time now = clock_.now();
  const bool waiting = std::any_of(dispatcher_->deferred().begin(), dispatcher_->deferred().end(), [&](const TaskId& id) {
    const TaskRecord& r = book_.at(id);
    return r.dropped_for_now && r.dropped_for_now->first == Outcome::kCharging;
  });
  if (!waiting || !options_.battery_planning) return false;
  if (now < charging_->next_reoffer()) {
    look_again_at(charging_->next_reoffer());
    return false;
  }
  charging_->reoffered(now);
  reschedule({}, fmt::format("battery {} on the charger: tasks dropped for the battery offered again",
                             percent(charging_->level())));
  return true;
}

BatteryFigures Executor::battery_figures() const { return charging_->figures(); }

bool Executor::charging_for_battery() const { return charging_->low(); }

void Executor::check_battery() {
  if (charging_->low() || !started_ || !charging_->below_threshold()) return;
  charging_->cancel_planned();
  charging_->enter_low();
  reschedule({}, "battery low");  // the plan starts after the charge (free_at)
  if (run_) return charge_now();
  if (!trip_) next();  // a trip goes to the dock anyway
}

void Executor::charge_now() {
  if (!run_ || run_->stopping()) return;
  const std::string why = fmt::format("the battery is below {}: the robot goes to charge",
                                      percent(options_.battery_threshold));
  if (run_->waiting()) return requeue_waiting(Outcome::kCharging, "waiting ended: " + why);
  // Not interruptible now: it finishes first (or on_interruptible_changed() comes back here).
  if (interruptible_now()) preempt_for(Outcome::kCharging, "preempted: " + why, {});
}

bool Executor::must_charge() {
  read_battery();
  if (!charging_->low()) {
    if (!charging_->below_threshold()) return charging_->planned() && charging_as_planned();
    charging_->cancel_planned();  // the hard threshold takes over
    charging_->enter_low();       // found low between two tasks
    reschedule({}, "battery low");
    return true;
  }
  if (charging_->level() < charging_->resume_level()) return true;
  book_.note_robot(options_.robot_name, EventKind::kCharged, Outcome::kCharging,
                   fmt::format("battery {} after {} since it fell below {}: dispatch resumes",
                               percent(charging_->level()), duration_text(clock_.now() - charging_->low_since()),
                               percent(options_.battery_threshold)));
  save_battery();
  reschedule({}, "charged");  // still charging for it: what no longer fits is dropped for the charge
  charging_->resumed();
  return false;
}

void Executor::charge() {
  if (robot_.location() != options_.dock) return go_to_dock(JourneyPurpose::kCharge);
  // On the charger: look again when the resume level is expected (at least every slot).
  look_again_at(clock_.now() + std::clamp(charging_->time_to_charge() + seconds(1), seconds(1), options_.slot_width));
}

}  // namespace rondo::exec
