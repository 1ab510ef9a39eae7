// archive_old_records: old finished tasks with their events, old events about no task and old
// traversals move to an archive database (SQLite) and leave the live store (backup.h), from an
// SQLite store (ATTACH) or a PostgreSQL one (read, copied, then deleted).
#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>
#include <SQLiteCpp/Transaction.h>
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "rondo/store/backup.h"
#include "db/dialect.h"
#include "migrations.h"
#include "store_access.h"
#include "write_tx.h"

namespace rondo::store {
namespace {

constexpr const char* kFinalStates = "('succeeded', 'failed', 'cancelled', 'preempted', 'dropped')";

// The live store's CREATE TABLE statements of the archived tables, made for the attached archive
// ("CREATE TABLE IF NOT EXISTS archive.events ..."): the archive has the same columns and keys.
std::vector<std::string> archive_schema(SQLite::Database& db) {
  std::vector<std::string> out;
  SQLite::Statement q(db,
                      "SELECT name, sql FROM main.sqlite_schema WHERE type = 'table' AND name IN "
                      "('tasks', 'events', 'traversals') ORDER BY name = 'tasks' DESC, name");
  while (q.executeStep()) {
    const std::string name = q.getColumn(0).getString();
    std::string sql = q.getColumn(1).getString();
    const std::string head = "CREATE TABLE " + name;
    if (sql.rfind(head, 0) != 0) throw std::runtime_error("unexpected schema of table " + name);
    out.push_back("CREATE TABLE IF NOT EXISTS archive." + name + sql.substr(head.size()));
  }
  return out;
}

// An archive made by an older build lacks the columns added to the live tables since (ALTER TABLE
// ADD COLUMN appends them, in the same order): they are added to it, NULL in its old rows, so that
// the rows copied below (SELECT *) line up.
void add_missing_archive_columns(SQLite::Database& db) {
  for (const char* table : {"tasks", "events", "traversals"}) {
    std::vector<std::string> have;
    {
      SQLite::Statement q(db, fmt::format("SELECT name FROM pragma_table_info('{}', 'archive')", table));
      while (q.executeStep()) have.push_back(q.getColumn(0).getString());
    }
    std::vector<std::string> added;
    {
      SQLite::Statement q(db, fmt::format("SELECT name, type FROM pragma_table_info('{}', 'main')", table));
      while (q.executeStep()) {
        const std::string name = q.getColumn(0).getString();
        if (std::find(have.begin(), have.end(), name) == have.end())
          added.push_back(fmt::format("ALTER TABLE archive.{} ADD COLUMN {} {}", table, name, q.getColumn(1).getString()));
      }
    }
    for (const std::string& sql : added) db.exec(sql);
  }
}

// An archive made before schema version 7 refuses events about the executive (its events table's
// subject CHECK): that table is made again from `create` (this build's "CREATE TABLE events (...)"),
// with its rows. `schema` is "archive." for an attached archive, "" for one opened on its own.
void widen_archive_subjects(SQLite::Database& db, const std::string& schema, const std::string& create) {
  const std::string sql =
      db.execAndGet(fmt::format("SELECT sql FROM {}sqlite_schema WHERE type = 'table' AND name = 'events'", schema))
          .getString();
  if (sql.find("'executive'") != std::string::npos) return;
  const std::string head = "CREATE TABLE events";
  if (create.rfind(head, 0) != 0) throw std::runtime_error("unexpected schema of table events");
  std::string names;
  {  // finished before the table is dropped (an open statement locks it)
    SQLite::Statement q(db, fmt::format("SELECT name FROM pragma_table_info('events', '{}')",
                                        schema.empty() ? "main" : schema.substr(0, schema.size() - 1)));
    while (q.executeStep()) names += (names.empty() ? "" : ", ") + q.getColumn(0).getString();
  }
  db.exec(
      fmt::format("ALTER TABLE {0}events RENAME TO events_v6; CREATE TABLE {0}events{1}; "
                  "INSERT INTO {0}events ({2}) SELECT {2} FROM {0}events_v6; DROP TABLE {0}events_v6",
                  schema, create.substr(head.size()), names));
}

// A table of the archive as this build's SQLite schema has it: its columns and their types.
struct ArchiveTable {
  std::string name;
  std::vector<std::pair<std::string, std::string>> columns;  // name, declared type
};

// Makes (or brings up to date) the archive's tables from a PostgreSQL store: SQLite's schema of this
// build is made in memory by the SQLite migrations, its CREATE TABLE texts become the archive's
// ("CREATE TABLE IF NOT EXISTS"), and an older archive gains the columns added since.
std::vector<ArchiveTable> prepare_archive(SQLite::Database& archive, const std::filesystem::path& file) {
  SQLite::Database model(":memory:", SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
  if (Status made = migrate(model, sqlite_migrations(), file); !made)
    throw std::runtime_error("making the archive's schema: " + made.error().message);
  std::vector<ArchiveTable> tables;
  for (const char* name : {"tasks", "events", "traversals"}) {
    ArchiveTable& t = tables.emplace_back(ArchiveTable{name, {}});
    std::string sql = model.execAndGet(fmt::format("SELECT sql FROM sqlite_schema WHERE type = 'table' AND name = '{}'",
                                                   name))
                          .getString();
    const std::string head = "CREATE TABLE " + t.name;
    if (sql.rfind(head, 0) != 0) throw std::runtime_error("unexpected schema of table " + t.name);
    archive.exec("CREATE TABLE IF NOT EXISTS " + t.name + sql.substr(head.size()));
    if (t.name == "events") widen_archive_subjects(archive, "", sql);
    SQLite::Statement columns(model, fmt::format("SELECT name, type FROM pragma_table_info('{}')", name));
    while (columns.executeStep()) t.columns.emplace_back(columns.getColumn(0).getString(), columns.getColumn(1).getString());
    std::vector<std::string> have;
    SQLite::Statement existing(archive, fmt::format("SELECT name FROM pragma_table_info('{}')", name));
    while (existing.executeStep()) have.push_back(existing.getColumn(0).getString());
    for (const auto& [column, type] : t.columns)
      if (std::find(have.begin(), have.end(), column) == have.end())
        archive.exec(fmt::format("ALTER TABLE {} ADD COLUMN {} {}", name, column, type));
  }
  return tables;
}

// Copies the rows of `table` that `where` selects from PostgreSQL into the archive; a row already
// there (an interrupted run's) is kept.
void copy_rows(db::Connection& pg, SQLite::Database& archive, const ArchiveTable& table, const std::string& where) {
  std::string names, marks;
  for (const auto& [column, type] : table.columns) {
    names += (names.empty() ? "" : ", ") + column;
    marks += marks.empty() ? "?" : ", ?";
  }
  auto rows = pg.query(fmt::format("SELECT {} FROM {} WHERE {}", names, table.name, where));
  SQLite::Statement insert(archive, fmt::format("INSERT OR IGNORE INTO {} ({}) VALUES ({})", table.name, names, marks));
  while (rows->next()) {
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
      const int column = static_cast<int>(i);
      const std::string& type = table.columns[i].second;
      if (rows->is_null(column))
        insert.bind(column + 1);
      else if (type == "INTEGER")
        insert.bind(column + 1, static_cast<std::int64_t>(rows->int64(column)));
      else if (type == "REAL")
        insert.bind(column + 1, rows->real(column));
      else
        insert.bind(column + 1, rows->text(column));
    }
    insert.exec();
    insert.reset();
    insert.clearBindings();
  }
}

// archive_old_records on a PostgreSQL store: the rows to move are read and deleted in one
// repeatable-read transaction, and the archive is committed between the two, so an interruption
// leaves them in both (a rerun copies nothing twice and deletes them) or in the store only.
Result<ArchiveReport> archive_from_postgres(Store& store, Duration age, const std::filesystem::path& file) {
  return guarded(store, "archiving old records", [&]() -> Result<ArchiveReport> {
    db::Connection& pg = connection(store);
    ArchiveReport report;
    WriteTx tx(pg);
    pg.exec_script("SET TRANSACTION ISOLATION LEVEL REPEATABLE READ");
    const std::optional<std::int64_t> latest = db::query_int64(
        pg,
        "SELECT MAX(t) FROM (SELECT MAX(time_ms) AS t FROM events UNION ALL "
        "SELECT MAX(start_ms + duration_ms) FROM traversals UNION ALL SELECT MAX(updated_ms) FROM tasks) AS latest");
    if (!latest) return report;  // an empty store: nothing to archive
    report.latest = time_from_db(*latest);
    report.cut = *report.latest - age;
    const std::int64_t cut = to_db(*report.cut);
    const std::string old_tasks =
        fmt::format("SELECT id FROM tasks WHERE state IN {} AND updated_ms < {}", kFinalStates, cut);
    const std::string old_events = fmt::format("(task_id IS NULL AND time_ms < {0}) OR task_id IN ({1})", cut, old_tasks);
    const std::string old_traversals = fmt::format("start_ms < {}", cut);
    {
      SQLite::Database archive(file.string(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
      SQLite::Transaction archive_tx(archive, SQLite::TransactionBehavior::IMMEDIATE);
      const std::vector<ArchiveTable> tables = prepare_archive(archive, file);
      copy_rows(pg, archive, tables[0], "id IN (" + old_tasks + ")");
      copy_rows(pg, archive, tables[1], old_events);
      copy_rows(pg, archive, tables[2], old_traversals);
      archive_tx.commit();
    }
    // The event log is append-only (a trigger refuses deletes); retention is the one exception,
    // inside this transaction.
    pg.exec_script("ALTER TABLE events DISABLE TRIGGER events_no_delete");
    report.events = pg.exec("DELETE FROM events WHERE " + old_events);
    pg.exec_script("ALTER TABLE events ENABLE TRIGGER events_no_delete");
    report.tasks = pg.exec("DELETE FROM tasks WHERE id IN (" + old_tasks + ")");
    report.traversals = pg.exec("DELETE FROM traversals WHERE " + old_traversals);
    tx.commit();
    return report;
  });
}

}  // namespace

Result<ArchiveReport> archive_old_records(Store& store, Duration age, Duration learning_window,
                                          const std::filesystem::path& archive) {
  if (age < learning_window)
    return Error::invalid(fmt::format("the age {} h is shorter than the learning window {} h: the nightly refit "
                                      "would lose the traversals it reads",
                                      std::chrono::duration_cast<hours>(age).count(),
                                      std::chrono::duration_cast<hours>(learning_window).count()));
  if (store.is_postgres()) return archive_from_postgres(store, age, archive);
  SQLite::Database* sqlite = sqlite_database(store);
  if (sqlite == nullptr) return Error::internal(fmt::format("{}: no SQLite connection", store.name()));
  return guarded(store, "archiving old records", [&]() -> Result<ArchiveReport> {
    SQLite::Database& db = *sqlite;
    ArchiveReport report;
    {  // every statement is finished before the DETACH below, which a pending one would block
      SQLite::Statement latest(db,
                               "SELECT MAX(t) FROM (SELECT MAX(time_ms) AS t FROM events UNION ALL "
                               "SELECT MAX(start_ms + duration_ms) FROM traversals UNION ALL "
                               "SELECT MAX(updated_ms) FROM tasks)");
      latest.executeStep();
      if (latest.isColumnNull(0)) return report;  // an empty store: nothing to archive
      report.latest = time_from_db(latest.getColumn(0).getInt64());
    }
    report.cut = *report.latest - age;
    const std::int64_t cut = to_db(*report.cut);

    // The live connection may not create files (OpenMode::kMustExist): the archive is created first.
    { SQLite::Database created(archive.string(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE); }
    {
      SQLite::Statement attach(db, "ATTACH DATABASE ? AS archive");
      attach.bind(1, archive.string());
      attach.exec();
    }
    struct Detach {
      SQLite::Database& db;
      ~Detach() {
        try {
          db.exec("DETACH DATABASE archive");
        } catch (const SQLite::Exception&) {  // the connection stays usable either way
        }
      }
    } detach{db};
    {
      SQLite::Transaction tx(db, SQLite::TransactionBehavior::IMMEDIATE);
      for (const std::string& create : archive_schema(db)) db.exec(create);
      add_missing_archive_columns(db);
      const std::string events_table =  // read (and its statement finished) before the archive's is made again
          db.execAndGet("SELECT sql FROM main.sqlite_schema WHERE type = 'table' AND name = 'events'").getString();
      widen_archive_subjects(db, "archive.", events_table);
      const std::string old_tasks =
          fmt::format("SELECT id FROM main.tasks WHERE state IN {} AND updated_ms < {}", kFinalStates, cut);
      const std::string old_events =
          fmt::format("(task_id IS NULL AND time_ms < {0}) OR task_id IN ({1})", cut, old_tasks);
      // The archive first (a row already there, from an interrupted run, is kept), then the deletes:
      // events before their tasks, as the foreign key wants.
      db.exec(fmt::format("INSERT OR IGNORE INTO archive.tasks SELECT * FROM main.tasks WHERE id IN ({})", old_tasks));
      db.exec(fmt::format("INSERT OR IGNORE INTO archive.events SELECT * FROM main.events WHERE {}", old_events));
      db.exec(fmt::format("INSERT OR IGNORE INTO archive.traversals SELECT * FROM main.traversals WHERE start_ms < {}", cut));
      // The event log is append-only (a trigger refuses deletes); retention is the one exception,
      // inside this transaction: the trigger is dropped and made again from its own text.
      const std::string no_delete =
          db.execAndGet("SELECT sql FROM main.sqlite_schema WHERE type = 'trigger' AND name = 'events_no_delete'")
              .getString();
      db.exec("DROP TRIGGER main.events_no_delete");
      report.events = db.exec(fmt::format("DELETE FROM main.events WHERE {}", old_events));
      db.exec(no_delete);
      report.tasks = db.exec(fmt::format("DELETE FROM main.tasks WHERE id IN ({})", old_tasks));
      report.traversals = db.exec(fmt::format("DELETE FROM main.traversals WHERE start_ms < {}", cut));
      tx.commit();
    }
    return report;
  });
}

}  // namespace rondo::store
