// Time from an observation that breaks an assumption to the new schedule over the office example's
// real fortnight (issue 16's acceptance: median and p99 over the 14-day run, goal < 20 ms):
// `rondo run examples/office/deployment.yaml` as the command runs it (SimRobot, the parametric
// world, the people's requests, the store on disk), with a listener put between the robot and the
// executor (RunRequest::wrap_listener) that forwards every callback and reads the steady clock
// around them. A break starts when a `door_open` = 0 observation raises the executor's count of
// broken assumptions, and ends when a callback returns with its count of reschedules raised (at
// once, or after the stopped task's end comes back from the robot). The run itself is unchanged:
// its report.json is that of `rondo run` with the same seed.
//
//   cmake --build build --target bench_courier_fortnight
//   build/bench/bench_courier_fortnight [runs] [days] [deployment] [seed] [seeds]
//   # defaults 3 14 examples/office/deployment.yaml <its seed> 1: `runs` runs of each of `seeds`
//   # seeds from `seed` (one seed's fortnight breaks few assumptions; more seeds, more samples)
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "bench_clock.h"
#include "deployment.h"
#include "run_session.h"

namespace {

using namespace rondo;

using rondo::bench::quantile;

// Forwards every callback to the executor; times each break until its reschedule.
class TimingListener final : public exec::RobotListener {
 public:
  TimingListener(exec::Executor& executor, std::vector<double>& samples) : ex_(executor), samples_(samples) {}
  void on_edge_finished(const exec::EdgeAttempt& a) override {
    timed([&] { ex_.on_edge_finished(a); });
  }
  void on_action_finished(const exec::ActionResult& r) override {
    timed([&] { ex_.on_action_finished(r); });
  }
  void on_interruptible_changed(bool i) override {
    timed([&] { ex_.on_interruptible_changed(i); });
  }
  void on_observation(const exec::Observation& o) override {
    const int broken = ex_.assumption_stats().broken, before = ex_.assumption_stats().reschedules;
    const double t0 = bench::steady_seconds();
    ex_.on_observation(o);
    if (ex_.assumption_stats().broken == broken) return check();
    if (ex_.assumption_stats().reschedules > before) {
      samples_.push_back(bench::steady_seconds() - t0);  // rescheduled within the call
    } else {
      since_ = t0;  // rescheduled once the stopped task's end comes back
      reschedules_ = before;
    }
  }
  void on_fault(const exec::RobotFault& f) override {
    timed([&] { ex_.on_fault(f); });
  }
  void on_ready() override {
    timed([&] { ex_.on_ready(); });
  }

 private:
  template <class F>
  void timed(F&& f) {
    f();
    check();
  }
  void check() {
    if (since_ && ex_.assumption_stats().reschedules > reschedules_) {
      samples_.push_back(bench::steady_seconds() - *since_);
      since_.reset();
    }
  }

  exec::Executor& ex_;
  std::vector<double>& samples_;
  std::optional<double> since_;
  int reschedules_ = 0;
};

}  // namespace

// argv[i] as a whole number of at least `least`, or `fallback` when it is not given; nullopt (said
// on stderr) when it is not one.
std::optional<std::uint64_t> count_arg(int argc, char** argv, int i, const char* what, std::uint64_t fallback,
                                       std::uint64_t least = 1) {
  if (argc <= i) return fallback;
  const std::string text = argv[i];
  if (text.empty() || text.size() > 9 || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }) ||
      std::stoull(text) < least) {
    fmt::print(stderr, "bench_courier_fortnight: argument {} ({}): expected a whole number from {}, found '{}'\n", i,
               what, least, text);
    return std::nullopt;
  }
  return std::stoull(text);
}

int main(int argc, char** argv) {
  const auto runs_arg = count_arg(argc, argv, 1, "runs", 3);
  const auto days_arg = count_arg(argc, argv, 2, "days", 14);
  if (!runs_arg || !days_arg) return 2;
  const int runs = static_cast<int>(*runs_arg);
  const int days = static_cast<int>(*days_arg);
  const std::string file = argc > 3 ? argv[3] : "examples/office/deployment.yaml";
  auto deployment = app::load_deployment(file);
  if (!deployment) {
    fmt::print(stderr, "bench_courier_fortnight: {} (run from the project root)\n", deployment.error().message);
    return 2;
  }
  deployment->days = days;
  const auto seed_arg = count_arg(argc, argv, 4, "seed", deployment->seed, 0);
  const auto seeds_arg = count_arg(argc, argv, 5, "seeds", 1);
  if (!seed_arg || !seeds_arg) return 2;
  const std::uint64_t first_seed = *seed_arg;
  const int seeds = static_cast<int>(*seeds_arg);
  fmt::print("# {} for {} days, seeds {}..{}; load average {}\n", file, days, first_seed,
             first_seed + static_cast<std::uint64_t>(seeds) - 1, bench::load_average());
  fmt::print("# seed  run  breaks  median_ms  p99_ms  max_ms  run_wall_s\n");
  std::vector<double> all;
  for (int k = 0; k < seeds; ++k) {
    deployment->seed = first_seed + static_cast<std::uint64_t>(k);
    for (int run = 0; run < runs; ++run) {
      const auto out = std::filesystem::temp_directory_path() / fmt::format("bench-courier-fortnight-{}", run);
      std::filesystem::remove_all(out);
      std::vector<double> samples;
      app::RunRequest request;
      request.deployment = *deployment;
      request.out = out;
      request.wrap_listener = [&samples](exec::Executor& ex) { return std::make_unique<TimingListener>(ex, samples); };
      const double t0 = bench::steady_seconds();
      auto result = app::run_deployment(request, std::cerr);
      if (!result) {
        fmt::print(stderr, "bench_courier_fortnight: {}\n", result.error().message);
        return 1;
      }
      const double wall = bench::steady_seconds() - t0;
      fmt::print("{:>6} {:>4} {:>7} {:>10.3f} {:>7.3f} {:>7.3f} {:>11.1f}\n", deployment->seed, run + 1, samples.size(),
                 1e3 * quantile(samples, 0.5), 1e3 * quantile(samples, 0.99),
                 samples.empty() ? 0.0 : 1e3 * *std::max_element(samples.begin(), samples.end()), wall);
      all.insert(all.end(), samples.begin(), samples.end());
      std::filesystem::remove_all(out);
    }
  }
  fmt::print("# all runs: {} breaks, median {:.3f} ms, p99 {:.3f} ms (goal < 20 ms); load average {}\n", all.size(),
             1e3 * quantile(all, 0.5), 1e3 * quantile(all, 0.99), bench::load_average());
  return 0;
}
