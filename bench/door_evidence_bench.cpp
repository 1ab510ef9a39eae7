// How strong is a failed attempt at a door's edge as evidence that the door is shut (issue 43)?
// Runs `rondo run` on a deployment (its own session: SimRobot, the parametric world, people's
// requests) with a listener between the robot and the executor that, at every attempt at an edge
// with a door, asks a copy of the world whether the door was shut then (the building's spells
// are a pure function of the deployment's seed and the time, so the copy agrees with the run's
// world). It prints, per seed and in all: the attempts at door edges, the failed ones, and how
// many of those failed at a shut door (P(shut | failed)), beside how often any attempt met a shut
// door (the base rate). The run itself is unchanged.
//
//   cmake --build build --target bench_door_evidence
//   build/bench/bench_door_evidence [deployment] [days] [first seed] [seeds]
//   # defaults: examples/office/deployment.yaml 14 1 5
#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "deployment.h"
#include "deployment_parts.h"
#include "run_session.h"

namespace {

using namespace rondo;

struct Counts {
  long attempts = 0, shut = 0, failed = 0, failed_shut = 0, failed_unknown = 0;
  Counts& operator+=(const Counts& o) {
    attempts += o.attempts;
    shut += o.shut;
    failed += o.failed;
    failed_shut += o.failed_shut;
    failed_unknown += o.failed_unknown;
    return *this;
  }
};

// Forwards every callback to the executor; counts the attempts at door edges against the world.
class DoorCounter final : public exec::RobotListener {
 public:
  DoorCounter(exec::Executor& executor, const map::TopoMap& map, const sim::EdgeWorld& world, Counts& counts)
      : ex_(executor), map_(map), world_(world), counts_(counts) {}
  void on_edge_finished(const exec::EdgeAttempt& a) override {
    if (map_.edge(a.edge).door && exec::is_learning_data(a.outcome)) {
      const std::optional<bool> shut = world_.closed_at(a.edge, a.start);
      ++counts_.attempts;
      if (shut.value_or(false)) ++counts_.shut;
      if (!a.succeeded()) {
        ++counts_.failed;
        if (!shut) ++counts_.failed_unknown;
        if (shut.value_or(false)) ++counts_.failed_shut;
      }
    }
    ex_.on_edge_finished(a);
  }
  void on_action_finished(const exec::ActionResult& r) override { ex_.on_action_finished(r); }
  void on_interruptible_changed(bool i) override { ex_.on_interruptible_changed(i); }
  void on_observation(const exec::Observation& o) override { ex_.on_observation(o); }
  void on_fault(const exec::RobotFault& f) override { ex_.on_fault(f); }
  void on_ready() override { ex_.on_ready(); }

 private:
  exec::Executor& ex_;
  const map::TopoMap& map_;
  const sim::EdgeWorld& world_;
  Counts& counts_;
};

double ratio(long a, long b) { return b == 0 ? 0.0 : static_cast<double>(a) / static_cast<double>(b); }

void print_row(const std::string& label, const Counts& c) {
  fmt::print("{:>6} {:>9} {:>6} {:>7} {:>12} {:>14.3f} {:>11.3f} {:>8}\n", label, c.attempts, c.shut, c.failed,
             c.failed_shut, ratio(c.failed_shut, c.failed), ratio(c.shut, c.attempts), c.failed_unknown);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string file = argc > 1 ? argv[1] : "examples/office/deployment.yaml";
  const int days = argc > 2 ? std::atoi(argv[2]) : 14;
  const int first_seed = argc > 3 ? std::atoi(argv[3]) : 1;
  const int seeds = argc > 4 ? std::atoi(argv[4]) : 5;
  if (days < 1 || first_seed < 0 || seeds < 1) {
    fmt::print(stderr, "bench_door_evidence: days and seeds must be whole numbers from 1\n");
    return 2;
  }
  auto deployment = app::load_deployment(file);
  if (!deployment) {
    fmt::print(stderr, "bench_door_evidence: {} (run from the project root)\n", deployment.error().message);
    return 2;
  }
  deployment->days = days;
  fmt::print("# {} for {} days, seeds {}..{}: attempts at edges with a door (succeeded or failed)\n", file, days,
             first_seed, first_seed + seeds - 1);
  fmt::print("#  seed  attempts   shut  failed  failed_shut  P(shut|failed)  P(shut)  unknown\n");
  Counts all;
  for (int k = 0; k < seeds; ++k) {
    deployment->seed = static_cast<std::uint64_t>(first_seed + k);
    auto parts = app::load_parts(*deployment);
    if (!parts || !parts->world) {
      fmt::print(stderr, "bench_door_evidence: {}\n", parts ? "the deployment has no simulated world" : parts.error().message);
      return 2;
    }
    parts->world->edges->set_seed(deployment->seed);  // as robot_factory.cpp seeds the run's world
    const auto out = std::filesystem::temp_directory_path() / fmt::format("bench-door-evidence-{}", ::getpid());
    std::filesystem::remove_all(out);
    Counts counts;
    app::RunRequest request;
    request.deployment = *deployment;
    request.out = out;
    request.wrap_listener = [&](exec::Executor& ex) {
      return std::make_unique<DoorCounter>(ex, parts->map, *parts->world->edges, counts);
    };
    auto result = app::run_deployment(request, std::cerr);
    std::filesystem::remove_all(out);
    if (!result) {
      fmt::print(stderr, "bench_door_evidence: {}\n", result.error().message);
      return 1;
    }
    print_row(std::to_string(deployment->seed), counts);
    all += counts;
  }
  print_row("all", all);
  return 0;
}
