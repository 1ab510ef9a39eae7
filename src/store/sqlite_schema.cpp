// The schema history of an SQLite store (migrations.h). PostgreSQL's, step for step: pg_schema.cpp.
#include "migrations.h"

namespace rondo::store {
namespace {

// Version 1: the first schema. Times are integer ms since the Unix epoch (UTC), durations integer
// ms. STRICT tables make SQLite enforce the declared column types.
constexpr std::string_view kSchemaV1 = R"sql(
CREATE TABLE tasks (
  id          TEXT    PRIMARY KEY NOT NULL,
  state       TEXT    NOT NULL,
  task_json   TEXT    NOT NULL CHECK (json_valid(task_json)),
  created_ms  INTEGER NOT NULL,
  updated_ms  INTEGER NOT NULL
) STRICT;
CREATE INDEX tasks_by_state ON tasks (state);

CREATE TABLE task_events (
  seq      INTEGER PRIMARY KEY AUTOINCREMENT,
  time_ms  INTEGER NOT NULL,
  task_id  TEXT    NOT NULL REFERENCES tasks (id),
  event    TEXT    NOT NULL,
  reason   TEXT    NOT NULL DEFAULT ''
) STRICT;
CREATE INDEX task_events_by_task ON task_events (task_id, seq);
CREATE TRIGGER task_events_no_update BEFORE UPDATE ON task_events
BEGIN SELECT RAISE(ABORT, 'task_events is append-only'); END;
CREATE TRIGGER task_events_no_delete BEFORE DELETE ON task_events
BEGIN SELECT RAISE(ABORT, 'task_events is append-only'); END;

CREATE TABLE traversals (
  id           INTEGER PRIMARY KEY,
  edge_id      TEXT    NOT NULL,
  from_node    TEXT    NOT NULL,
  to_node      TEXT    NOT NULL,
  start_ms     INTEGER NOT NULL,
  duration_ms  INTEGER NOT NULL CHECK (duration_ms >= 0),
  success      INTEGER NOT NULL CHECK (success IN (0, 1)),
  origin       TEXT    UNIQUE
) STRICT;
CREATE INDEX traversals_by_edge_start ON traversals (edge_id, start_ms);
CREATE INDEX traversals_by_start ON traversals (start_ms);

CREATE TABLE observations (
  id       INTEGER PRIMARY KEY,
  what     TEXT    NOT NULL,
  place    TEXT    NOT NULL,
  time_ms  INTEGER NOT NULL,
  value    REAL    NOT NULL,
  note     TEXT
) STRICT;
CREATE INDEX observations_by_what_place_time ON observations (what, place, time_ms);
)sql";

// Version 2 (the durable executor): the task event log becomes the event log of the whole
// executive. Events carry an outcome code and a subject (task, robot, request, schedule), and only
// task events name a task; old rows keep their sequence numbers, with subject 'task' and no code.
// Tasks record who added them and how far they got (restart), the robot its last known state
// (restore), and the store the identity of what it holds (a run's deployment, seed and length).
constexpr std::string_view kSchemaV2 = R"sql(
CREATE TABLE events (
  seq      INTEGER PRIMARY KEY AUTOINCREMENT,
  time_ms  INTEGER NOT NULL,
  subject  TEXT    NOT NULL CHECK (subject IN ('task', 'robot', 'request', 'schedule')),
  task_id  TEXT    REFERENCES tasks (id),
  about    TEXT    NOT NULL DEFAULT '',
  event    TEXT    NOT NULL,
  code     TEXT    NOT NULL DEFAULT '',
  reason   TEXT    NOT NULL DEFAULT '',
  CHECK ((subject = 'task') = (task_id IS NOT NULL))
) STRICT;
INSERT INTO events (seq, time_ms, subject, task_id, event, reason)
  SELECT seq, time_ms, 'task', task_id, event, reason FROM task_events ORDER BY seq;
DROP TRIGGER task_events_no_update;
DROP TRIGGER task_events_no_delete;
DROP INDEX task_events_by_task;
DROP TABLE task_events;
CREATE INDEX events_by_task ON events (task_id, seq) WHERE task_id IS NOT NULL;
CREATE TRIGGER events_no_update BEFORE UPDATE ON events
BEGIN SELECT RAISE(ABORT, 'events is append-only'); END;
CREATE TRIGGER events_no_delete BEFORE DELETE ON events
BEGIN SELECT RAISE(ABORT, 'events is append-only'); END;

ALTER TABLE tasks ADD COLUMN source TEXT NOT NULL DEFAULT '';
ALTER TABLE tasks ADD COLUMN progress_json TEXT CHECK (progress_json IS NULL OR json_valid(progress_json));

CREATE TABLE robot_state (
  robot       TEXT    PRIMARY KEY NOT NULL,
  node        TEXT    NOT NULL,
  x           REAL,
  y           REAL,
  yaw         REAL,
  battery     REAL    CHECK (battery IS NULL OR (battery >= 0 AND battery <= 1)),
  on_board    TEXT    NOT NULL DEFAULT '[]' CHECK (json_valid(on_board)),
  fault       TEXT,
  updated_ms  INTEGER NOT NULL
) STRICT;

CREATE TABLE meta (
  key    TEXT PRIMARY KEY NOT NULL,
  value  TEXT NOT NULL
) STRICT;
)sql";

