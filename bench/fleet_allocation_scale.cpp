// The fleet's allocation at scale (issue 38, "Scale, in bench/"), in a running fleet of simulated
// robots on the generated hospital (bench/fleet_scale_building.h), built as `rondo run` builds it
// (the deployment's robots, options and allocator, a store on disk):
// - one new task among the queued ones: the time of the fleet's Allocator::allocate() for a unit of
//   one new standard task, every robot eligible, p50 / p99 / max over many new tasks each against
//   the same fleet (nothing is committed, so each sees the same queue), by an allocator made for the
//   samples (under `fleet`, its first sample makes the travel oracle it keeps); then the whole of
//   Fleet::add_task() for some of them (checked, allocated, stored in one transaction, scheduled by
//   its robot), which does commit: the queue grows by one each time;
// - a faulted robot's re-allocation: the robot with the most planned tasks faults, and the time
//   from the moment the fleet re-allocates (ExecutorOptions::reallocate_after after the fault) until
//   every task it released is stored on another robot and scheduled there; several robots in turn.
// The queue is a day of routines (the building's with no requests: `queued` tasks a day), every
// instance added at the start of the day; the figures are taken a minute later, when every robot
// has planned its share. Once under each allocator: `fleet` (the default) and `greedy`.
//
//   cmake --build build --target bench_fleet_allocation_scale
//   build/bench/bench_fleet_allocation_scale [robots=100] [queued=1000] [samples=200] [adds=50]
//                                            [faults=5] [wings=14] [folder=/tmp/rondo-fleet-allocation-scale]
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "bench_clock.h"
#include "deployment.h"
#include "deployment_parts.h"
#include "fleet_scale_building.h"
#include "robot_factory.h"
#include "rondo/exec/clock.h"
#include "rondo/fleet/fleet.h"
#include "rondo/fleet/fleet_scheduler_allocator.h"
#include "rondo/sim/sim_robot.h"
#include "rondo/store/store.h"

