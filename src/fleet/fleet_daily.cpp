// The fleet's daily rhythm: routine tasks made at local midnight for the day ahead (and routines
// added while running), the nightly refit of what the building learned, and start().
#include <fmt/format.h>
#include <malloc.h>

#include <chrono>
#include <set>

#include "rondo/fleet/fleet.h"

namespace rondo::fleet {
namespace {

std::chrono::year_month_day next_day(std::chrono::year_month_day d) {
  return std::chrono::year_month_day{std::chrono::sys_days{d} + std::chrono::days{1}};
}

}  // namespace

void Fleet::start() {
  if (started_) return;
  started_ = true;
  // A fleet of several takes back what an on-demand task preempts (a fleet of one: its robot keeps it).
  if (robots_.size() > 1)
    for (const auto& r : robots_)
      r->on_preempted([this, &robot = *r](const TaskId& id) { offer_preempted(robot, id); });
  for (const auto& r : robots_) r->start();
  create_routine_tasks(building_.zone.local_date(building_.clock.now()));
  for (const auto& r : robots_) r->schedule_restored();
  schedule_midnight();
  schedule_refit();
  for (const auto& r : robots_) r->kick_soon();
}

void Fleet::add_routines(std::vector<Routine> routines) {
  for (Routine& r : routines) routines_.push_back(std::move(r));
}

void Fleet::create_routine_tasks(std::chrono::year_month_day day) {
  std::vector<Task> batch;
  const Time now = building_.clock.now();
  for (const Routine& r : routines_) {
    // A routine no robot says it can run (a deployment's, once its vehicles told what they run)
    // makes no task that day, with a `rejected` event; the others' tasks are added as always.
    const std::optional<std::string> why = cannot_run(r.task);
    for (Task& t : instances_on(r, day, building_.zone)) {
      if (!t.window || t.window->deadline <= now || building_.book.known(t.id)) continue;
      if (why) {
        building_.book.note_request(t.id, exec::EventKind::kRejected, exec::Outcome::kInvalidRequest,
                                    fmt::format("from routine {}: {}", r.name, *why));
        continue;
      }
      batch.push_back(std::move(t));
    }
  }
  if (batch.empty()) return;
  if (auto ok = add_tasks(std::move(batch), "routine"); !ok) building_.book.write_error(ok.error().message);
}

std::vector<Task> Fleet::todays_instances(std::size_t first_routine) const {
  std::vector<Task> batch;
  const Time now = building_.clock.now();
  for (std::size_t i = first_routine; i < routines_.size(); ++i)
    for (Task& t : instances_on(routines_[i], building_.zone.local_date(now), building_.zone))
      if (t.window && t.window->deadline - t.duration > now && !building_.book.known(t.id))
        batch.push_back(std::move(t));
  return batch;
}

Status Fleet::add_routine_now(Routine routine) {
  for (const Routine& r : routines_)
    if (r.name == routine.name) return Error::invalid(fmt::format("routine '{}': the name is already taken", r.name));
  for (const std::string* node : {&routine.task.start_node, &routine.task.end_node})
    if (!node->empty() && !building_.map.find_node(*node))
      return Error::invalid(fmt::format("routine '{}': node '{}' is not on the map", routine.name, *node));
  if (auto why = cannot_run(routine.task)) return Error::invalid(fmt::format("routine '{}': {}", routine.name, *why));
  routines_.push_back(std::move(routine));
  if (!started_) return Status{};
  std::vector<Task> batch = todays_instances(routines_.size() - 1);
  if (batch.empty()) return Status{};
  if (auto ok = add_tasks(std::move(batch), "routine"); !ok) {
    routines_.pop_back();
    return ok;
  }
  for (const auto& r : robots_) r->reconsider();
  return Status{};
}

Status Fleet::add_routines_now(std::vector<Routine> routines, const store::RequestTaken& taken,
                               const std::string& why) {
  std::set<std::string> names;
  for (const Routine& r : routines_) names.insert(r.name);
  Status valid;
  if (routines.empty()) valid = Error::invalid("it holds no routine");
  for (const Routine& routine : routines) {
    if (!valid) break;
    if (!names.insert(routine.name).second)
      valid = Error::invalid(fmt::format("routine '{}': the name is already taken", routine.name));
    for (const std::string* node : {&routine.task.start_node, &routine.task.end_node})
      if (valid && !node->empty() && !building_.map.find_node(*node))
        valid = Error::invalid(fmt::format("routine '{}': node '{}' is not on the map", routine.name, *node));
    if (auto cannot = cannot_run(routine.task); valid && cannot)
      valid = Error::invalid(fmt::format("routine '{}': {}", routine.name, *cannot));
  }
  if (!valid) {
    const store::RequestTaken refused{taken.id, taken.at, "rejected: " + valid.error().message};
    building_.book.note_request(fmt::format("request {}", taken.id), exec::EventKind::kRejected,
                                exec::Outcome::kInvalidRequest, valid.error().message, &refused);
    return valid;
  }
  // Marked taken with what keeps the routines: a kill after this finds them at the restart.
  RONDO_RETURN_IF_ERROR(building_.book.take_request(taken, exec::EventKind::kRoutinesAdded, exec::Outcome::kNone, why));
  const std::size_t first = routines_.size();
  for (Routine& r : routines) routines_.push_back(std::move(r));
  if (!started_) return Status{};  // start() adds today's instances
  std::vector<Task> batch = todays_instances(first);
  if (batch.empty()) return Status{};
  // A refusal here is in the event log; the routines stay (they are kept), and make tomorrow's.
  if (auto ok = add_tasks(std::move(batch), "routine"); !ok) building_.book.write_error(ok.error().message);
  for (const auto& r : robots_) r->reconsider();
  return Status{};
}

Status Fleet::remove_routine(const std::string& name) {
  const auto it = std::find_if(routines_.begin(), routines_.end(), [&](const Routine& r) { return r.name == name; });
  if (it == routines_.end()) return Error::not_found(fmt::format("no routine '{}'", name));
  routines_.erase(it);
  return Status{};
}

void Fleet::schedule_midnight() {
  const auto tomorrow = next_day(building_.zone.local_date(building_.clock.now()));
  building_.clock.schedule_at(building_.zone.at(tomorrow, Duration{0}), [this, tomorrow] {
    create_routine_tasks(tomorrow);
    schedule_midnight();
  });
}

void Fleet::schedule_refit() {
  if (!options_.refit_at) return;
  const Time now = building_.clock.now();
  auto day = building_.zone.local_date(now);
  Time at = building_.zone.at(day, *options_.refit_at);
  if (at <= now) at = building_.zone.at(next_day(day), *options_.refit_at);
  building_.clock.schedule_at(at, [this] {
    refit();
    // The night's traversal log and tables are freed: hand the free pages back to the system, so
    // a long-lived service's resident memory is what it holds, not its largest night so far.
    ::malloc_trim(0);
    schedule_refit();
  });
}

void Fleet::refit() {
  if (building_.refit()) ++refits_;
}

}  // namespace rondo::fleet
