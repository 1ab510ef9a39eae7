// The fleet's front: robots, tasks in (checked, allocated, stored, handed to their robots), and
// changes routed to the robot whose task it is.
#include "rondo/fleet/fleet.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>
#include <utility>

namespace rondo::fleet {
namespace {

std::string names_of(const std::vector<std::unique_ptr<exec::Executor>>& robots) {
  std::string s;
  for (const auto& r : robots) s += fmt::format("{}'{}'", s.empty() ? "" : ", ", r->name());
  return s;
}

}  // namespace

Fleet::Fleet(exec::Clock& clock, const map::TopoMap& map, store::Store& store, const TimeZone& zone,
             const exec::ExecutorOptions& options, std::shared_ptr<plan::LearnedEdgeModels> models,
             std::unique_ptr<Allocator> allocator)
    : building_(clock, map, store, zone, options, std::move(models)),
      options_(options),
      allocator_(allocator ? std::move(allocator) : std::make_unique<GreedyAllocator>()) {}

Fleet::~Fleet() = default;

exec::Executor& Fleet::add_robot(exec::Robot& robot, exec::ExecutorOptions options,
                                 std::unique_ptr<schedule::Scheduler> scheduler) {
  robots_.push_back(std::make_unique<exec::Executor>(building_, robot, std::move(options), std::move(scheduler)));
  watch(*robots_.back());
  exec::Executor& added = *robots_.back();
  // Posted: the robot is in the middle of its schedule when it calls, and a move calls back into it.
  added.on_dropped([this, &added](const std::vector<TaskId>& ids) {
    if (robots_.size() > 1)
      building_.clock.schedule_after(Duration{0}, [this, &added, ids] { offer_dropped(added, ids); });
  });
  added.on_free([this, &added] {
    if (robots_.size() > 1 && free_posted_.insert(added.name()).second)
      building_.clock.schedule_after(Duration{0}, [this, &added] {
        free_posted_.erase(added.name());
        offer_to_free(added);
      });
  });
  return *robots_.back();
}

exec::Executor* Fleet::find_robot(std::string_view name) const {
  for (const auto& r : robots_)
    if (r->name() == name) return r.get();
  return nullptr;
}

std::size_t Fleet::index_of(const std::string& robot) const {
  for (std::size_t i = 0; i < robots_.size(); ++i)
    if (robots_[i]->name() == robot) return i;
  return robots_.size();
}

Status Fleet::runs_here(const Task& task) const {
  if (!task.robot.empty() && !find_robot(task.robot))
    return Error::invalid(fmt::format("task {}: robot '{}' is not in this deployment (its {} {})", task.id, task.robot,
                                      robots_.size() == 1 ? "robot is" : "robots are", names_of(robots_)));
  for (const std::string* node : {&task.start_node, &task.end_node}) {
    if (!node->empty() && !building_.map.find_node(*node))
      return Error::invalid(fmt::format("task {}: node '{}' is not on the map", task.id, *node));
  }
  if (task.kind == TaskKind::kStandard && task.start_node.empty() && !task.has_spec())
    return Error::invalid(fmt::format("task {}: a standard task needs a start node", task.id));
  return Status{};
}

std::optional<std::string> Fleet::cannot_run(const std::vector<Action>& actions) const {
  std::optional<std::string> why;
  for (const auto& r : robots_) {
    auto no = r->cannot_run(actions);
    if (!no) return std::nullopt;
    if (!why) why = std::move(no);  // the first robot's words: a fleet of one says what it always said
  }
  return why;
}

std::optional<std::string> Fleet::cannot_run(const Task& task) const {
  if (!task.robot.empty()) {
    const exec::Executor* own = find_robot(task.robot);
    return own ? own->cannot_run(task.actions) : std::nullopt;
  }
  return cannot_run(task.actions);
}

Status Fleet::accept(const Task& task) const {
  if (auto ok = validate(task, "task " + task.id); !ok) return ok;
  if (building_.book.contains(task.id)) return Error::invalid(fmt::format("task {}: the id is already taken", task.id));
  RONDO_RETURN_IF_ERROR(runs_here(task));
  // Refused now rather than failed at its place: no robot says it can run one of its actions.
  if (auto why = cannot_run(task)) return Error::invalid(fmt::format("task {}: {}", task.id, *why));
  return Status{};
}

std::vector<std::size_t> Fleet::eligible(const Task& task) const {
  if (!task.robot.empty()) return {index_of(task.robot)};
  std::vector<std::size_t> can, working;
  for (std::size_t i = 0; i < robots_.size(); ++i) {
    if (robots_[i]->cannot_run(task.actions)) continue;
    can.push_back(i);
    if (!robots_[i]->out_of_service() && !robots_[i]->paused()) working.push_back(i);
  }
  return working.empty() ? can : working;
}

std::vector<Allocation> Fleet::allocate(const std::vector<Task>& tasks, const Skip& skip) {
  std::vector<AllocationUnit> units;
  std::vector<std::size_t> unit_of(tasks.size());
  std::map<std::string, std::size_t> unit_of_job;  // a delivery job's halves go together
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const Task& t = tasks[i];
    if (t.delivery) {
      if (auto it = unit_of_job.find(t.delivery->job); it != unit_of_job.end()) {
        AllocationUnit& unit = units[it->second];
        unit.tasks.push_back(&t);
        unit_of[i] = it->second;
        // Only a robot that runs both halves' actions (a robot that loads may not unload); when
        // none does, the first half's robots, as before.
        const std::vector<std::size_t> also = eligible(t);
        std::vector<std::size_t> both;
        for (const std::size_t r : unit.eligible)
          if (std::find(also.begin(), also.end(), r) != also.end()) both.push_back(r);
        if (!both.empty()) unit.eligible = std::move(both);
        continue;
      }
    }
    std::vector<std::size_t> may = eligible(t);
    if (t.delivery) {
      // A job with a half already on a robot (a return planned for an object on board) stays there.
      for (const TaskId& other : building_.book.order()) {
        const exec::TaskRecord& r = building_.book.at(other);
        if (r.task.delivery && r.task.delivery->job == t.delivery->job && !r.robot.empty() &&
            index_of(r.robot) < robots_.size()) {
          may = {index_of(r.robot)};
          break;
        }
      }
      unit_of_job[t.delivery->job] = units.size();
    }
    if (skip) std::erase_if(may, [&](std::size_t r) { return skip(t, r); });
    unit_of[i] = units.size();
    units.push_back({.tasks = {&t}, .eligible = std::move(may)});
  }
  // Units no robot may take are left out of the allocator's question.
  std::vector<AllocationUnit> asked;
  std::vector<std::size_t> answer_of(units.size(), units.size());
  for (std::size_t u = 0; u < units.size(); ++u)
    if (!units[u].eligible.empty()) {
      answer_of[u] = asked.size();
      asked.push_back(units[u]);
    }
  std::vector<const exec::Executor*> robots;
  for (const auto& r : robots_) robots.push_back(r.get());
  const std::vector<Allocation> chosen = allocator_->allocate(asked, robots, building_);
  std::vector<Allocation> out;
  out.reserve(tasks.size());
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const std::size_t a = answer_of[unit_of[i]];
    out.push_back(a < chosen.size() ? chosen[a] : Allocation{.robot = robots_.size(), .why = "no robot may take it"});
  }
  return out;
}

