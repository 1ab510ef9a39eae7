#include "rondo/store/task_events.h"

#include <SQLiteCpp/Statement.h>
#include <SQLiteCpp/Transaction.h>

#include <fmt/format.h>

#include "event_rows.h"
#include "sqlite_error.h"

namespace rondo::store {
namespace {

TaskEvent event_from_row(const SQLite::Statement& row) {
  return TaskEvent{row.getColumn(0).getInt64(), time_from_db(row.getColumn(1).getInt64()), row.getColumn(2).getString(),
                   row.getColumn(3).getString(), row.getColumn(4).getString()};
}

std::vector<TaskEvent> read_all(SQLite::Statement& query) {
  std::vector<TaskEvent> out;
  while (query.executeStep()) out.push_back(event_from_row(query));
  return out;
}

}  // namespace

std::int64_t insert_event_row(SQLite::Database& db, Time at, std::string_view task_id, std::string_view event,
                              std::string_view reason) {
  SQLite::Statement insert(db, "INSERT INTO task_events (time_ms, task_id, event, reason) VALUES (?, ?, ?, ?)");
  insert.bind(1, to_db(at));
  insert.bind(2, std::string(task_id));
  insert.bind(3, std::string(event));
  insert.bind(4, std::string(reason));
  insert.exec();
  return db.getLastInsertRowid();
}

bool task_exists(SQLite::Database& db, std::string_view id) {
  SQLite::Statement query(db, "SELECT 1 FROM tasks WHERE id = ?");
  query.bind(1, std::string(id));
  return query.executeStep();
}

Result<std::int64_t> append_task_event(Store& store, const TaskEvent& event) {
  return guarded(store, "appending a task event", [&]() -> Result<std::int64_t> {
    SQLite::Database& db = connection(store);
    SQLite::Transaction tx(db, SQLite::TransactionBehavior::IMMEDIATE);
    if (!task_exists(db, event.task_id)) {
      return Error::not_found(
          fmt::format("{}: no task '{}' for event '{}'", store.file().string(), event.task_id, event.event));
    }
    const std::int64_t seq = insert_event_row(db, event.time, event.task_id, event.event, event.reason);
    tx.commit();
    return seq;
  });
}

Result<std::vector<TaskEvent>> read_task_events(const Store& store, std::int64_t after_seq) {
  return guarded(store, "reading task events", [&]() -> Result<std::vector<TaskEvent>> {
    SQLite::Statement query(connection(store),
                            "SELECT seq, time_ms, task_id, event, reason FROM task_events WHERE seq > ? ORDER BY seq");
    query.bind(1, after_seq);
    return read_all(query);
  });
}

Result<std::vector<TaskEvent>> read_task_events_of(const Store& store, std::string_view task_id) {
  return guarded(store, "reading task events", [&]() -> Result<std::vector<TaskEvent>> {
    SQLite::Statement query(
        connection(store),
        "SELECT seq, time_ms, task_id, event, reason FROM task_events WHERE task_id = ? ORDER BY seq");
    query.bind(1, std::string(task_id));
    return read_all(query);
  });
}

}  // namespace rondo::store
