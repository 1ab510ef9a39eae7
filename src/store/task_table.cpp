#include "rondo/store/task_table.h"

#include <SQLiteCpp/Statement.h>
#include "write_tx.h"

#include <fmt/format.h>

#include <limits>

#include "event_rows.h"
#include "request_rows.h"
#include "rondo/core/time.h"
#include "sqlite_error.h"

namespace rondo::store {
namespace {

constexpr const char* kSelectTask =
    "SELECT id, state, task_json, created_ms, updated_ms, source, progress_json, planned_start_ms, planned_end_ms, "
    "COALESCE(robot, '') FROM tasks";

std::optional<Time> optional_time(const SQLite::Column& c) {
  return c.isNull() ? std::nullopt : std::optional<Time>(time_from_db(c.getInt64()));
}

void bind_optional_time(SQLite::Statement& s, int index, std::optional<Time> t) {
  if (t)
    s.bind(index, to_db(*t));
  else
    s.bind(index);
}

Result<TaskRow> task_from_row(const Store& store, const SQLite::Statement& row) {
  TaskRow r;
  r.id = row.getColumn(0).getString();
  r.state = row.getColumn(1).getString();
  const std::string text = row.getColumn(2).getString();
  r.task = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (r.task.is_discarded()) {
    return Error::storage(fmt::format("{}: task '{}': the stored JSON does not parse", store.file().string(), r.id));
  }
  r.created = time_from_db(row.getColumn(3).getInt64());
  r.updated = time_from_db(row.getColumn(4).getInt64());
  r.source = row.getColumn(5).getString();
  if (!row.getColumn(6).isNull()) {
    r.progress = Json::parse(row.getColumn(6).getString(), nullptr, /*allow_exceptions=*/false);
    if (r.progress.is_discarded())
      return Error::storage(fmt::format("{}: task '{}': the stored progress does not parse", store.file().string(), r.id));
  }
  r.planned_start = optional_time(row.getColumn(7));
  r.planned_end = optional_time(row.getColumn(8));
  r.robot = row.getColumn(9).getString();
  return r;
}

Result<std::vector<TaskRow>> read_tasks(const Store& store, SQLite::Statement& query) {
  std::vector<TaskRow> out;
  while (query.executeStep()) {
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
    if (t.id.empty()) return Error::invalid(store.file().string() + ": a task needs a non-empty id");
  }
  const std::string what =
      tasks.size() == 1 ? fmt::format("adding task '{}'", tasks[0].id) : fmt::format("adding {} tasks", tasks.size());
  return guarded(store, what, [&]() -> Status {
    SQLite::Database& db = connection(store);
    WriteTx tx(db);
    SQLite::Statement insert(db,
                             "INSERT INTO tasks (id, state, task_json, created_ms, updated_ms, source, progress_json, "
                             "planned_start_ms, planned_end_ms, robot) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, NULLIF(?, '')) "
                             "ON CONFLICT (id) DO NOTHING");
    for (const TaskRow& task : tasks) {
      insert.reset();
      insert.bind(1, task.id);
      insert.bind(2, task.state);
      insert.bind(3, task.task.dump());
      insert.bind(4, to_db(task.created));
      insert.bind(5, to_db(task.updated));
      insert.bind(6, task.source);
      if (task.progress.is_null())
        insert.bind(7);
      else
        insert.bind(7, task.progress.dump());
      bind_optional_time(insert, 8, task.planned_start);
      bind_optional_time(insert, 9, task.planned_end);
      insert.bind(10, task.robot);
      if (insert.exec() == 0) {  // the transaction rolls back: none of `tasks` is stored
        return Error::invalid(fmt::format("{}: task '{}' is already stored", store.file().string(), task.id));
      }
      insert_event_row(db, {.time = task.created,
                            .task_id = task.id,
                            .event = task.state,
                            .code = std::string(code),
                            .reason = std::string(reason)});
    }
    if (taken) RONDO_RETURN_IF_ERROR(mark_request_taken(db, store.file(), *taken));
    tx.commit();  // with synchronous=FULL the WAL is synced to disk here
    return {};
  });
}

Status set_task_robot(Store& store, std::string_view id, std::string_view robot) {
  return guarded(store, fmt::format("allocating task '{}'", id), [&]() -> Status {
    SQLite::Statement update(connection(store), "UPDATE tasks SET robot = NULLIF(?, '') WHERE id = ?");
    update.bind(1, std::string(robot));
    update.bind(2, std::string(id));
    if (update.exec() == 0) return Error::not_found(fmt::format("{}: no task '{}'", store.file().string(), id));
    return {};
  });
}

Status set_task_state(Store& store, std::string_view id, std::string_view state, Time at, std::string_view reason,
                      std::string_view code, const std::optional<PlannedTimes>& planned) {
  return guarded(store, fmt::format("changing the state of task '{}'", id), [&]() -> Status {
    SQLite::Database& db = connection(store);
    WriteTx tx(db);
    SQLite::Statement update(db, planned ? "UPDATE tasks SET state = ?, updated_ms = ?, planned_start_ms = ?, "
                                           "planned_end_ms = ? WHERE id = ?"
                                         : "UPDATE tasks SET state = ?, updated_ms = ? WHERE id = ?");
    update.bind(1, std::string(state));
    update.bind(2, to_db(at));
    if (planned) {
      bind_optional_time(update, 3, planned->start);
      bind_optional_time(update, 4, planned->end);
    }
    update.bind(planned ? 5 : 3, std::string(id));
    if (update.exec() == 0) return Error::not_found(fmt::format("{}: no task '{}'", store.file().string(), id));
    insert_event_row(db, {.time = at,
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
    SQLite::Statement update(connection(store), "UPDATE tasks SET progress_json = ? WHERE id = ?");
    if (progress.is_null())
      update.bind(1);
    else
      update.bind(1, progress.dump());
    update.bind(2, std::string(id));
    if (update.exec() == 0) return Error::not_found(fmt::format("{}: no task '{}'", store.file().string(), id));
    return {};
  });
}

Status set_task_definition(Store& store, std::string_view id, const Json& task) {
  return guarded(store, fmt::format("changing task '{}'", id), [&]() -> Status {
    SQLite::Statement update(connection(store), "UPDATE tasks SET task_json = ? WHERE id = ?");
    update.bind(1, task.dump());
    update.bind(2, std::string(id));
    if (update.exec() == 0) return Error::not_found(fmt::format("{}: no task '{}'", store.file().string(), id));
    return {};
  });
}

Result<TaskRow> get_task(const Store& store, std::string_view id) {
  return guarded(store, fmt::format("reading task '{}'", id), [&]() -> Result<TaskRow> {
    SQLite::Statement query(connection(store), std::string(kSelectTask) + " WHERE id = ?");
    query.bind(1, std::string(id));
    if (!query.executeStep()) return Error::not_found(fmt::format("{}: no task '{}'", store.file().string(), id));
    return task_from_row(store, query);
  });
}

Result<std::vector<TaskRow>> list_tasks(const Store& store) {
  return guarded(store, "listing tasks", [&]() -> Result<std::vector<TaskRow>> {
    SQLite::Statement query(connection(store), std::string(kSelectTask) + " ORDER BY created_ms, id");
    return read_tasks(store, query);
  });
}

Result<std::vector<TaskRow>> list_tasks_in_state(const Store& store, std::string_view state) {
  return guarded(store, fmt::format("listing tasks in state '{}'", state), [&]() -> Result<std::vector<TaskRow>> {
    SQLite::Statement query(connection(store), std::string(kSelectTask) + " WHERE state = ? ORDER BY created_ms, id");
    query.bind(1, std::string(state));
    return read_tasks(store, query);
  });
}

Result<TaskPage> find_tasks(const Store& store, const TaskFilter& filter) {
  return guarded(store, "finding tasks", [&]() -> Result<TaskPage> {
    // SQLite's julianday() reads the codec's times ("2026-11-23T08:45:00Z", with or without
    // milliseconds), so the window is compared as a time, not as text.
    std::string where = " WHERE (?1 = '' OR state = ?1) AND (?2 = '' OR source = ?2)";
    std::string window = "1";
    if (filter.from) window += " AND julianday(json_extract(task_json, '$.window.deadline')) > julianday(?3)";
    if (filter.to) window += " AND julianday(json_extract(task_json, '$.window.release')) < julianday(?4)";
    if (filter.from || filter.to) {
      if (filter.windowless_by_added)
        window = fmt::format(
            "({}) OR (json_extract(task_json, '$.window') IS NULL AND created_ms >= ?7 AND created_ms < ?8)", window);
      where += " AND (" + window + ")";
    }
    const auto bind = [&](SQLite::Statement& q) {
      q.bind(1, filter.state);
      q.bind(2, filter.source);
      if (filter.from) q.bind(3, format_time(*filter.from));
      if (filter.to) q.bind(4, format_time(*filter.to));
      if (filter.windowless_by_added) {
        q.bind(7, filter.from ? to_db(*filter.from) : std::numeric_limits<std::int64_t>::min());
        q.bind(8, filter.to ? to_db(*filter.to) : std::numeric_limits<std::int64_t>::max());
      }
    };
    TaskPage page;
    SQLite::Statement count(connection(store), "SELECT COUNT(*) FROM tasks" + where);
    bind(count);
    if (count.executeStep()) page.total = count.getColumn(0).getInt64();
    SQLite::Statement query(connection(store), std::string(kSelectTask) + where + " ORDER BY rowid LIMIT ?5 OFFSET ?6");
    bind(query);
    query.bind(5, static_cast<std::int64_t>(filter.limit));
    query.bind(6, static_cast<std::int64_t>(filter.offset));
    RONDO_ASSIGN_OR_RETURN(page.rows, read_tasks(store, query));
    return page;
  });
}

Result<std::map<std::string, long>> count_tasks_by_state(const Store& store) {
  return guarded(store, "counting tasks by state", [&]() -> Result<std::map<std::string, long>> {
    SQLite::Statement q(connection(store), "SELECT state, COUNT(*) FROM tasks GROUP BY state");
    std::map<std::string, long> out;
    while (q.executeStep()) out[q.getColumn(0).getString()] = q.getColumn(1).getInt64();
    return out;
  });
}

}  // namespace rondo::store
