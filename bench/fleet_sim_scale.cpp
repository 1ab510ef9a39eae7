// The fleet at scale (issue 38, "Scale, in bench/"): `rondo run` of a generated hospital
// (bench/fleet_scale_building.h) with many simulated robots and many tasks a day, as the command
// runs it (the fleet, the simulated world, the people's requests, the store on disk, the report
// and the day pictures). It prints the cost of each simulated day, in wall and in CPU seconds (the
// run's own run.json), and the memory the process holds at the end of each day and at its peak, so
// that a cost that grows with the run shows as a rising column. Target of the acceptance: 100
// robots, 10,000 tasks a day, 7 days in under 5 minutes on the shared 2-core machine.
//
//   cmake --build build --target bench_fleet_sim_scale
//   build/bench/bench_fleet_sim_scale [robots=100] [tasks_per_day=10000] [days=7] [wings=14]
//                                     [allocator=fleet] [seed=1] [folder=/tmp/rondo-fleet-sim-scale] [hours]
//   # a smaller run first: build/bench/bench_fleet_sim_scale 10 1000 1
//   # `hours`: stop that long after the start (RunRequest::run_for), for a size whose day is too long
//
// The folder gets the deployment (building/) and the run (run/, removed first: every run is fresh).
#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "bench_clock.h"
#include "deployment.h"
#include "fleet_scale_building.h"
#include "run_session.h"

namespace {

using namespace rondo;

// A line of /proc/self/status in MiB (VmRSS: held now; VmHWM: the peak so far).
double status_mib(const std::string& key) {
  std::ifstream f("/proc/self/status");
  for (std::string line; std::getline(f, line);)
    if (line.rfind(key + ":", 0) == 0) return std::atof(line.c_str() + key.size() + 1) / 1024.0;
  return 0;
}

// Forwards every callback of the first robot to its executor, and notes the memory held when the
// first callback of each new simulated day arrives (the first robot's edges and actions come often
// enough to mark the days).
class DayMemory final : public exec::RobotListener {
 public:
  DayMemory(exec::Executor& executor, Time start, std::vector<double>& rss_mib)
      : ex_(executor), start_(start), rss_mib_(rss_mib) {}
  void on_edge_finished(const exec::EdgeAttempt& a) override {
    mark(a.start + a.duration);
    ex_.on_edge_finished(a);
  }
  void on_action_finished(const exec::ActionResult& r) override { ex_.on_action_finished(r); }
  void on_interruptible_changed(bool i) override { ex_.on_interruptible_changed(i); }
  void on_observation(const exec::Observation& o) override { ex_.on_observation(o); }
  void on_fault(const exec::RobotFault& f) override { ex_.on_fault(f); }
  void on_ready() override { ex_.on_ready(); }

 private:
  void mark(Time now) {
    const auto day = static_cast<std::size_t>((now - start_) / std::chrono::hours(24));
    while (rss_mib_.size() < day) rss_mib_.push_back(status_mib("VmRSS"));
  }

  exec::Executor& ex_;
  Time start_;
  std::vector<double>& rss_mib_;
};

std::optional<int> whole(int argc, char** argv, int i, const char* what, int fallback) {
  if (argc <= i) return fallback;
  const std::string text = argv[i];
  if (text.empty() || text.size() > 7 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }) || std::stoi(text) < 1) {
    fmt::print(stderr, "bench_fleet_sim_scale: argument {} ({}): expected a whole number from 1, found '{}'\n", i, what,
               text);
    return std::nullopt;
  }
  return std::stoi(text);
}

}  // namespace

int main(int argc, char** argv) {
  const auto robots = whole(argc, argv, 1, "robots", 100);
  const auto tasks = whole(argc, argv, 2, "tasks_per_day", 10000);
  const auto days = whole(argc, argv, 3, "days", 7);
  const auto wings = whole(argc, argv, 4, "wings", 14);
  if (!robots || !tasks || !days || !wings) return 2;
  bench::ScaleBuilding b{.robots = *robots, .wings = *wings, .tasks_per_day = *tasks, .days = *days};
  if (argc > 5) b.allocator = argv[5];
  if (argc > 6) b.seed = std::strtoull(argv[6], nullptr, 10);
  const std::filesystem::path folder = argc > 7 ? argv[7] : "/tmp/rondo-fleet-sim-scale";
  const std::filesystem::path file = bench::write_scale_building(folder / "building", b);
  auto deployment = app::load_deployment(file);
  if (!deployment) {
    fmt::print(stderr, "bench_fleet_sim_scale: {}\n", deployment.error().message);
    return 2;
  }
  std::filesystem::remove_all(folder / "run");
  std::optional<int> hours;
  if (argc > 8 && !(hours = whole(argc, argv, 8, "hours", 24))) return 2;
  fmt::print("# {} robots, {} tasks a day, {} days{}, {} wings, allocator {}, seed {}; load average {}\n", b.robots,
             b.tasks_per_day, b.days, hours ? fmt::format(" (the first {} h only)", *hours) : "", b.wings, b.allocator,
             b.seed, bench::load_average());

  std::vector<double> rss_mib;
  app::RunRequest request;
  request.deployment = *deployment;
  request.out = folder / "run";
  if (hours) request.run_for = std::chrono::hours(*hours);
  const Time start = deployment->zone.at(deployment->start, Duration{0});
  request.wrap_listener = [&](exec::Executor& ex) { return std::make_unique<DayMemory>(ex, start, rss_mib); };
  const double t0 = bench::steady_seconds();
  auto result = app::run_deployment(request, std::cerr);
  const double wall = bench::steady_seconds() - t0;
  if (!result) {
    fmt::print(stderr, "bench_fleet_sim_scale: {}\n", result.error().message);
    return 1;
  }
  rss_mib.push_back(status_mib("VmRSS"));

  std::ifstream run_json(folder / "run" / "run.json");
  const Json run = Json::parse(run_json, nullptr, /*allow_exceptions=*/false);
  const Json& report = result->report;
  fmt::print("# day  wall_s  cpu_s  rss_mib_at_end\n");
  // The days run (fewer than asked with `hours`).
  const std::size_t days_run = run.is_object() ? run["day_wall_seconds"].size() : 0;
  for (int d = 0; static_cast<std::size_t>(d) < days_run; ++d) {
    const auto i = static_cast<std::size_t>(d);
    const auto number = [&](const char* key) {
      return run.is_object() && run[key].size() > i && run[key][i].is_number() ? run[key][i].get<double>() : 0.0;
    };
    fmt::print("{:>5} {:>7.1f} {:>6.1f} {:>15.0f}\n", d + 1, number("day_wall_seconds"), number("day_cpu_seconds"),
               i < rss_mib.size() ? rss_mib[i] : 0.0);
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto count = [&](const char* key) { return report.value(key, Json()).dump(); };
  fmt::print("# run: wall {:.1f} s (the report and pictures included), cpu {:.1f} s, peak RSS {:.0f} MiB\n", wall,
             run.is_object() ? run.value("cpu_seconds", 0.0) : 0.0, static_cast<double>(usage.ru_maxrss) / 1024.0);
  fmt::print("# tasks: {}\n", count("tasks"));
  fmt::print("# load average after: {}\n", bench::load_average());
  return 0;
}
