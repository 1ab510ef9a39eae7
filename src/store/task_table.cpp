#include "rondo/store/task_table.h"

#include <fmt/format.h>

#include <limits>

#include "db/dialect.h"
#include "event_rows.h"
#include "request_rows.h"
#include "rondo/core/time.h"
#include "store_access.h"
#include "write_tx.h"

namespace rondo::store {
namespace {

constexpr const char* kSelectTask =
    "SELECT id, state, task_json, created_ms, updated_ms, source, progress_json, planned_start_ms, planned_end_ms, "
    "COALESCE(robot, '') FROM tasks";

std::optional<Time> optional_time(const db::Rows& row, int column) {
  return row.is_null(column) ? std::nullopt : std::optional<Time>(time_from_db(row.int64(column)));
}

std::optional<std::string> optional_json(const Json& j) {
  return j.is_null() ? std::nullopt : std::optional<std::string>(j.dump());
}

Result<TaskRow> task_from_row(const Store& store, const db::Rows& row) {
  TaskRow r;
  r.id = row.text(0);
  r.state = row.text(1);
  const std::string text = row.text(2);
  r.task = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (r.task.is_discarded()) {
    return Error::storage(fmt::format("{}: task '{}': the stored JSON does not parse", store.name(), r.id));
  }
  r.created = time_from_db(row.int64(3));
  r.updated = time_from_db(row.int64(4));
  r.source = row.text(5);
  if (!row.is_null(6)) {
    r.progress = Json::parse(row.text(6), nullptr, /*allow_exceptions=*/false);
    if (r.progress.is_discarded())
      return Error::storage(fmt::format("{}: task '{}': the stored progress does not parse", store.name(), r.id));
  }
  r.planned_start = optional_time(row, 7);
  r.planned_end = optional_time(row, 8);
  r.robot = row.text(9);
  return r;
}

Result<std::vector<TaskRow>> read_tasks(const Store& store, db::Rows& query) {
  std::vector<TaskRow> out;
  while (query.next()) {
    auto r = task_from_row(store, query);
    if (!r) return r.error();
    out.push_back(std::move(*r));
  }
  return out;
}

}  // namespace

Status add_task(Store& store, const TaskRow& task, std::string_view reason, std::string_view code) {
  return add_tasks(store, std::span<const TaskRow>(&task, 1), reason, code);
}

Status add_tasks(Store& store, std::span<const TaskRow> tasks, std::string_view reason, std::string_view code,
                 const RequestTaken* taken) {
  if (tasks.empty() && !taken) return {};
  for (const TaskRow& t : tasks) {
    if (t.id.empty()) return Error::invalid(store.name() + ": a task needs a non-empty id");
  }
  const std::string what =
      tasks.size() == 1 ? fmt::format("adding task '{}'", tasks[0].id) : fmt::format("adding {} tasks", tasks.size());
  return guarded(store, what, [&]() -> Status {
    db::Connection& db = connection(store);
    WriteTx tx(db);
    constexpr std::string_view kInsert =
        "INSERT INTO tasks (id, state, task_json, created_ms, updated_ms, source, progress_json, planned_start_ms, "
        "planned_end_ms, robot) VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, NULLIF($10, '')) ON CONFLICT (id) DO NOTHING";
    for (const TaskRow& task : tasks) {
      const std::int64_t added =
          db.exec(kInsert, {task.id, task.state, task.task.dump(), to_db(task.created), to_db(task.updated), task.source,
                            optional_json(task.progress), to_db(task.planned_start), to_db(task.planned_end), task.robot});
      if (added == 0) {  // the transaction rolls back: none of `tasks` is stored
        return Error::invalid(fmt::format("{}: task '{}' is already stored", store.name(), task.id));
      }
      append_event_row(db, {.time = task.created,
                            .task_id = task.id,
                            .event = task.state,
                            .code = std::string(code),
                            .reason = std::string(reason)});
    }
    if (taken) RONDO_RETURN_IF_ERROR(mark_request_taken(db, store.name(), *taken));
    tx.commit();  // with synchronous=FULL the WAL is synced to disk here
    return {};
  });
}

Status set_task_robot(Store& store, std::string_view id, std::string_view robot) {
  return guarded(store, fmt::format("allocating task '{}'", id), [&]() -> Status {
    if (connection(store).exec("UPDATE tasks SET robot = NULLIF($1, '') WHERE id = $2", {robot, id}) == 0) return Error::not_found(fmt::format("{}: no task '{}'", store.name(), id));
    return {};
  });
}

Status set_task_state(Store& store, std::string_view id, std::string_view state, Time at, std::string_view reason,
                      std::string_view code, const std::optional<PlannedTimes>& planned) {
  return guarded(store, fmt::format("changing the state of task '{}'", id), [&]() -> Status {
    db::Connection& db = connection(store);
    WriteTx tx(db);
    const std::int64_t changed =
        planned ? db.exec("UPDATE tasks SET state = $1, updated_ms = $2, planned_start_ms = $3, planned_end_ms = $4 "
                          "WHERE id = $5",
                          {state, to_db(at), to_db(planned->start), to_db(planned->end), id})
                : db.exec("UPDATE tasks SET state = $1, updated_ms = $2 WHERE id = $3", {state, to_db(at), id});
    if (changed == 0) return Error::not_found(fmt::format("{}: no task '{}'", store.name(), id));
    append_event_row(db, {.time = at,
                          .task_id = std::string(id),
                          .event = std::string(state),
                          .code = std::string(code),
                          .reason = std::string(reason)});
    tx.commit();
    return {};
  });
}

Status set_task_progress(Store& store, std::string_view id, const Json& progress) {
  return guarded(store, fmt::format("recording the progress of task '{}'", id), [&]() -> Status {
    if (connection(store).exec("UPDATE tasks SET progress_json = $1 WHERE id = $2", {optional_json(progress), id}) == 0) return Error::not_found(fmt::format("{}: no task '{}'", store.name(), id));
    return {};
  });
}

Status set_task_definition(Store& store, std::string_view id, const Json& task) {
  return guarded(store, fmt::format("changing task '{}'", id), [&]() -> Status {
    if (connection(store).exec("UPDATE tasks SET task_json = $1 WHERE id = $2", {task.dump(), id}) == 0) return Error::not_found(fmt::format("{}: no task '{}'", store.name(), id));
    return {};
  });
}

Result<TaskRow> get_task(const Store& store, std::string_view id) {
  return guarded(store, fmt::format("reading task '{}'", id), [&]() -> Result<TaskRow> {
    auto query = connection(store).query(std::string(kSelectTask) + " WHERE id = $1", {id});
    if (!query->next()) return Error::not_found(fmt::format("{}: no task '{}'", store.name(), id));
    return task_from_row(store, *query);
  });
}

Result<std::vector<TaskRow>> list_tasks(const Store& store) {
  return guarded(store, "listing tasks", [&]() -> Result<std::vector<TaskRow>> {
    auto query = connection(store).query(std::string(kSelectTask) + " ORDER BY created_ms, id");
    return read_tasks(store, *query);
  });
}

Result<std::vector<TaskRow>> list_tasks_in_state(const Store& store, std::string_view state) {
  return guarded(store, fmt::format("listing tasks in state '{}'", state), [&]() -> Result<std::vector<TaskRow>> {
    auto query = connection(store).query(std::string(kSelectTask) + " WHERE state = $1 ORDER BY created_ms, id", {state});
    return read_tasks(store, *query);
  });
}

Result<TaskPage> find_tasks(const Store& store, const TaskFilter& filter) {
  return guarded(store, "finding tasks", [&]() -> Result<TaskPage> {
    db::Connection& db = connection(store);
    // The codec's times ("2026-11-23T08:45:00Z", with or without milliseconds) are compared as
    // times, not as text (db::as_time).
    const auto window_time = [&](std::string_view key) {
      return db::as_time(db.backend(), db::json_field(db.backend(), "task_json", {"window", key}));
    };
    std::string where = " WHERE ($1 = '' OR state = $1) AND ($2 = '' OR source = $2)";
    db::Params params{filter.state, filter.source};
    std::string window = "TRUE";
    if (filter.from) {
      params.emplace_back(format_time(*filter.from));
      window += fmt::format(" AND {} > {}", window_time("deadline"), db::as_time(db.backend(), fmt::format("${}", params.size())));
    }
    if (filter.to) {
      params.emplace_back(format_time(*filter.to));
      window += fmt::format(" AND {} < {}", window_time("release"), db::as_time(db.backend(), fmt::format("${}", params.size())));
    }
    if (filter.from || filter.to) {
      if (filter.windowless_by_added) {
        params.emplace_back(filter.from ? to_db(*filter.from) : std::numeric_limits<std::int64_t>::min());
        params.emplace_back(filter.to ? to_db(*filter.to) : std::numeric_limits<std::int64_t>::max());
        window = fmt::format("({}) OR ({} IS NULL AND created_ms >= ${} AND created_ms < ${})", window,
                             db::json_field(db.backend(), "task_json", {"window"}), params.size() - 1, params.size());
      }
      where += " AND (" + window + ")";
    }
    TaskPage page;
    page.total = db::query_int64(db, "SELECT COUNT(*) FROM tasks" + where, params).value_or(0);
    // rowid: the order the tasks were accepted in (SQLite's implicit rowid; a column of that name on PostgreSQL).
    const std::size_t n = params.size();
    params.emplace_back(static_cast<std::int64_t>(filter.limit));
    params.emplace_back(static_cast<std::int64_t>(filter.offset));
    auto query = db.query(fmt::format("{}{} ORDER BY rowid LIMIT ${} OFFSET ${}", kSelectTask, where, n + 1, n + 2), params);
    RONDO_ASSIGN_OR_RETURN(page.rows, read_tasks(store, *query));
    return page;
  });
}

Result<std::map<std::string, long>> count_tasks_by_state(const Store& store) {
  return guarded(store, "counting tasks by state", [&]() -> Result<std::map<std::string, long>> {
    auto q = connection(store).query("SELECT state, COUNT(*) FROM tasks GROUP BY state");
    std::map<std::string, long> out;
    while (q->next()) out[q->text(0)] = q->int64(1);
    return out;
  });
}

Result<std::map<std::string, std::map<std::string, long>>> count_tasks_by_robot(const Store& store) {
  using Counts = std::map<std::string, std::map<std::string, long>>;
  return guarded(store, "counting tasks by robot", [&]() -> Result<Counts> {
    auto q = connection(store).query(
        "SELECT COALESCE(robot, ''), state, COUNT(*) FROM tasks GROUP BY COALESCE(robot, ''), state");
    Counts out;
    while (q->next()) out[q->text(0)][q->text(1)] = q->int64(2);
    return out;
  });
}

}  // namespace rondo::store
