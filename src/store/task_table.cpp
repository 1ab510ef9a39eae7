#include "rondo/store/task_table.h"

#include <SQLiteCpp/Statement.h>
#include <SQLiteCpp/Transaction.h>

#include <fmt/format.h>

#include "event_rows.h"
#include "request_rows.h"
#include "sqlite_error.h"

namespace rondo::store {
namespace {

constexpr const char* kSelectTask =
    "SELECT id, state, task_json, created_ms, updated_ms, source, progress_json FROM tasks";

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
    SQLite::Transaction tx(db, SQLite::TransactionBehavior::IMMEDIATE);
    SQLite::Statement insert(db,
                             "INSERT INTO tasks (id, state, task_json, created_ms, updated_ms, source, progress_json) "
                             "VALUES (?, ?, ?, ?, ?, ?, ?) ON CONFLICT (id) DO NOTHING");
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

Status set_task_state(Store& store, std::string_view id, std::string_view state, Time at, std::string_view reason,
                      std::string_view code) {
  return guarded(store, fmt::format("changing the state of task '{}'", id), [&]() -> Status {
    SQLite::Database& db = connection(store);
    SQLite::Transaction tx(db, SQLite::TransactionBehavior::IMMEDIATE);
    SQLite::Statement update(db, "UPDATE tasks SET state = ?, updated_ms = ? WHERE id = ?");
    update.bind(1, std::string(state));
    update.bind(2, to_db(at));
    update.bind(3, std::string(id));
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

}  // namespace rondo::store
