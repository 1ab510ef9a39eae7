#include "rondo/schedule/default_scheduler.h"

#include <algorithm>

#include "instance.h"
#include "label_dp.h"
#include "local_search.h"

namespace rondo::schedule {

namespace {

using detail::Instance;
using detail::LabelDpOptions;
using detail::LabelDpResult;
using detail::OrderImprover;

// Stops when the parent does, or when only `keep` of the parent's budget (seconds) is left: gives
// one phase a share of a time budget without reading a clock.
class ShareStop final : public StopCondition {
 public:
  ShareStop(const StopCondition& parent, double keep_seconds) : parent_(parent), keep_(keep_seconds) {}
  bool should_stop() const override {
    if (parent_.should_stop()) return true;
    auto left = parent_.seconds_left();
    return left && *left <= keep_;
  }
  std::optional<double> seconds_left() const override {
    auto left = parent_.seconds_left();
    if (!left) return std::nullopt;
    return *left - keep_;
  }

 private:
  const StopCondition& parent_;
  double keep_;
};

struct Incumbent {
  std::vector<std::size_t> order;
  std::int64_t objective = detail::kNever;
  bool found() const { return objective < detail::kNever; }
  void offer(const std::vector<std::size_t>& o, std::int64_t obj) {
    if (obj < objective) {
      order = o;
      objective = obj;
    }
  }
};

}  // namespace

Schedule DefaultScheduler::solve(const Problem& problem, const StopCondition& stop) {
  const Instance in(problem);
  const std::size_t n = in.size();
  Incumbent best;
  OrderImprover improver(in, options_.seed);
  bool proved = false, proved_infeasible = false;

  auto improve = [&](std::vector<std::size_t> order, const StopCondition& s) {
    if (options_.improve && !order.empty()) improver.descend(order, s);
    const auto timing = in.time(order);
    if (timing.feasible) best.offer(order, timing.objective);
  };
  auto beam = [&](std::size_t width, const StopCondition& s) {
    LabelDpResult r = detail::run_label_dp(in, LabelDpOptions{.beam_width = width}, s);
    if (r.outcome == LabelDpResult::Outcome::kFound) improve(std::move(r.order), s);
    return r.outcome;
  };

  // 1. A first schedule: restricted dynamic programs of growing width.
  std::size_t width = std::max<std::size_t>(1, options_.first_beam_width);
  while (!best.found() && !stop.should_stop()) {
    beam(width, stop);
    if (width >= options_.max_beam_width) break;
    width *= 4;
  }

  // 2. Small problems: prove the optimum (or infeasibility) with the exact dynamic program, given
  //    half of what is left of a time budget.
  if (n <= options_.exact_max_tasks && !stop.should_stop()) {
    // A good upper bound first pays off when the exact program is large; tiny ones prove at once.
    if (best.found() && options_.improve && n > 20) {
      std::vector<std::size_t> o = best.order;
      const auto left = stop.seconds_left();
      ShareStop quick(stop, left ? *left * 0.9 : 0.0);
      best.offer(o, improver.iterate(o, quick, 30));
    }
    const auto left = stop.seconds_left();
    ShareStop half(stop, left ? *left * 0.3 : 0.0);
    LabelDpOptions exact{.beam_width = 0,
                         .max_labels_per_stage = options_.exact_max_labels,
                         .upper_bound = best.objective};
    LabelDpResult r = detail::run_label_dp(in, exact, half);
    if (r.outcome == LabelDpResult::Outcome::kFound) best.offer(r.order, r.objective);
    if (r.exhaustive && r.outcome != LabelDpResult::Outcome::kAborted) {
      proved = best.found();
      proved_infeasible = !best.found();
    }
  }

  // 3. Anytime improvement: iterated local search, interleaved with wider restricted programs.
  if (!proved && !proved_infeasible && options_.improve) {
    const bool budgeted = stop.seconds_left().has_value();
    while (!stop.should_stop()) {
      if (best.found()) {
        std::vector<std::size_t> o = best.order;
        best.offer(o, improver.iterate(o, stop, 200));
      }
      if (width < options_.max_beam_width) {
        width *= 2;
        beam(width, stop);
      } else if (!budgeted || !best.found()) {
        // No time budget: stop once the widest program has run. No schedule after the widest
        // program: nothing is left to improve, and waiting for the deadline (a problem that does
        // not fit) would spend the whole budget of a caller that drops tasks and asks again.
        break;
      }
    }
  }

  Schedule s;
  if (best.found()) {
    s = in.to_schedule(best.order, proved ? SolveStatus::kOptimal : SolveStatus::kFeasible);
    if (proved) s.lower_bound = s.objective;
  } else {
    s.status = proved_infeasible ? SolveStatus::kInfeasible : SolveStatus::kTimeout;
  }
  return s;
}

}  // namespace rondo::schedule
