// `rondo task ...`: check task and routine files, and show the tasks routines make.
#include <chrono>
#include <map>

#include <fmt/format.h>

#include "commands.h"
#include "rondo/core/task_codec.h"
#include "time_parsing_cli.h"

namespace rondo::app {
namespace {

struct TaskOptions {
  std::string file;
  bool json = false;
  std::string from;
  int days = 7;
};

void check(const TaskOptions& o, CommandContext& ctx) {
  auto file = load_task_file(o.file);
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
  auto file = load_task_file(o.file);
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
  const TimeZone zone = file->zone.value_or(TimeZone::utc());
  ctx.out << fmt::format("{:<36} {:<26} {:<26} {:>8} {:>4}  {}\n", "id", "release", "deadline", "duration", "prio",
                         "start");
  for (const auto& t : tasks) {
    ctx.out << fmt::format("{:<36} {:<26} {:<26} {:>8} {:>4}  {}\n", t.id,
                           t.window ? zone.format_local(t.window->release) : "now",
                           t.window ? zone.format_local(t.window->deadline) : "-", format_duration(t.duration),
                           t.priority, t.start_node.empty() ? "-" : t.start_node);
  }
}

}  // namespace

void add_task_commands(CLI::App& root, CommandContext& ctx) {
  auto* task = root.add_subcommand("task", "Check task and routine files");
  task->require_subcommand(1);
  auto options = std::make_shared<TaskOptions>();

  auto* check_cmd = task->add_subcommand("check", "Validate a task/routine file (YAML or JSON)");
  check_cmd->add_option("FILE", options->file, "task file")->required();
  check_cmd->add_flag("--json", options->json, "print the result as JSON");
  check_cmd->callback([options, &ctx] { check(*options, ctx); });

  auto* expand_cmd = task->add_subcommand("expand", "List a file's tasks and the tasks its routines make");
  expand_cmd->add_option("FILE", options->file, "task file")->required();
  expand_cmd->add_option("--from", options->from, "first local date, YYYY-MM-DD (routines only)")->required();
  expand_cmd->add_option("--days", options->days, "number of days")->check(CLI::Range(1, 3660));
  expand_cmd->add_flag("--json", options->json, "print the tasks as a task file in JSON");
  expand_cmd->callback([options, &ctx] { expand(*options, ctx); });
}

}  // namespace rondo::app
