#include "rondo/store/events.h"


#include <fmt/format.h>

#include <array>
#include <limits>
#include <optional>
#include <utility>

#include "event_rows.h"
#include "store_access.h"
#include "write_tx.h"

namespace rondo::store {
namespace {

constexpr std::array<std::pair<Subject, const char*>, 5> kSubjects{{{Subject::kTask, "task"},
                                                                    {Subject::kRobot, "robot"},
                                                                    {Subject::kRequest, "request"},
                                                                    {Subject::kSchedule, "schedule"},
                                                                    {Subject::kExecutive, "executive"}}};

constexpr const char* kSelect =
    "SELECT seq, time_ms, subject, COALESCE(task_id, ''), about, event, code, reason, robot FROM events";

Event event_from_row(const db::Rows& row) {
  Event e;
  e.seq = row.int64(0);
  e.time = time_from_db(row.int64(1));
  const auto subject = parse_subject(row.text(2));  // the schema checks it
  e.subject = subject ? *subject : Subject::kTask;
  e.task_id = row.text(3);
  e.about = row.text(4);
  e.event = row.text(5);
  e.code = row.text(6);
  e.reason = row.text(7);
  e.robot = row.text(8);
  return e;
}

std::vector<Event> read_all(db::Rows& query) {
  std::vector<Event> out;
  while (query.next()) out.push_back(event_from_row(query));
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
  return Error::invalid(fmt::format("unknown event subject '{}' (task, robot, request, schedule or executive)", text));
}

std::optional<std::int64_t> insert_event_row(db::Connection& db, const Event& e) {
  // The robot: the event's own; else a robot event's subject, or a task event's task's robot.
  const std::string& robot = !e.robot.empty() || e.subject != Subject::kRobot ? e.robot : e.about;
  if (e.subject == Subject::kTask) {
    // Only if the task is stored, read with its robot in the same statement (one round trip).
    return db::query_int64(db,
                           "INSERT INTO events (time_ms, subject, task_id, about, event, code, reason, robot) "
                           "SELECT CAST($1 AS BIGINT), 'task', id, CAST($3 AS TEXT), CAST($4 AS TEXT), "
                           "CAST($5 AS TEXT), CAST($6 AS TEXT), COALESCE(NULLIF(CAST($7 AS TEXT), ''), robot, '') "
                           "FROM tasks WHERE id = $2 RETURNING seq",
                           {to_db(e.time), e.task_id, e.about, e.event, e.code, e.reason, robot});
  }
  const auto seq = db::query_int64(db,
                                   "INSERT INTO events (time_ms, subject, about, event, code, reason, robot) "
                                   "VALUES ($1, $2, $3, $4, $5, $6, $7) RETURNING seq",
                                   {to_db(e.time), to_string(e.subject), e.about, e.event, e.code, e.reason, robot});
  if (!seq) throw db::Failure(db::FailureKind::kStorage, "the event log gave no sequence number");
  return seq;
}

Result<std::int64_t> append_event(Store& store, const Event& event) {
  if ((event.subject == Subject::kTask) == event.task_id.empty()) {
    return Error::invalid(fmt::format("{}: event '{}': a task event names its task, and only a task event does",
                                      store.name(), event.event));
  }
  return guarded(store, "appending an event", [&]() -> Result<std::int64_t> {
    db::Connection& db = connection(store);
    WriteTx tx(db);
    const std::optional<std::int64_t> seq = insert_event_row(db, event);
    if (!seq)
      return Error::not_found(fmt::format("{}: no task '{}' for event '{}'", store.name(), event.task_id, event.event));
    tx.commit();
    return *seq;
  });
}

Result<std::vector<Event>> read_events(const Store& store, std::int64_t after_seq, std::int64_t limit) {
  return guarded(store, "reading events", [&]() -> Result<std::vector<Event>> {
    auto query = connection(store).query(std::string(kSelect) + " WHERE seq > $1 ORDER BY seq LIMIT $2",
                                         {after_seq, limit > 0 ? limit : std::numeric_limits<std::int64_t>::max()});
    return read_all(*query);
  });
}

Result<std::vector<Event>> read_events_of(const Store& store, std::string_view task_id) {
  return guarded(store, "reading events", [&]() -> Result<std::vector<Event>> {
    auto query = connection(store).query(std::string(kSelect) + " WHERE task_id = $1 ORDER BY seq", {task_id});
    return read_all(*query);
  });
}

Result<LogEnd> log_end(const Store& store) {
  return guarded(store, "reading the end of the event log", [&]() -> Result<LogEnd> {
    auto query = connection(store).query("SELECT seq, time_ms FROM events ORDER BY seq DESC LIMIT 1");
    if (!query->next()) return LogEnd{};
    return LogEnd{query->int64(0), time_from_db(query->int64(1))};
  });
}

}  // namespace rondo::store
