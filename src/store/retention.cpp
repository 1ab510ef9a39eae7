// archive_old_records: old finished tasks with their events, old events about no task and old
// traversals move to an archive database and leave the live store (backup.h).
#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>
#include <SQLiteCpp/Transaction.h>
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "rondo/store/backup.h"
#include "store_access.h"

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

}  // namespace

Result<ArchiveReport> archive_old_records(Store& store, Duration age, Duration learning_window,
                                          const std::filesystem::path& archive) {
  if (age < learning_window)
    return Error::invalid(fmt::format("the age {} h is shorter than the learning window {} h: the nightly refit "
                                      "would lose the traversals it reads",
                                      std::chrono::duration_cast<hours>(age).count(),
                                      std::chrono::duration_cast<hours>(learning_window).count()));
  SQLite::Database* sqlite = sqlite_database(store);
  if (sqlite == nullptr)
    return Error::unsupported(fmt::format("{}: archiving old records is built for SQLite stores only", store.name()));
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