namespace {

using namespace rondo;

using rondo::bench::quantile;

// A row: wall milliseconds (p50, p99, max) and the thread's CPU milliseconds (p50, p99); the machine
// is shared, so the CPU time says what the work costs whatever else runs.
void print_row(const char* allocator, std::size_t robots, std::size_t queue, const char* what,
               const std::vector<double>& wall_ms, const std::vector<double>& cpu_ms) {
  if (wall_ms.empty()) return;
  fmt::print("{:<7} {:>6} {:>6} {:<22} {:>7} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f}\n", allocator, robots, queue,
             what, wall_ms.size(), quantile(wall_ms, 0.5), quantile(wall_ms, 0.99),
             *std::max_element(wall_ms.begin(), wall_ms.end()), quantile(cpu_ms, 0.5), quantile(cpu_ms, 0.99));
}

struct Args {
  int robots = 100, queued = 1000, samples = 200, adds = 50, faults = 5, wings = 14;
  std::filesystem::path folder = "/tmp/rondo-fleet-allocation-scale";
};

std::optional<Args> parse(int argc, char** argv) {
  Args a;
  int* fields[] = {&a.robots, &a.queued, &a.samples, &a.adds, &a.faults, &a.wings};
  for (int i = 1; i < argc && i <= 6; ++i) {
    const std::string text = argv[i];
    if (text.empty() || text.size() > 7 ||
        !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      fmt::print(stderr, "bench_fleet_allocation_scale: argument {}: expected a whole number, found '{}'\n", i, text);
      return std::nullopt;
    }
    *fields[i - 1] = std::stoi(text);
  }
  if (argc > 7) a.folder = argv[7];
  if (a.robots < 2) {
    fmt::print(stderr, "bench_fleet_allocation_scale: a fleet needs at least 2 robots\n");
    return std::nullopt;
  }
  return a;
}

// A new room check somewhere in the building, due within the day: the kind of task a person adds.
Task new_task(std::mt19937_64& rng, const Args& a, Time now, int n) {
  std::uniform_int_distribution<int> wing(1, a.wings), k(1, 5), minutes_ahead(0, 12 * 60), width(60, 180), dur(2, 5);
  Task t;
  t.id = fmt::format("bench-{}", n);
  t.kind = TaskKind::kStandard;
  t.start_node = bench::wing_node(wing(rng), k(rng));
  const Time release = now + std::chrono::minutes(minutes_ahead(rng));
  t.window = TimeWindow{release, release + std::chrono::minutes(width(rng))};
  t.duration = std::chrono::minutes(dur(rng));
  t.priority = 3;
  t.activity = "room check";
  t.actions = {Action{.name = "room_check", .args = {}}};
  return t;
}

std::size_t queued(const fleet::Fleet& fleet) {
  std::size_t n = 0;
  for (const auto& r : fleet.robots()) n += r->activity().planned.size() + r->deferred().size();
  return n;
}

// One fleet under `kind`; prints its rows. False when it could not be built.
bool measure(const Args& a, const app::Deployment& base, app::AllocatorKind kind) {
  app::Deployment d = base;
  d.allocator = kind;
  const char* name = kind == app::AllocatorKind::kFleet ? "fleet" : "greedy";
  auto parts = app::load_parts(d);
  if (!parts) {
    fmt::print(stderr, "bench_fleet_allocation_scale: {}\n", parts.error().message);
    return false;
  }
  const std::filesystem::path db_file = a.folder / fmt::format("{}.sqlite", name);
  for (const char* tail : {"", "-wal", "-shm"}) std::filesystem::remove(db_file.string() + tail);
  auto db = store::Store::open(db_file);
  if (!db) {
    fmt::print(stderr, "bench_fleet_allocation_scale: {}\n", db.error().message);
    return false;
  }
  const Time start = d.zone.at(d.start, Duration{0});
  exec::SimClock clock(start);
  exec::ExecutorOptions shared = d.executor;
  shared.dock = parts->dock;
  shared.seed = d.seed;
  std::vector<app::DeploymentRobot> deployed;
  for (std::size_t i = 0; i < d.robots.size(); ++i) {
    auto robot = app::make_robot(d, d.robots[i], *parts, clock, parts->robots[i].start, d.seed + i);
    if (!robot) {
      fmt::print(stderr, "bench_fleet_allocation_scale: {}\n", robot.error().message);
      return false;
    }
    deployed.push_back(std::move(*robot));
  }
  fleet::Fleet fleet(clock, parts->map, *db, d.zone, shared, {}, app::make_allocator(d));
  for (std::size_t i = 0; i < d.robots.size(); ++i)
    fleet.add_robot(*deployed[i].robot, app::robot_options(d, d.robots[i], parts->robots[i]));
  fleet.add_routines(parts->plan.routines);
  const double built = bench::steady_seconds();
  fleet.start();
  clock.run_until(start + std::chrono::minutes(1));
  const double started = bench::steady_seconds() - built;

  // One new task at a time through the allocator interface, against the same fleet.
  std::unique_ptr<fleet::Allocator> allocator = app::make_allocator(d);
  std::vector<const exec::Executor*> robots;
  std::vector<std::size_t> everyone;
  for (const auto& r : fleet.robots()) {
    everyone.push_back(robots.size());
    robots.push_back(r.get());
  }
  std::mt19937_64 rng(7);
  std::vector<double> allocate_ms, allocate_cpu_ms;
  const std::size_t queue = queued(fleet);
  for (int s = 0; s < a.samples; ++s) {
    const Task t = new_task(rng, a, clock.now(), s);
    const std::vector<fleet::AllocationUnit> units{{.tasks = {&t}, .eligible = everyone}};
    const double t0 = bench::steady_seconds(), c0 = bench::thread_seconds();
    const std::vector<fleet::Allocation> to = allocator->allocate(units, robots, fleet.building());
    allocate_ms.push_back(1e3 * (bench::steady_seconds() - t0));
    allocate_cpu_ms.push_back(1e3 * (bench::thread_seconds() - c0));
    if (to.size() != 1) fmt::print(stderr, "bench_fleet_allocation_scale: allocate() gave {} answers\n", to.size());
  }
  print_row(name, d.robots.size(), queue, "allocate(1 new task)", allocate_ms, allocate_cpu_ms);
  if (const auto* fleet_allocator = dynamic_cast<const fleet::FleetSchedulerAllocator*>(allocator.get()))
    fmt::print(
        "# {}: of the {} samples, {} inserted into the robots' plans, {} solved whole ({} after an "
        "insertion left the task out); the first made the held travel oracle\n",
        name, a.samples, fleet_allocator->counts().inserted, fleet_allocator->counts().solved,
        fleet_allocator->counts().fell_back);

  // The whole of add_task(), committed: the queue grows by one each time.
  std::vector<double> add_ms, add_cpu_ms;
  for (int s = 0; s < a.adds; ++s) {
    Task t = new_task(rng, a, clock.now(), a.samples + s);
    const double t0 = bench::steady_seconds(), c0 = bench::thread_seconds();
    const Status added = fleet.add_task(std::move(t), "bench");
    add_ms.push_back(1e3 * (bench::steady_seconds() - t0));
    add_cpu_ms.push_back(1e3 * (bench::thread_seconds() - c0));
    if (!added) fmt::print(stderr, "bench_fleet_allocation_scale: {}\n", added.error().message);
  }
  print_row(name, d.robots.size(), queued(fleet), "Fleet::add_task", add_ms, add_cpu_ms);

  // Faults: the robot with the most planned tasks, one after another.
  for (int f = 0; f < a.faults; ++f) {
    std::size_t worst = 0, most = 0;
    for (std::size_t i = 0; i < fleet.robots().size(); ++i) {
      const auto& r = *fleet.robots()[i];
      if (!r.able()) continue;
      const std::size_t n = r.activity().planned.size() + r.deferred().size();
      if (n > most) most = n, worst = i;
    }
    exec::Executor& robot = *fleet.robots()[worst];
    auto* sim = dynamic_cast<sim::SimRobot*>(deployed[worst].robot.get());
    if (sim == nullptr || most == 0) break;
    const std::vector<TaskId> held = robot.activity().planned;
    const Time at = clock.now();
    sim->inject_fault(exec::RobotFault{.kind = exec::RobotFault::Kind::kError, .message = "bench: a fault"});
    const Time moves = at + robot.reallocate_after();
    clock.run_until(moves - std::chrono::milliseconds(1));
    const double t0 = bench::steady_seconds(), c0 = bench::thread_seconds();
    clock.run_until(moves);
    const double ms = 1e3 * (bench::steady_seconds() - t0), cpu_ms = 1e3 * (bench::thread_seconds() - c0);
    std::size_t moved = 0;
    for (const TaskId& id : held)
      if (fleet.book().at(id).robot != robot.name()) ++moved;
    fmt::print("{:<7} {:>6} {:>6} {:<22} {:>7} {:>9.1f} {:>9} {:>9} {:>9.1f} {:>9} (robot {}: {} planned, {} moved)\n",
               name, d.robots.size(), queued(fleet), "re-allocate a fault", 1, ms, "", "", cpu_ms, "", robot.name(),
               held.size(), moved);
  }
  fmt::print("# {}: fleet built and started in {:.1f} s; load average {}\n", name, started, bench::load_average());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<Args> a = parse(argc, argv);
  if (!a) return 2;
  const bench::ScaleBuilding b{
      .robots = a->robots, .wings = a->wings, .tasks_per_day = a->queued, .days = 1, .routine_share = 1.0};
  const std::filesystem::path file = bench::write_scale_building(a->folder / "building", b);
  auto deployment = app::load_deployment(file);
  if (!deployment) {
    fmt::print(stderr, "bench_fleet_allocation_scale: {}\n", deployment.error().message);
    return 2;
  }
  fmt::print("# {} robots, a day of {} routine tasks, {} wings; load average {}\n", a->robots, a->queued, a->wings,
             bench::load_average());
  fmt::print("{:<7} {:>6} {:>6} {:<22} {:>7} {:>9} {:>9} {:>9} {:>9} {:>9}\n", "alloc", "robots", "queued", "what",
             "samples", "p50_ms", "p99_ms", "max_ms", "cpu_p50", "cpu_p99");
  for (const app::AllocatorKind kind : {app::AllocatorKind::kFleet, app::AllocatorKind::kGreedy})
    if (!measure(*a, *deployment, kind)) return 1;
  return 0;
}
