#include "rondo/exec/task_book.h"

#include <fmt/format.h>

#include <set>
#include <utility>

#include "rondo/core/task_codec.h"
#include "rondo/store/task_table.h"

namespace rondo::exec {

Status TaskBook::add(std::vector<Task> tasks, std::string_view source, const store::RequestTaken* taken,
                     const std::vector<std::string>& robots) {
  if (!robots.empty() && robots.size() != tasks.size())
    return Error::internal(fmt::format("{} tasks, allocated to {} robots", tasks.size(), robots.size()));
  std::set<TaskId> ids;
  for (const Task& t : tasks) {
    if (t.id.empty()) return Error::invalid("a task needs an id");
    if (records_.contains(t.id)) return Error::invalid(fmt::format("task {}: the id is already taken", t.id));
    if (!ids.insert(t.id).second) return Error::invalid(fmt::format("task {}: the id appears twice", t.id));
  }
  // All or nothing: a batch the store refuses (or cannot write) leaves no task behind, in the store
  // or in memory, so the caller can send it again.
  const Time now = clock_.now();
  const std::string reason = fmt::format("added by {}", source);
  std::vector<store::TaskRow> rows;
  rows.reserve(tasks.size());
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const Task& t = tasks[i];
    rows.push_back({.id = t.id,
                    .task = encode(t),
                    .state = to_string(TaskState::kQueued),
                    .created = now,
                    .updated = now,
                    .source = std::string(source),
                    .robot = robots.empty() ? std::string() : robots[i]});
  }
  RONDO_RETURN_IF_ERROR(store::add_tasks(store_, rows, reason, to_string(Outcome::kAdded), taken));
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const TaskId id = tasks[i].id;
    records_.emplace(id, TaskRecord{.task = std::move(tasks[i]),
                                    .robot = robots.empty() ? std::string() : robots[i],
                                    .state = TaskState::kQueued,
                                    .outcome = Outcome::kAdded,
                                    .reason = reason,
                                    .source = std::string(source),
                                    .added = now});
    order_.push_back(id);
  }
  return {};
}

Status TaskBook::allocate(const TaskId& id, const std::string& robot) {
  TaskRecord& r = records_.at(id);
  if (r.robot == robot) return {};
  RONDO_RETURN_IF_ERROR(store::set_task_robot(store_, id, robot));
  r.robot = robot;
  return {};
}

void TaskBook::restore(TaskRecord record) {
  const TaskId id = record.task.id;
  const bool final = is_final(record.state);
  records_.emplace(id, std::move(record));
  order_.push_back(id);
  if (final) finished_now(id);
}

void TaskBook::finished_now(const TaskId& id) {
  if (!schedule_sweep_) return;
  finished_.push_back(id);
  if (finished_.size() == 1) schedule_sweep_();
}

std::vector<TaskId> TaskBook::sweep() {
  std::vector<TaskId> gone;
  for (const TaskId& id : std::exchange(finished_, {})) {
    const auto it = records_.find(id);
    if (it == records_.end() || !is_final(it->second.state)) continue;
    records_.erase(it);
    gone.push_back(id);
  }
  if (gone.empty()) return gone;
  const std::set<TaskId> erased(gone.begin(), gone.end());
  std::erase_if(order_, [&](const TaskId& id) { return erased.contains(id); });
  return gone;
}

std::optional<TaskState> TaskBook::state_of(const TaskId& id) const {
  if (const TaskRecord* r = find(id)) return r->state;
  auto row = store::get_task(store_, id);
  if (!row) return std::nullopt;
  auto state = parse_task_state(row->state);
  return state ? std::optional<TaskState>(*state) : std::nullopt;
}

Result<std::optional<TaskRecord>> TaskBook::lookup(const TaskId& id, const TimeZone& zone) const {
  if (const TaskRecord* r = find(id)) return std::optional<TaskRecord>(*r);
  RONDO_ASSIGN_OR_RETURN(std::optional<store::StoredTask> stored, store::read_stored_task(store_, id));
  if (!stored) return std::optional<TaskRecord>{};
  RONDO_ASSIGN_OR_RETURN(TaskRecord r, record_of(*stored, zone));
  r.started = stored->started;
  return std::optional<TaskRecord>(std::move(r));
}

void TaskBook::restore_counts(const std::vector<store::Event>& events) {
  for (const store::Event& e : events) {
    const std::optional<Outcome> code = parse_outcome(e.code);
    if (e.subject == store::Subject::kTask && code == Outcome::kAdded) continue;  // add() counts nothing
    const auto state = parse_task_state(e.event);
    if (e.subject == store::Subject::kTask && state) {
      // A transition: counted when it is not final (transition()); a note named like a state
      // (an on-demand task's "waiting") is counted the same way by append().
      if (!is_final(*state)) ++event_counts_[e.event][code.value_or(Outcome::kNone)];
      continue;
    }
    if (code) ++event_counts_[e.event][*code];
  }
}

void TaskBook::transition(const TaskId& id, TaskState state, Outcome outcome, const std::string& reason) {
  TaskRecord& r = records_.at(id);
  r.state = state;
  r.outcome = outcome;
  r.reason = reason;
  if (is_final(state)) {
    r.ended = clock_.now();
    r.dropped_for_now.reset();
    finished_now(id);
  } else {
    ++event_counts_[to_string(state)][outcome];
  }
  // The store is the record of what happened: a failed write is reported, the run goes on.
  // With the planned times as they stand, so a finished task read back from the store (after it
  // left memory) is still shown planned against actual.
  if (auto ok = store::set_task_state(store_, id, to_string(state), clock_.now(), reason, to_string(outcome),
                                      store::PlannedTimes{r.planned_start, r.planned_end});
      !ok)
    write_errors_.push_back(ok.error().message);
}

