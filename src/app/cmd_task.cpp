// `rondo task ...`: check task and routine files, show the tasks routines make, and read a
// command in words into tasks (docs/commands.md).
#include <chrono>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "commands.h"
#include "number_options.h"
#include "request_queue.h"
#include "rondo/core/task_codec.h"
#include "rondo/lang/command.h"
#include "rondo/ltl/task_formula.h"
#include "rondo/map/map_loader.h"
#include "time_parsing_cli.h"

namespace rondo::app {
namespace {

struct TaskOptions {
  std::string file;
  bool json = false;
  std::string from;
  int days = 7;
};

struct AddOptions {
  std::vector<std::string> words;  // the sentence, as one argument or as several
  std::string map;
  std::string places;
  std::string at;         // "now" for the sentence; default: the system clock
  std::string time_zone;  // default: the places file's time_zone
  std::string data;       // a deployment's folder (rondo run --out, rondo serve --data): queue it there
  std::string store;      // or a store by name: a postgresql:// URL (rondo serve --store)
  bool dry_run = false;
  bool json = false;
};

void print_tasks(const std::vector<Task>& tasks, const TimeZone& zone, std::ostream& out) {
  out << fmt::format("{:<36} {:<26} {:<26} {:>8} {:>4}  {}\n", "id", "release", "deadline", "duration", "prio",
                     "start");
  for (const auto& t : tasks) {
    out << fmt::format("{:<36} {:<26} {:<26} {:>8} {:>4}  {}\n", t.id,
                       t.window ? zone.format_local(t.window->release) : "now",
                       t.window ? zone.format_local(t.window->deadline) : "-", format_duration(t.duration), t.priority,
                       t.has_spec()           ? "spec: " + t.spec
                       : t.start_node.empty() ? "-"
                                              : t.start_node);
  }
}

// Without a map, a task's formula is checked for the fragment and its automaton's size.
PlaceCheck formula_check() {
  return {.known = {}, .map_name = {}, .spec = [](std::string_view f) { return ltl::check_task_formula(f); }};
}

void check(const TaskOptions& o, CommandContext& ctx) {
  const PlaceCheck formulas = formula_check();
  auto file = load_task_file(o.file, &formulas);
  if (!file) {
    fail(ctx, file.error());
    return;
  }
  if (o.json) {
    Json j{{"file", o.file}, {"valid", true}, {"tasks", file->tasks.size()}, {"routines", file->routines.size()}};
    if (file->zone) j["timezone"] = file->zone->name();
    ctx.out << j.dump(2) << '\n';
    return;
  }
  ctx.out << fmt::format("{}: ok: {} task(s), {} routine(s){}\n", o.file, file->tasks.size(), file->routines.size(),
                         file->zone ? ", time zone " + file->zone->name() : std::string());
}

// Lists the tasks of a file and those its routines make on `days` days from `from`.
void expand(const TaskOptions& o, CommandContext& ctx) {
  const PlaceCheck formulas = formula_check();
  auto file = load_task_file(o.file, &formulas);
  if (!file) {
    fail(ctx, file.error());
    return;
  }
  std::vector<Task> tasks = file->tasks;
  if (!file->routines.empty()) {
    auto first = parse_date_option("--from", o.from);
    if (!first) {
      fail(ctx, first.error());
      return;
    }
    for (int d = 0; d < o.days; ++d) {
      const auto day = std::chrono::year_month_day{std::chrono::sys_days{*first} + std::chrono::days{d}};
      for (const auto& r : file->routines) {
        auto made = instances_on(r, day, *file->zone);
        tasks.insert(tasks.end(), made.begin(), made.end());
      }
    }
  }
  if (o.json) {
    TaskFile out{file->zone, tasks, {}};
    ctx.out << encode(out).dump(2) << '\n';
    return;
  }
  print_tasks(tasks, file->zone.value_or(TimeZone::utc()), ctx.out);
}

std::string sentence_of(const std::vector<std::string>& words) {
  std::string sentence;
  for (const auto& w : words) sentence += (sentence.empty() ? "" : " ") + w;
  return sentence;
}

// The zone of the sentence's local times: --time-zone, else the places file's; one is needed.
Result<TimeZone> zone_for(const AddOptions& o, const lang::Places& places) {
  if (!o.time_zone.empty()) {
    auto zone = TimeZone::named(o.time_zone);
    if (!zone) return Error::invalid("--time-zone: " + zone.error().message);
    return *zone;
  }
  if (places.zone()) return *places.zone();
  return Error::invalid("no time zone: give --time-zone ZONE, or time_zone in the places file");
}

Result<lang::Command> read_sentence(const AddOptions& o, TimeZone& zone) {
  RONDO_ASSIGN_OR_RETURN(auto map, map::load_map(o.map));
  lang::Places places = lang::Places::from_map(map);
  if (!o.places.empty()) {
    RONDO_ASSIGN_OR_RETURN(places, lang::Places::load(o.places, map));
  }
  RONDO_ASSIGN_OR_RETURN(zone, zone_for(o, places));
  lang::CommandContext ctx{&places, zone, {}};
  if (o.at.empty()) {
    ctx.now = std::chrono::floor<std::chrono::minutes>(std::chrono::system_clock::now());
  } else {
    auto at = zone.parse_time(o.at);
    if (!at) return Error::invalid("--at: " + at.error().message);
    ctx.now = *at;
  }
  const std::string sentence = sentence_of(o.words);
  auto command = lang::parse_command(sentence, ctx);
  if (!command) return command.error().with_context("'" + sentence + "'");
  return command;
}

// Prints what the sentence means; with --data (and without --dry-run) it is queued first in the
// deployment's store, for its executive to take (request_queue.h).
void add(const AddOptions& o, CommandContext& ctx) {
  TimeZone zone = TimeZone::utc();
  auto command = read_sentence(o, zone);
  if (!command) {
    fail(ctx, command.error());
    return;
  }
  if ((!o.data.empty() || !o.store.empty()) && !o.dry_run) {
    Result<QueuedAt> q = Error::internal("not queued");
    if (!o.store.empty()) {
      auto where = store::StoreLocation::parse(o.store);
      q = where ? queue_command(*where, sentence_of(o.words), *command, zone) : where.error().with_context("--store");
    } else {
      q = queue_command(o.data, sentence_of(o.words), *command, zone);
    }
    if (!q) {
      fail(ctx, q.error());
      return;
    }
    if (!q->already_queued.empty()) {
      ctx.err << fmt::format("rondo task add: already queued: {} (in {}); nothing queued\n",
                             fmt::join(q->already_queued, ", "), q->store);
    } else {
      ctx.err << fmt::format("rondo task add: queued as request {} in {}: {}\n", q->id, q->store, q->what);
    }
  }
  if (o.json) {
    ctx.out << request_body(*command, zone).dump(2) << '\n';
    return;
  }
  if (command->cancel) {
    const auto& c = *command->cancel;
    if (c.what == lang::Cancellation::What::kDelivery) {
      ctx.out << fmt::format("cancel the delivery of '{}'\n", c.object);
    } else if (c.what == lang::Cancellation::What::kActivity) {
      ctx.out << fmt::format("cancel '{}' tasks at {}\n", c.activity, fmt::join(c.nodes, ", "));
    } else {
      ctx.out << fmt::format("cancel task '{}'\n", c.id);
    }
    return;
  }
  if (!command->tasks.empty()) print_tasks(command->tasks, zone, ctx.out);
  for (const auto& r : command->routines) {
    ctx.out << fmt::format("routine {}: {} at {}, {}-{}{}{}\n", r.name, r.task.activity, r.task.start_node,
                           format_time_of_day(r.window_start), format_time_of_day(r.window_end),
                           r.every ? ", every " + format_duration(*r.every) : std::string(),
                           r.days.empty() ? ", daily" : fmt::format(", {} day(s) a week", r.days.size()));
  }
}

}  // namespace

void add_task_commands(CLI::App& root, CommandContext& ctx) {
  auto* task = root.add_subcommand("task", "Check task and routine files; read commands in words");
  task->require_subcommand(1);
  auto options = std::make_shared<TaskOptions>();

  auto* check_cmd = task->add_subcommand("check", "Validate a task/routine file (YAML or JSON)");
  check_cmd->add_option("FILE", options->file, "task file")->required();
  check_cmd->add_flag("--json", options->json, "print the result as JSON");
  check_cmd->callback([options, &ctx] { check(*options, ctx); });

  auto* expand_cmd = task->add_subcommand("expand", "List a file's tasks and the tasks its routines make");
  expand_cmd->add_option("FILE", options->file, "task file")->required();
  expand_cmd->add_option("--from", options->from, "first local date, YYYY-MM-DD (routines only)")->required();
  expand_cmd->add_option("--days", options->days, "number of days")->transform(whole_number(1, 3660));
  expand_cmd->add_flag("--json", options->json, "print the tasks as a task file in JSON");
  expand_cmd->callback([options, &ctx] { expand(*options, ctx); });

  auto add_options = std::make_shared<AddOptions>();
  auto* add_cmd = task->add_subcommand("add", "Print (and with --data queue) the task(s) a command in words means");
  add_cmd->add_option("SENTENCE", add_options->words, "the command, e.g. \"check office A-123 before 15:00\"")
      ->required();
  add_cmd->add_option("--map", add_options->map, "the map whose node names places resolve to")->required();
  add_cmd->add_option("--places", add_options->places, "places file: rooms, aliases, people, groups");
  add_cmd->add_option("--at", add_options->at, "what 'now' is: a time, local in the zone if it has no offset");
  add_cmd->add_option("--time-zone", add_options->time_zone, "IANA zone of local times (default: the places file's)");
  add_cmd->add_option("--data", add_options->data,
                      "queue it in this deployment's store (a rondo run --out or rondo serve --data folder)");
  add_cmd->add_option("--store", add_options->store,
                      "queue it in this store: a rondo serve --store URL (postgresql://...; no password in it)")
      ->excludes(add_cmd->get_option("--data"));
  add_cmd->add_flag("--dry-run", add_options->dry_run, "only print, even with --data or --store");
  add_cmd->add_flag("--json", add_options->json, "print a task file in JSON (or the cancellation)");
  add_cmd->callback([add_options, &ctx] { add(*add_options, ctx); });
}

}  // namespace rondo::app
