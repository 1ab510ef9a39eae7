#include "run_session.h"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <ostream>

#include "rondo/core/atomic_file.h"
#include "rondo/core/task_codec.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor.h"
#include "rondo/sim/request_generator.h"
#include "rondo/sim/sim_robot.h"
#include "rondo/sim/sim_world.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/store.h"
#include "rondo/store/traversal_log.h"
#include "deployment_parts.h"
#include "run_report.h"

namespace rondo::app {
namespace {

Status write_file(const std::filesystem::path& file, const std::string& text) {
  return write_file_atomically(file, text);
}

std::string date_text(std::chrono::year_month_day d) {
  return fmt::format("{:04d}-{:02d}-{:02d}", static_cast<int>(d.year()), static_cast<unsigned>(d.month()),
                     static_cast<unsigned>(d.day()));
}

void draw_progress(std::ostream& out, int done, int total) {
  constexpr int kWidth = 30;
  const int filled = total > 0 ? done * kWidth / total : kWidth;
  out << fmt::format("\r  day {:>3}/{} [{}{}]", done, total, std::string(static_cast<std::size_t>(filled), '#'),
                     std::string(static_cast<std::size_t>(kWidth - filled), ' '))
      << std::flush;
}

// Everything one run needs, alive for the whole run.
struct Session {
  DeploymentParts parts;
  store::Store store;
};

// The whole deployment is loaded and checked before the run folder is touched: a deployment that
// fails validation leaves --out as it was.
Result<Session> open_session(const RunRequest& request) {
  RONDO_ASSIGN_OR_RETURN(DeploymentParts parts, load_parts(request.deployment));
  const std::filesystem::path db = request.out / "rondo.sqlite";
  if (std::filesystem::exists(db))
    return Error::invalid(fmt::format("{}: already exists; give a fresh --out folder", db.string()));
  std::error_code ec;
  std::filesystem::create_directories(request.out / "days", ec);
  if (ec) return Error::io(fmt::format("{}: cannot create the run folder: {}", request.out.string(), ec.message()));
  RONDO_ASSIGN_OR_RETURN(store::Store store, store::Store::open(db, {.sync_commits = request.realtime}));
  // What run this store holds, so that a restart can tell its own store from another's.
  const Deployment& d = request.deployment;
  for (const auto& [key, value] : std::initializer_list<std::pair<const char*, std::string>>{
           {"run.deployment", d.name},
           {"run.deployment_file", std::filesystem::absolute(d.file).lexically_normal().string()},
           {"run.seed", std::to_string(d.seed)},
           {"run.days", std::to_string(d.days)},
           {"run.realtime", request.realtime ? "true" : "false"}})
    RONDO_RETURN_IF_ERROR(store::set_meta(store, key, value));
  return Session{std::move(parts), std::move(store)};
}

}  // namespace

Result<RunResult> run_deployment(const RunRequest& request, std::ostream& progress_to) {
  const auto wall_start = std::chrono::steady_clock::now();
  const Deployment& d = request.deployment;
  RONDO_ASSIGN_OR_RETURN(Session s, open_session(request));
  const map::TopoMap& map = s.parts.map;
  const map::NodeIndex dock = s.parts.dock;

  const Time start = request.realtime ? std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now())
                                      : d.zone.at(d.start, Duration{0});
  exec::SimClock sim_clock(start);
  exec::SystemClock system_clock;
  exec::Clock& clock = request.realtime ? static_cast<exec::Clock&>(system_clock) : sim_clock;
  sim::SimRobot robot(clock, map, s.parts.world, {.start = dock, .dock = dock, .seed = d.seed});
  exec::ExecutorOptions options = d.executor;
  options.dock = dock;
  options.seed = d.seed;
  exec::Executor executor(clock, robot, map, s.store, d.zone, options);
  executor.add_routines(s.parts.plan.routines);
  if (!s.parts.plan.tasks.empty()) RONDO_RETURN_IF_ERROR(executor.add_tasks(s.parts.plan.tasks, "deployment"));
  executor.start();

  // Spans on the charger for the day pictures, sampled once a minute (reads only: the run is the
  // same with or without it).
  std::vector<std::pair<Time, Time>> charging;
  std::optional<Time> charging_since;
  std::function<void()> sample_charger = [&] {
    const bool on = robot.charging();
    if (on && !charging_since) charging_since = clock.now();
    if (!on && charging_since) {
      charging.emplace_back(*charging_since, clock.now());
      charging_since.reset();
    }
    clock.schedule_after(minutes(1), sample_charger);
  };
  clock.schedule_at(start, sample_charger);

  sim::Rng people_rng(d.seed * 0x9E3779B97F4A7C15ULL + 17);
  const auto run_until = [&](Time t) {
    if (request.realtime)
      system_clock.run_until(t);
    else
      sim_clock.run_until(t);
  };
  auto today = d.zone.local_date(start);
  for (int day = 0; day < d.days; ++day) {
    const auto tomorrow = std::chrono::year_month_day{std::chrono::sys_days{today} + std::chrono::days{1}};
    const Time day_from = std::max(start, d.zone.at(today, Duration{0}));
    const Time day_to = d.zone.at(tomorrow, Duration{0});
    if (s.parts.people) {
      for (sim::Request& r : s.parts.people->between(day_from, day_to, people_rng))
        clock.schedule_at(r.at, [&executor, tasks = r.tasks()]() mutable {
          (void)executor.add_tasks(std::move(tasks), "request");
        });
    }
    run_until(day_to);
    const std::string date = date_text(today);
    DayPicture picture =
        day_picture(executor, fmt::format("{} — {} (day {})", d.name, date, day + 1), day_from, day_to, d.zone);
    for (const auto& [a, b] : charging)
      if (b > day_from && a < day_to) picture.charging.emplace_back(a, b);
    if (charging_since) picture.charging.emplace_back(*charging_since, day_to);
    RONDO_RETURN_IF_ERROR(write_file(request.out / "days" / (date + ".svg"), render_day_svg(picture)));
    if (request.progress) draw_progress(progress_to, day + 1, d.days);
    today = tomorrow;
  }
  if (request.progress) progress_to << "\n";
  const Time end = clock.now();

  RunResult result;
  result.report = run_report(executor, {.from = start, .to = end, .distance_m = robot.distance_m(),
                                        .charging = robot.charging_time()});
  result.report["deployment"] = d.name;
  result.report["seed"] = d.seed;
  result.report["days"] = d.days;
  RONDO_ASSIGN_OR_RETURN(const std::vector<Traversal> log, store::find_traversals(s.store));
  result.report["travel_table"] = travel_table(map, log, start, d.days);
  result.write_errors = static_cast<int>(executor.write_errors().size());
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  RONDO_RETURN_IF_ERROR(write_file(request.out / "report.json", result.report.dump(2) + "\n"));
  Json run{{"wall_seconds", result.wall_seconds},
           {"simulated_days", d.days},
           {"realtime", request.realtime},
           {"store_write_errors", executor.write_errors()}};
  RONDO_RETURN_IF_ERROR(write_file(request.out / "run.json", run.dump(2) + "\n"));
  return result;
}

}  // namespace rondo::app