void TaskBook::set_progress(const TaskId& id, std::size_t actions_done) {
  records_.at(id).actions_done = actions_done;
  if (auto ok = store::set_task_progress(store_, id, progress_json(records_.at(id))); !ok)
    write_errors_.push_back(ok.error().message);
}

void TaskBook::set_spec_state(const TaskId& id, std::uint32_t state, const std::string& place) {
  TaskRecord& r = records_.at(id);
  if (r.spec_state == state && r.spec_place == place) return;
  r.spec_state = state;
  r.spec_place = place;
  if (auto ok = store::set_task_progress(store_, id, progress_json(r)); !ok)
    write_errors_.push_back(ok.error().message);
}

void TaskBook::set_not_before(const TaskId& id, Time t) {
  TaskRecord& r = records_.at(id);
  r.not_before = t;
  if (auto ok = store::set_task_progress(store_, id, progress_json(r)); !ok) write_errors_.push_back(ok.error().message);
}

void TaskBook::set_door_wait(const TaskId& id, std::optional<DoorWait> wait) {
  const auto it = records_.find(id);
  if (it == records_.end()) return;  // finished and gone from memory: it waits for nothing
  TaskRecord& r = it->second;
  if (r.door_wait == wait) return;
  r.door_wait = std::move(wait);
  if (auto ok = store::set_task_progress(store_, id, progress_json(r)); !ok)
    write_errors_.push_back(ok.error().message);
}

Json TaskBook::progress_json(const TaskRecord& r) {
  Json j{{"actions_done", r.actions_done}};
  if (r.not_before) j["not_before_ms"] = r.not_before->time_since_epoch().count();
  if (r.spec_state) j["spec_state"] = *r.spec_state;
  if (!r.spec_place.empty()) j["spec_place"] = r.spec_place;
  if (r.door_wait)
    j["blocked"] = Json{{"door", r.door_wait->door},
                        {"since_ms", r.door_wait->since.time_since_epoch().count()},
                        {"seen_at", r.door_wait->seen_at}};
  return j;
}

void TaskBook::read_progress(const Json& progress, TaskRecord& r) {
  if (!progress.is_object()) return;
  if (progress.contains("actions_done") && progress["actions_done"].is_number_unsigned())
    r.actions_done = progress["actions_done"].get<std::size_t>();
  if (progress.contains("not_before_ms") && progress["not_before_ms"].is_number_integer())
    r.not_before = Time{Duration{progress["not_before_ms"].get<Duration::rep>()}};
  if (progress.contains("spec_state") && progress["spec_state"].is_number_unsigned() &&
      progress["spec_state"].get<std::uint64_t>() <= UINT32_MAX)
    r.spec_state = progress["spec_state"].get<std::uint32_t>();
  if (progress.contains("spec_place") && progress["spec_place"].is_string())
    r.spec_place = progress["spec_place"].get<std::string>();
  if (!progress.contains("blocked") || !progress["blocked"].is_object()) return;
  const Json& b = progress["blocked"];
  const auto text = [&b](const char* key) { return b.contains(key) && b[key].is_string(); };
  if (!text("door") || !text("seen_at") || !b.contains("since_ms") || !b["since_ms"].is_number_integer()) return;
  r.door_wait = DoorWait{b["door"].get<std::string>(), Time{Duration{b["since_ms"].get<Duration::rep>()}},
                         b["seen_at"].get<std::string>()};
}

void TaskBook::note(const TaskId& id, EventKind event, Outcome outcome, const std::string& reason) {
  append({.time = clock_.now(), .task_id = id, .event = std::string(to_string(event)), .code = std::string(to_string(outcome)), .reason = reason});
}

void TaskBook::note_robot(const std::string& robot, EventKind event, Outcome outcome, const std::string& reason) {
  append({.time = clock_.now(),
          .subject = store::Subject::kRobot,
          .about = robot,
          .event = std::string(to_string(event)),
          .code = std::string(to_string(outcome)),
          .reason = reason});
}

void TaskBook::note_schedule(EventKind event, Outcome outcome, const std::string& reason) {
  append({.time = clock_.now(),
          .subject = store::Subject::kSchedule,
          .about = "schedule",
          .event = std::string(to_string(event)),
          .code = std::string(to_string(outcome)),
          .reason = reason});
}

void TaskBook::note_request(const std::string& about, EventKind event, Outcome outcome,
                            const std::string& reason, const store::RequestTaken* taken) {
  append({.time = clock_.now(),
          .subject = store::Subject::kRequest,
          .about = about,
          .event = std::string(to_string(event)),
          .code = std::string(to_string(outcome)),
          .reason = reason},
         taken);
}

Status TaskBook::take_request(const store::RequestTaken& taken, EventKind event, Outcome outcome,
                              const std::string& reason) {
  const store::Event e{.time = clock_.now(),
                       .subject = store::Subject::kRequest,
                       .about = fmt::format("request {}", taken.id),
                       .event = std::string(to_string(event)),
                       .code = std::string(to_string(outcome)),
                       .reason = reason};
  RONDO_RETURN_IF_ERROR(store::take_request(store_, taken, &e));
  if (auto code = parse_outcome(e.code)) ++event_counts_[e.event][*code];
  return {};
}

void TaskBook::append(store::Event event, const store::RequestTaken* taken) {
  if (auto code = parse_outcome(event.code)) ++event_counts_[event.event][*code];
  if (taken) {
    if (auto ok = store::take_request(store_, *taken, &event); !ok) write_errors_.push_back(ok.error().message);
  } else if (auto ok = store::append_event(store_, event); !ok) {
    write_errors_.push_back(ok.error().message);
  }
}

}  // namespace rondo::exec
