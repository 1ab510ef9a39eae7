// The executor and the battery (docs/executor.md, "Battery"): readings at every robot callback
// and before every command (BatteryWatch, which learns the battery's costs from them), and the
// hard threshold: below it the robot goes to charge at the next interruptible moment, whatever the
// schedule says, and starts nothing new until the battery is back at the resume level.
#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "battery_watch.h"
#include "dispatcher.h"
#include "rondo/exec/executor.h"
#include "task_run.h"
#include "text.h"

namespace rondo::exec {
namespace {

// A state of charge for people: "14.9 %".
std::string percent(double level) { return fmt::format("{:.1f} %", level * 100); }

}  // namespace

void Executor::read_battery() { battery_->read(clock_.now(), robot_.battery(), robot_.charging()); }

double Executor::resume_level() const {
  return options_.battery_resume > 0 ? options_.battery_resume : options_.battery_reserve;
}

bool Executor::below_threshold() const {
  return options_.battery_threshold > 0 && battery_->level() < options_.battery_threshold;
}

Duration Executor::time_to_charge() const {
  const double hours = battery_->estimator().hours_to_charge(battery_->level(), resume_level());
  return hours > 0 ? from_seconds(hours * 3600) : Duration{0};
}

BatteryFigures Executor::battery_figures() const {
  BatteryFigures f = battery_->figures();
  f.low_battery = low_battery_count_;
  return f;
}

void Executor::enter_low_battery() {
  low_battery_ = true;
  ++low_battery_count_;
  low_since_ = clock_.now();
  book_.note_robot("battery low", Outcome::kCharging,
                   fmt::format("battery {} at {}, below the hard threshold {}: the robot goes to charge at the "
                               "next interruptible moment and starts nothing new until {} (about {} on the "
                               "charger)",
                               percent(battery_->level()), map_.node(robot_.location()).name,
                               percent(options_.battery_threshold), percent(resume_level()),
                               duration_text(time_to_charge())));
}

void Executor::check_battery() {
  if (low_battery_ || !started_ || !below_threshold()) return;
  enter_low_battery();
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
  if (!low_battery_) {
    if (!below_threshold()) return false;
    enter_low_battery();  // found low between two tasks
    reschedule({}, "battery low");
    return true;
  }
  if (battery_->level() < resume_level()) return true;
  book_.note_robot("charged", Outcome::kCharging,
                   fmt::format("battery {} after {} since it fell below {}: dispatch resumes",
                               percent(battery_->level()), duration_text(clock_.now() - low_since_),
                               percent(options_.battery_threshold)));
  reschedule({}, "charged");  // still charging for it: what no longer fits is dropped for the charge
  low_battery_ = false;
  return false;
}

void Executor::charge() {
  if (robot_.location() != options_.dock) return go_to_dock();
  // On the charger: look again when the resume level is expected (at least every slot).
  look_again_at(clock_.now() + std::clamp(time_to_charge() + seconds(1), seconds(1), options_.slot_width));
}

}  // namespace rondo::exec