void Fleet::hand_out(const std::vector<TaskId>& ids) {
  for (const auto& r : robots_) {
    std::vector<TaskId> mine;
    for (const TaskId& id : ids)
      if (building_.book.at(id).robot == r->name()) mine.push_back(id);
    if (!mine.empty()) r->take(std::move(mine));
  }
}

Status Fleet::add_tasks(std::vector<Task> tasks, std::string_view source, const store::RequestTaken* taken) {
  std::string ids;
  for (const Task& t : tasks) ids += (ids.empty() ? "" : ",") + t.id;
  Status ok;
  for (const Task& t : tasks)
    if (ok) ok = accept(t);
  std::vector<TaskId> added;
  std::vector<Allocation> to;
  if (ok) {
    to = allocate(tasks);
    std::vector<std::string> robots;
    for (const Allocation& a : to) robots.push_back(robots_[a.robot]->name());
    for (const Task& t : tasks) added.push_back(t.id);
    ok = building_.book.add(std::move(tasks), source, taken, robots);
  }
  if (!ok) {
    // A refused request is part of the record too (a queued one is taken with it).
    std::optional<store::RequestTaken> refused;
    if (taken) refused = store::RequestTaken{taken->id, taken->at, "rejected: " + ok.error().message};
    building_.book.note_request(taken ? fmt::format("request {}", taken->id) : ids, exec::EventKind::kRejected,
                                exec::Outcome::kInvalidRequest, fmt::format("from {}: {}", source, ok.error().message),
                                refused ? &*refused : nullptr);
    return ok;
  }
  // A fleet says why it chose each robot (a fleet of one has nothing to say).
  if (robots_.size() > 1)
    for (std::size_t i = 0; i < added.size(); ++i)
      building_.book.note(added[i], exec::EventKind::kAllocated, exec::Outcome::kNone,
                          fmt::format("to {}: {}", robots_[to[i].robot]->name(), to[i].why));
  hand_out(added);
  return Status{};
}

void Fleet::reject_request(const store::RequestTaken& taken, const std::string& reason) {
  building_.book.note_request(fmt::format("request {}", taken.id), exec::EventKind::kRejected,
                              exec::Outcome::kInvalidRequest, reason, &taken);
}

exec::Executor& Fleet::robot_of(const TaskId& id) const {
  const exec::TaskRecord* r = building_.book.find(id);
  exec::Executor* own = r ? find_robot(r->robot) : nullptr;
  // A task no robot holds (over, and gone from memory): any robot answers for the book.
  return own ? *own : robot();
}

Status Fleet::cancel_task(const TaskId& id, const std::string& reason) {
  return robot_of(id).cancel_task(id, reason);
}

Status Fleet::confirm_action(const TaskId& id, const std::string& by) {
  return robot_of(id).confirm_action(id, by);
}

Status Fleet::update_task(const TaskId& id, std::optional<TimeWindow> window, std::optional<int> priority) {
  return robot_of(id).update_task(id, window, priority);
}

std::optional<double> Fleet::door_open_probability(const std::string& door, Time t) const {
  return robot().door_open_probability(door, t);
}

std::vector<std::string> Fleet::door_names() const {
  return robot().door_names();
}

std::vector<exec::LearnedActionTime> Fleet::loading_times() const {
  return robot().loading_times();
}

}  // namespace rondo::fleet