// Version 3 (commands in words, `rondo task add --data`): the durable queue of requests that
// another process (the CLI) writes and the running executive takes. A request is taken once:
// taken_ms is set in the same transaction that stores its tasks (or its rejection's event).
constexpr std::string_view kSchemaV3 = R"sql(
CREATE TABLE requests (
  id         INTEGER PRIMARY KEY AUTOINCREMENT,
  queued_ms  INTEGER NOT NULL,
  source     TEXT    NOT NULL DEFAULT '',
  sentence   TEXT    NOT NULL DEFAULT '',
  body_json  TEXT    NOT NULL CHECK (json_valid(body_json)),
  taken_ms   INTEGER,
  outcome    TEXT    NOT NULL DEFAULT '',
  CHECK ((taken_ms IS NULL) = (outcome = ''))
) STRICT;
CREATE INDEX requests_waiting ON requests (id) WHERE taken_ms IS NULL;
)sql";

// Version 4 (`rondo serve`: finished tasks leave memory and are read from the store): when the task
// was planned to start and end, as the executor had it at its latest state change, so a finished
// task is shown planned against actual. Old rows have none (NULL).
constexpr std::string_view kSchemaV4 = R"sql(
ALTER TABLE tasks ADD COLUMN planned_start_ms INTEGER;
ALTER TABLE tasks ADD COLUMN planned_end_ms INTEGER;
)sql";

// Version 5 (a fleet, issue 38): every task, event, traversal and observation names its robot.
// tasks.robot is the robot the task is allocated to (NULL: none); in events, traversals and
// observations '' is none (a request's or the schedule's event, an imported traversal). A store
// of a single-robot version held one robot: its rows get that robot's name (robot_state's only
// row, else the default name 'robot'); imported traversals (with an origin) stay ''.
constexpr std::string_view kSchemaV5 = R"sql(
ALTER TABLE tasks ADD COLUMN robot TEXT;
ALTER TABLE events ADD COLUMN robot TEXT NOT NULL DEFAULT '';
ALTER TABLE traversals ADD COLUMN robot TEXT NOT NULL DEFAULT '';
ALTER TABLE observations ADD COLUMN robot TEXT NOT NULL DEFAULT '';
CREATE TEMP TABLE v5_single_robot AS
  SELECT COALESCE((SELECT robot FROM robot_state WHERE (SELECT COUNT(*) FROM robot_state) = 1), 'robot') AS name;
UPDATE tasks SET robot = (SELECT name FROM v5_single_robot);
UPDATE traversals SET robot = (SELECT name FROM v5_single_robot) WHERE origin IS NULL;
UPDATE observations SET robot = (SELECT name FROM v5_single_robot);
DROP TRIGGER events_no_update;
UPDATE events SET robot = (SELECT name FROM v5_single_robot) WHERE subject IN ('task', 'robot');
CREATE TRIGGER events_no_update BEFORE UPDATE ON events
BEGIN SELECT RAISE(ABORT, 'events is append-only'); END;
DROP TABLE v5_single_robot;
CREATE INDEX traversals_by_robot_start ON traversals (robot, start_ms);
)sql";

