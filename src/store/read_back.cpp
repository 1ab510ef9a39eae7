#include "rondo/store/read_back.h"

#include <fmt/format.h>

#include <algorithm>

#include "store_access.h"

namespace rondo::store {
namespace {

// Rowid order is the order the tasks were accepted in, also within one batch.
Result<std::vector<TaskRow>> tasks_in_insertion_order(const Store& store) {
  RONDO_ASSIGN_OR_RETURN(std::vector<TaskRow> all, list_tasks(store));
  RONDO_ASSIGN_OR_RETURN(std::vector<std::string> order,
                         guarded(store, "reading the task order", [&]() -> Result<std::vector<std::string>> {
                           // rowid: SQLite's implicit one; a column of that name on PostgreSQL.
                           auto q = connection(store).query("SELECT id FROM tasks ORDER BY rowid");
                           std::vector<std::string> ids;
                           while (q->next()) ids.push_back(q->text(0));
                           return ids;
                         }));
  std::map<std::string, TaskRow> by_id;
  for (TaskRow& r : all) {
    std::string id = r.id;
    by_id.emplace(std::move(id), std::move(r));
  }
  std::vector<TaskRow> out;
  out.reserve(order.size());
  for (const std::string& id : order) {
    auto it = by_id.find(id);
    if (it != by_id.end()) out.push_back(std::move(it->second));
  }
  return out;
}

// One of a task's events, in append order: its last transition and its drop for now.
void fold(StoredTask& t, const Event& e) {
  if (e.code == "added") ++t.added_events;
  if (e.event == "queued") t.started.reset();
  if (!t.started && (e.event == "waiting" || e.event == "navigating" || e.event == "acting")) t.started = e.time;
  if (e.event == t.row.state) {
    t.last_transition = e;
    t.dropped_for_now.reset();  // a change of state since the drop
  } else if (e.event == kDroppedForNowEvent) {
    t.dropped_for_now = e;
  } else if (e.event == kReOfferedEvent) {
    t.dropped_for_now.reset();
  }
}

// A drop older than the change that put the task in its state is over (fold() takes events in
// append order, so only a state event named differently from the current state can precede it).
void settle(StoredTask& t) {
  if (t.dropped_for_now && t.last_transition && t.dropped_for_now->seq < t.last_transition->seq)
    t.dropped_for_now.reset();
}

}  // namespace

std::optional<Time> StoredRun::latest() const {
  std::optional<Time> t;
  const auto later = [&t](Time x) { t = t ? std::max(*t, x) : x; };
  if (log_end.seq > 0) later(log_end.time);
  if (traversals_end) later(*traversals_end);
  if (robot) later(robot->updated);
  return t;
}

Result<StoredRun> read_back(const Store& store, std::string_view robot) {
  StoredRun run;
  RONDO_ASSIGN_OR_RETURN(std::vector<TaskRow> rows, tasks_in_insertion_order(store));
  RONDO_ASSIGN_OR_RETURN(run.events, read_events(store));
  RONDO_ASSIGN_OR_RETURN(run.log_end, log_end(store));
  RONDO_ASSIGN_OR_RETURN(run.robot, load_robot_state(store, robot));
  RONDO_ASSIGN_OR_RETURN(run.meta, read_meta(store));
  RONDO_ASSIGN_OR_RETURN(run.traversals_end,
                         guarded(store, "reading the end of the traversal log", [&]() -> Result<std::optional<Time>> {
                           const auto end = db::query_int64(connection(store),
                                                            "SELECT MAX(start_ms + duration_ms) FROM traversals");
                           if (!end) return std::optional<Time>{};
                           return std::optional<Time>(time_from_db(*end));
                         }));

  std::map<std::string, std::size_t> index;
  run.tasks.reserve(rows.size());
  for (TaskRow& r : rows) {
    index.emplace(r.id, run.tasks.size());
    run.tasks.push_back(StoredTask{.row = std::move(r),
                                   .last_transition = std::nullopt,
                                   .dropped_for_now = std::nullopt,
                                   .added_events = 0,
                                   .started = std::nullopt});
  }
  for (const Event& e : run.events) {
    if (e.subject != Subject::kTask) continue;
    const auto it = index.find(e.task_id);
    if (it == index.end()) continue;  // the schema's foreign key makes this impossible
    fold(run.tasks[it->second], e);
  }
  for (StoredTask& t : run.tasks) settle(t);
  return run;
}

Result<std::vector<StoredTask>> read_stored_tasks(const Store& store, std::vector<TaskRow> rows) {
  std::vector<StoredTask> out;
  out.reserve(rows.size());
  for (TaskRow& r : rows) {
    RONDO_ASSIGN_OR_RETURN(const std::vector<Event> events, read_events_of(store, r.id));
    StoredTask t{.row = std::move(r),
                 .last_transition = std::nullopt,
                 .dropped_for_now = std::nullopt,
                 .added_events = 0,
                 .started = std::nullopt};
    for (const Event& e : events) fold(t, e);
    settle(t);
    out.push_back(std::move(t));
  }
  return out;
}

Result<std::optional<StoredTask>> read_stored_task(const Store& store, std::string_view id) {
  auto row = get_task(store, id);
  if (!row) {
    if (row.error().code == ErrorCode::kNotFound) return std::optional<StoredTask>{};
    return row.error();
  }
  std::vector<TaskRow> rows;
  rows.push_back(std::move(*row));
  RONDO_ASSIGN_OR_RETURN(std::vector<StoredTask> tasks, read_stored_tasks(store, std::move(rows)));
  return std::optional<StoredTask>(std::move(tasks.front()));
}

}  // namespace rondo::store
