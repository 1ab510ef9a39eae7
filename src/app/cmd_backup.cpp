// `rondo backup --data DIR FILE` (or --db STORE FILE): a consistent copy of a store, also while
// `rondo serve` runs on it (SQLite's online backup, or pg_dump for a PostgreSQL store;
// docs/operations.md).
#include <fmt/format.h>

#include <memory>
#include <string>

#include "commands.h"
#include "rondo/store/backup.h"
#include "rondo/store/store.h"

namespace rondo::app {
namespace {

struct BackupArgs {
  std::string data;
  std::string db;
  std::string file;
};

void run_backup(const BackupArgs& args, CommandContext& ctx) {
  if (args.data.empty() == args.db.empty())
    return (void)fail(ctx, Error::invalid("backup: give the data folder (--data DIR) or the store (--db FILE), one of them"));
  const std::string source = args.db.empty() ? (std::filesystem::path(args.data) / "rondo.sqlite").string() : args.db;
  // kMustExist: a mistyped folder is an error, not an empty store; an older schema is migrated
  // first, as `rondo serve` would on its next start.
  auto db = store::Store::open_named(source, {.mode = store::OpenMode::kMustExist});
  if (!db) return (void)fail(ctx, db.error());
  auto report = store::backup_store(*db, args.file);
  if (!report) return (void)fail(ctx, report.error());
  if (db->is_postgres())
    ctx.out << fmt::format("{}: backed up to {} (pg_dump custom format, {} bytes, read back by pg_restore --list)\n",
                           source, report->file.string(), report->bytes);
  else
    ctx.out << fmt::format("{}: backed up to {} ({} pages, {} bytes, integrity ok)\n", source, report->file.string(),
                           report->pages, report->bytes);
}

}  // namespace

void add_backup_commands(CLI::App& root, CommandContext& ctx) {
  auto args = std::make_shared<BackupArgs>();
  auto* backup = root.add_subcommand("backup", "Copy a store while it is in use (SQLite online backup), checked");
  backup->add_option("file", args->file, "The backup file to write (must not exist)")->required();
  backup->add_option("--data", args->data, "The data folder of `rondo serve` (holds rondo.sqlite)");
  backup->add_option("--db", args->db,
                     "The store itself, instead of --data: a file, or a postgresql:// URL (backed up with pg_dump)");
  backup->callback([args, &ctx] { run_backup(*args, ctx); });
}

}  // namespace rondo::app