// The lease (pg_schema.cpp, version 6) in meaning: an SQLite store is used by one executive
// process, so its epoch stays 0 and nothing checks it; the table and the column keep the two
// schemas alike.
constexpr std::string_view kSchemaV6 = R"sql(
CREATE TABLE lease (
  id          INTEGER PRIMARY KEY NOT NULL CHECK (id = 1),
  epoch       INTEGER NOT NULL,
  holder      TEXT    NOT NULL DEFAULT '',
  taken_ms    INTEGER NOT NULL DEFAULT 0,
  renewed_ms  INTEGER NOT NULL DEFAULT 0
) STRICT;
INSERT INTO lease (id, epoch) VALUES (1, 0);
ALTER TABLE events ADD COLUMN epoch INTEGER NOT NULL DEFAULT 0;
)sql";

// Events about the executive process itself (a takeover names the instance that became active).
// SQLite cannot change a CHECK in place: the events table is made again, with every row, its
// sequence numbers (and AUTOINCREMENT's high-water mark) and its indexes and append-only triggers.
constexpr std::string_view kSchemaV7 = R"sql(
ALTER TABLE events RENAME TO events_v6;
CREATE TABLE events (
  seq      INTEGER PRIMARY KEY AUTOINCREMENT,
  time_ms  INTEGER NOT NULL,
  subject  TEXT    NOT NULL CHECK (subject IN ('task', 'robot', 'request', 'schedule', 'executive')),
  task_id  TEXT    REFERENCES tasks (id),
  about    TEXT    NOT NULL DEFAULT '',
  event    TEXT    NOT NULL,
  code     TEXT    NOT NULL DEFAULT '',
  reason   TEXT    NOT NULL DEFAULT '',
  robot    TEXT    NOT NULL DEFAULT '',
  epoch    INTEGER NOT NULL DEFAULT 0,
  CHECK ((subject = 'task') = (task_id IS NOT NULL))
) STRICT;
INSERT INTO events (seq, time_ms, subject, task_id, about, event, code, reason, robot, epoch)
  SELECT seq, time_ms, subject, task_id, about, event, code, reason, robot, epoch FROM events_v6 ORDER BY seq;
DELETE FROM sqlite_sequence WHERE name = 'events';
INSERT INTO sqlite_sequence (name, seq) SELECT 'events', seq FROM sqlite_sequence WHERE name = 'events_v6';
DROP TABLE events_v6;
CREATE INDEX events_by_task ON events (task_id, seq) WHERE task_id IS NOT NULL;
CREATE TRIGGER events_no_update BEFORE UPDATE ON events
BEGIN SELECT RAISE(ABORT, 'events is append-only'); END;
CREATE TRIGGER events_no_delete BEFORE DELETE ON events
BEGIN SELECT RAISE(ABORT, 'events is append-only'); END;
)sql";

// A robot's wait for other robots before a traversal (docs/traffic.md), apart from its duration.
constexpr std::string_view kSchemaV8 = R"sql(
ALTER TABLE traversals ADD COLUMN waited_ms INTEGER NOT NULL DEFAULT 0;
)sql";

constexpr Migration kSqliteMigrations[] = {
    {1, "tasks, task_events (append-only), traversals, observations", kSchemaV1},
    {2, "events with subject and outcome code; task source and progress; robot_state; meta", kSchemaV2},
    {3, "requests: the queue of requests written by other processes (rondo task add --data)", kSchemaV3},
    {4, "tasks: planned start and end", kSchemaV4},
    {5, "the robot of every task, event, traversal and observation", kSchemaV5},
    {6, "the lease of the active executive (its epoch) and the epoch of every event", kSchemaV6},
    {7, "events about the executive process (subject executive: a takeover)", kSchemaV7},
    {8, "traversals: the wait for other robots before each attempt", kSchemaV8},
};

}  // namespace

std::span<const Migration> sqlite_migrations() {
  return kSqliteMigrations;
}

}  // namespace rondo::store
