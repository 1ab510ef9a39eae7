#include "rondo/store/events.h"

#include <SQLiteCpp/Statement.h>
#include "write_tx.h"

#include <fmt/format.h>

#include <array>
#include <utility>

#include "event_rows.h"
#include "sqlite_error.h"

namespace rondo::store {
namespace {

constexpr std::array<std::pair<Subject, const char*>, 4> kSubjects{
    {{Subject::kTask, "task"}, {Subject::kRobot, "robot"}, {Subject::kRequest, "request"}, {Subject::kSchedule, "schedule"}}};

constexpr const char* kSelect =
    "SELECT seq, time_ms, subject, COALESCE(task_id, ''), about, event, code, reason, robot FROM events";

Event event_from_row(const SQLite::Statement& row) {
  Event e;
  e.seq = row.getColumn(0).getInt64();
  e.time = time_from_db(row.getColumn(1).getInt64());
  const auto subject = parse_subject(row.getColumn(2).getString());  // the schema checks it
  e.subject = subject ? *subject : Subject::kTask;
  e.task_id = row.getColumn(3).getString();
  e.about = row.getColumn(4).getString();
  e.event = row.getColumn(5).getString();
  e.code = row.getColumn(6).getString();
  e.reason = row.getColumn(7).getString();
  e.robot = row.getColumn(8).getString();
  return e;
}

std::vector<Event> read_all(SQLite::Statement& query) {
  std::vector<Event> out;
  while (query.executeStep()) out.push_back(event_from_row(query));
  return out;
}

}  // namespace

const char* to_string(Subject subject) {
  for (const auto& [s, name] : kSubjects)
    if (s == subject) return name;
  return "task";
}

Result<Subject> parse_subject(std::string_view text) {
  for (const auto& [s, name] : kSubjects)
    if (text == name) return s;
  return Error::invalid(fmt::format("unknown event subject '{}' (task, robot, request or schedule)", text));
}

std::int64_t insert_event_row(SQLite::Database& db, const Event& e) {
  // The robot: the event's own; else a robot event's subject, or a task event's task's robot.
  SQLite::Statement insert(db,
                           "INSERT INTO events (time_ms, subject, task_id, about, event, code, reason, robot) "
                           "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, COALESCE(NULLIF(?8, ''), "
                           "(SELECT robot FROM tasks WHERE id = ?3), ''))");
  insert.bind(1, to_db(e.time));
  insert.bind(2, to_string(e.subject));
  if (e.subject == Subject::kTask)
    insert.bind(3, e.task_id);
  else
    insert.bind(3);  // NULL
  insert.bind(4, e.about);
  insert.bind(5, e.event);
  insert.bind(6, e.code);
  insert.bind(7, e.reason);
  insert.bind(8, !e.robot.empty() || e.subject != Subject::kRobot ? e.robot : e.about);
  insert.exec();
  return db.getLastInsertRowid();
}

bool task_exists(SQLite::Database& db, std::string_view id) {
  SQLite::Statement query(db, "SELECT 1 FROM tasks WHERE id = ?");
  query.bind(1, std::string(id));
  return query.executeStep();
}

Result<std::int64_t> append_event(Store& store, const Event& event) {
  if ((event.subject == Subject::kTask) == event.task_id.empty()) {
    return Error::invalid(fmt::format("{}: event '{}': a task event names its task, and only a task event does",
                                      store.file().string(), event.event));
  }
  return guarded(store, "appending an event", [&]() -> Result<std::int64_t> {
    SQLite::Database& db = connection(store);
    WriteTx tx(db);
    if (event.subject == Subject::kTask && !task_exists(db, event.task_id)) {
      return Error::not_found(
          fmt::format("{}: no task '{}' for event '{}'", store.file().string(), event.task_id, event.event));
    }
    const std::int64_t seq = insert_event_row(db, event);
    tx.commit();
    return seq;
  });
}

Result<std::vector<Event>> read_events(const Store& store, std::int64_t after_seq, std::int64_t limit) {
  return guarded(store, "reading events", [&]() -> Result<std::vector<Event>> {
    SQLite::Statement query(connection(store), std::string(kSelect) + " WHERE seq > ? ORDER BY seq LIMIT ?");
    query.bind(1, after_seq);
    query.bind(2, limit > 0 ? limit : std::int64_t{-1});
    return read_all(query);
  });
}

Result<std::vector<Event>> read_events_of(const Store& store, std::string_view task_id) {
  return guarded(store, "reading events", [&]() -> Result<std::vector<Event>> {
    SQLite::Statement query(connection(store), std::string(kSelect) + " WHERE task_id = ? ORDER BY seq");
    query.bind(1, std::string(task_id));
    return read_all(query);
  });
}

Result<LogEnd> log_end(const Store& store) {
  return guarded(store, "reading the end of the event log", [&]() -> Result<LogEnd> {
    SQLite::Statement query(connection(store), "SELECT seq, time_ms FROM events ORDER BY seq DESC LIMIT 1");
    if (!query.executeStep()) return LogEnd{};
    return LogEnd{query.getColumn(0).getInt64(), time_from_db(query.getColumn(1).getInt64())};
  });
}

}  // namespace rondo::store
