// The event log: an append-only record of everything that happened in the executive. Most events
// belong to a task (every state change with its outcome code and reason, a planned start that
// moved); others are about the robot (a fault, ready again, an observation that mattered), a
// request (refused, and why) or the schedule (made again, and why). Rows are never updated or
// deleted: there is no API for it and the schema's triggers refuse it. The sequence number gives
// the order of appends; a client that has seen up to seq N reads on with read_events(N).
//
//   Result<std::int64_t> seq = append_event(db, {.time = now, .task_id = "t1", .event = "failed",
//                                                .code = "navigation overrun", .reason = "..."});
//   append_event(db, {.time = now, .subject = Subject::kRobot, .about = "robot", .event = "fault",
//                     .code = "robot fault", .reason = "lost connection"});
//   Result<std::vector<Event>> newer = read_events(db, *seq);   // only those after seq
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/store.h"

namespace rondo::store {

// What an event is about. kExecutive: the executive process itself (a takeover names the
// instance that became active, in `about`, at the epoch the event records).
enum class Subject { kTask, kRobot, kRequest, kSchedule, kExecutive };
const char* to_string(Subject subject);
Result<Subject> parse_subject(std::string_view text);

struct Event {
  std::int64_t seq = 0;  // assigned by the store: increasing, never reused; ignored when appending
  Time time{};
  Subject subject = Subject::kTask;
  std::string task_id{};  // a stored task when subject is kTask; empty otherwise
  std::string about{};    // for other subjects: the robot, the request's id; may be empty
  std::string event{};    // a state name for state changes ("queued", "failed", ...) or another event
  std::string code{};     // the outcome code (docs/executor.md), e.g. "too late"; empty when none
  std::string reason{};   // why, for people; may be empty
  // The robot it is about: when appended empty, a robot event's `about` or a task event's task's
  // robot (tasks.robot), else none (''); a request's or the schedule's event has none.
  std::string robot{};

  bool operator==(const Event&) const = default;
};

// Appends `event` in its own committed transaction and returns its sequence number.
// Errors: kNotFound (a task event whose task_id is not stored), kInvalidInput (a task event
// without a task id, or another subject with one), kStorage.
Result<std::int64_t> append_event(Store& store, const Event& event);

// The events with seq > after_seq, in append order; at most `limit` of them (0: all).
Result<std::vector<Event>> read_events(const Store& store, std::int64_t after_seq = 0, std::int64_t limit = 0);
// The events of one task, in append order (empty for an unknown task).
Result<std::vector<Event>> read_events_of(const Store& store, std::string_view task_id);
// The sequence number of the latest event (0 for an empty log), and its time.
struct LogEnd {
  std::int64_t seq = 0;
  Time time{};
};
Result<LogEnd> log_end(const Store& store);

}  // namespace rondo::store
