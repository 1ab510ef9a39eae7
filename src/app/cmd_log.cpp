// `rondo log ...`: the traversal log in the SQLite store (import robot logs, summarise them).
#include <fmt/format.h>

#include <charconv>
#include <memory>
#include <string>

#include "commands.h"
#include "rondo/core/document.h"
#include "rondo/core/utf8.h"
#include "rondo/exec/executor_types.h"
#include "rondo/store/backup.h"
#include "rondo/store/store.h"
#include "rondo/store/traversal_stats.h"
#include "rondo/store/witham_import.h"

namespace rondo::app {
namespace {

struct ImportArgs {
  std::string witham_dir;
  std::string db;
  bool json = false;
};

struct StatsArgs {
  std::string db;
  bool json = false;
};

struct MigrateArgs {
  std::string db;
};

struct ArchiveArgs {
  std::string db;
  std::string older_than;
  std::string out;
};

// "90d", "2160h", "1h30m": days, or what parse_duration reads (up to kMaxSeconds either way).
Result<Duration> parse_age(const std::string& text) {
  if (!text.empty() && text.back() == 'd') {
    constexpr auto kMaxDays = static_cast<std::int64_t>(kMaxSeconds / 86400);
    std::int64_t n = -1;
    const auto [end, err] = std::from_chars(text.data(), text.data() + text.size() - 1, n);
    if (err == std::errc{} && end == text.data() + text.size() - 1 && n >= 0 && n <= kMaxDays)
      return Duration{hours(24 * n)};
    return Error::invalid(
        fmt::format("--older-than: '{}' is not a number of days from 0 to {}", quote_for_message(text), kMaxDays));
  }
  auto d = parse_duration(text);
  if (!d) return Error::invalid(fmt::format("--older-than: {}", d.error().message));
  return *d;
}

void run_archive(const ArchiveArgs& args, CommandContext& ctx) {
  auto age = parse_age(args.older_than);
  if (!age) return (void)fail(ctx, age.error());
  auto db = store::Store::open_named(args.db, {.mode = store::OpenMode::kMustExist});
  if (!db) return (void)fail(ctx, db.error());
  // The executor's learning window: the nightly refit reads the traversals of its last 14 days.
  const Duration window = exec::ExecutorOptions{}.refit_window.value_or(Duration{0});
  auto report = store::archive_old_records(*db, *age, window, args.out);
  if (!report) return (void)fail(ctx, report.error());
  if (!report->cut) {
    ctx.out << fmt::format("{}: the store is empty; nothing archived\n", printable_path(args.db));
    return;
  }
  ctx.out << fmt::format("{}: before {} (latest record {}): {} finished tasks, {} events and {} traversals moved to {}\n",
                         printable_path(args.db), format_time(*report->cut), format_time(*report->latest),
                         report->tasks, report->events, report->traversals, printable_path(args.out));
}

void run_import(const ImportArgs& args, CommandContext& ctx) {
  auto db = store::Store::open_named(args.db, {.mode = store::OpenMode::kCreateIfMissing});
  if (!db) {
    fail(ctx, db.error());
    return;
  }
  auto report = store::import_witham_logs(*db, args.witham_dir);
  if (!report) {
    fail(ctx, report.error());
    return;
  }
  if (args.json) {
    Json j;
    j["db"] = printable_path(args.db);
    j["source"] = printable_path(args.witham_dir);
    j["attempts"] = report->attempts;
    j["successes"] = report->successes;
    j["edges"] = report->edges;
    j["inserted"] = report->stored.inserted;
    j["already_present"] = report->stored.already_present;
    ctx.out << j.dump(2) << '\n';
    return;
  }
  ctx.out << fmt::format(
      "imported {} into {}\n"
      "  attempts:        {}\n"
      "  successes:       {}\n"
      "  edges:           {}\n"
      "  inserted:        {}\n"
      "  already present: {}\n",
      printable_path(args.witham_dir), printable_path(args.db), report->attempts, report->successes, report->edges,
      report->stored.inserted, report->stored.already_present);
}

Json stats_json(const std::string& db_file, const store::TraversalSummary& summary) {
  Json j;
  j["db"] = printable_path(db_file);
  j["attempts"] = summary.attempts;
  j["successes"] = summary.successes;
  j["edges"] = summary.edges.size();
  Json per_edge = Json::array();
  for (const store::EdgeSummary& e : summary.edges) {
    Json row;
    row["edge"] = e.edge_id;
    row["from"] = e.from;
    row["to"] = e.to;
    row["attempts"] = e.attempts;
    row["successes"] = e.successes;
    row["first"] = format_time(e.first_start);
    row["last"] = format_time(e.last_start);
    row["mean_success_duration_s"] =
        e.mean_success_duration ? Json(to_seconds(*e.mean_success_duration)) : Json(nullptr);
    per_edge.push_back(std::move(row));
  }
  j["per_edge"] = std::move(per_edge);
  return j;
}

void print_stats_table(std::ostream& out, const store::TraversalSummary& summary) {
  constexpr const char* kRow = "{:<28} {:>8} {:>9} {:>8}  {:<20}  {:<20}\n";
  out << fmt::format(kRow, "edge", "attempts", "successes", "mean ok", "first", "last");
  for (const store::EdgeSummary& e : summary.edges) {
    const std::string mean =
        e.mean_success_duration ? fmt::format("{:.1f}s", to_seconds(*e.mean_success_duration)) : "-";
    out << fmt::format(kRow, e.edge_id, e.attempts, e.successes, mean, format_time(e.first_start),
                       format_time(e.last_start));
  }
  out << fmt::format("{:<28} {:>8} {:>9}\n", fmt::format("total ({} edges)", summary.edges.size()), summary.attempts,
                     summary.successes);
}

void run_stats(const StatsArgs& args, CommandContext& ctx) {
  // A read command never writes: a mistyped path is an error, not an empty store, and an older
  // schema is refused rather than migrated.
  auto db = store::Store::open_named(args.db, {.mode = store::OpenMode::kReadOnly});
  if (!db) {
    fail(ctx, db.error());
    return;
  }
  auto summary = store::summarize_traversals(*db);
  if (!summary) {
    fail(ctx, summary.error());
    return;
  }
  if (args.json) {
    // A store written before import checked names may hold an edge id that is not UTF-8: it is
    // shown with U+FFFD in its place rather than failing the whole report.
    ctx.out << stats_json(args.db, *summary).dump(2, ' ', false, Json::error_handler_t::replace) << '\n';
  } else {
    print_stats_table(ctx.out, *summary);
  }
}

void run_migrate(const MigrateArgs& args, CommandContext& ctx) {
  auto before = store::Store::open_named(args.db, {.mode = store::OpenMode::kReadOnly});
  const bool current = before.ok();
  before = Error::internal("closed");  // close the read-only connection before writing
  auto db = store::Store::open_named(args.db, {.mode = store::OpenMode::kMustExist});
  if (!db) {
    fail(ctx, db.error());
    return;
  }
  ctx.out << fmt::format("{}: schema version {}{}\n", printable_path(args.db), store::Store::latest_schema_version(),
                         current ? " (already current)" : "");
}

}  // namespace

void add_log_commands(CLI::App& root, CommandContext& ctx) {
  CLI::App* log = root.add_subcommand("log", "The traversal log in the rondo database: import robot logs, summarise");
  log->require_subcommand(1);

  auto import_args = std::make_shared<ImportArgs>();
  CLI::App* import_cmd = log->add_subcommand(
      "import", "Import robot logs into the database (atomic; running it again adds only what is missing)");
  import_cmd->add_option("--witham", import_args->witham_dir, "Folder of Witham Wharf <From>_<To>.data edge logs")
      ->required();
  import_cmd->add_option("--db", import_args->db, "The store: an SQLite file (created if missing) or a postgresql:// URL")->required();
  import_cmd->add_flag("--json", import_args->json, "Print the import report as JSON");
  import_cmd->callback([import_args, &ctx] { run_import(*import_args, ctx); });

  auto stats_args = std::make_shared<StatsArgs>();
  CLI::App* stats = log->add_subcommand("stats", "Per-edge counts of the traversal log");
  stats->add_option("--db", stats_args->db, "The store: an SQLite file (must exist) or a postgresql:// URL")->required();
  stats->add_flag("--json", stats_args->json, "Print JSON: totals 'attempts', 'successes', 'edges' and 'per_edge'");
  stats->callback([stats_args, &ctx] { run_stats(*stats_args, ctx); });

  auto migrate_args = std::make_shared<MigrateArgs>();
  CLI::App* migrate = log->add_subcommand(
      "migrate", "Bring a database to this rondo's schema (the read-only commands refuse an older one)");
  migrate->add_option("--db", migrate_args->db, "The store: an SQLite file (must exist) or a postgresql:// URL")->required();
  migrate->callback([migrate_args, &ctx] { run_migrate(*migrate_args, ctx); });

  auto archive_args = std::make_shared<ArchiveArgs>();
  CLI::App* archive = log->add_subcommand(
      "archive", "Move old events, traversals and finished tasks to an archive database (retention)");
  archive->add_option("--db", archive_args->db, "The store: an SQLite file (must exist; may be in use) or a postgresql:// URL")->required();
  archive->add_option("--older-than", archive_args->older_than,
                      "Age counted back from the store's latest record: 90d, 2160h (at least the 14-day learning window)")
      ->required();
  archive->add_option("--out", archive_args->out, "The archive database (created, or added to)")->required();
  archive->callback([archive_args, &ctx] { run_archive(*archive_args, ctx); });
}

}  // namespace rondo::app
