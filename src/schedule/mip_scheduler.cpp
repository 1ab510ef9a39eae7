#include "rondo/schedule/mip_scheduler.h"

#include <algorithm>
#include <initializer_list>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "instance.h"

// CBC's headers are included as system headers (see CMakeLists.txt) and are not warning-clean.
#include <CbcEventHandler.hpp>
#include <CbcModel.hpp>
#include <CbcSolver.hpp>
#include <CoinPackedMatrix.hpp>
#include <OsiClpSolverInterface.hpp>

namespace rondo::schedule {

namespace {

using detail::Instance;

// Asks CBC to stop at its next node once the caller's stop condition fires.
class StopHandler final : public CbcEventHandler {
 public:
  explicit StopHandler(const StopCondition& condition) : stop_(&condition) {}
  CbcAction event(CbcEvent) override { return stop_->should_stop() ? stop : noAction; }
  CbcEventHandler* clone() const override { return new StopHandler(*this); }

 private:
  const StopCondition* stop_;
};

double to_s(std::int64_t ms) { return static_cast<double>(ms) / 1000.0; }

}  // namespace

Status MipScheduler::check_supported(const Problem& p) {
  if (p.robot.capacity > 0) return Error::unsupported("the MIP of the paper has no capacity constraint");
  for (const auto& t : p.tasks)
    if (t.transfer && !t.transfer->appearance.empty())
      return Error::unsupported("the MIP of the paper has no rule for same-looking items");
  if (p.return_to) return Error::unsupported("the MIP of the paper has no return to a depot");
  if (p.window_travel) return Error::unsupported("the MIP of the paper has no chance constraint");
  return {};
}

Schedule MipScheduler::solve(const Problem& problem, const StopCondition& stop) {
  fixed_pairs_ = 0;
  Schedule none;
  none.status = SolveStatus::kTimeout;
  if (!check_supported(problem)) return none;
  const Instance in(problem);
  const std::size_t n = in.size();
  if (n == 0) return in.to_schedule({}, SolveStatus::kOptimal);

  // Precedence closure for fixing pairs: before[j][k] = j must precede k.
  std::vector<std::vector<char>> before(n, std::vector<char>(n, 0));
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t j : in.predecessors(k)) before[j][k] = 1;

  // Columns: s_0..s_{n-1}, then y_jk for j < k.
  std::vector<double> lower(n), upper(n), cost(n, 1.0);
  std::vector<std::int64_t> earliest(n);
  for (std::size_t i = 0; i < n; ++i) {
    earliest[i] = std::max(in.release(i), in.travel(n, i, 0));
    lower[i] = to_s(earliest[i]);
    upper[i] = to_s(std::max(in.latest(i), earliest[i]));
    if (in.latest(i) < earliest[i]) {
      none.status = SolveStatus::kInfeasible;
      return none;
    }
  }
  // Rows as triplets, assembled once (appending rows one by one is quadratic in CoinUtils).
  std::vector<int> row_index, column_index;
  std::vector<double> element;
  std::vector<double> row_lower, row_upper;
  auto add_row = [&](std::initializer_list<std::pair<int, double>> terms, double ub) {
    const auto r = static_cast<int>(row_upper.size());
    for (const auto& [c, v] : terms) {
      row_index.push_back(r);
      column_index.push_back(c);
      element.push_back(v);
    }
    row_lower.push_back(-COIN_DBL_MAX);
    row_upper.push_back(ub);
  };
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = j + 1; k < n; ++k) {
      const int y = static_cast<int>(n + pairs.size());
      pairs.push_back({j, k});
      const std::int64_t ejk = in.travel(j, k, 0), ekj = in.travel(k, j, 0);
      bool j_first_ok = earliest[j] + in.duration(j) + ejk <= in.latest(k) && !before[k][j];
      bool k_first_ok = earliest[k] + in.duration(k) + ekj <= in.latest(j) && !before[j][k];
      if (!options_.interval_algebra) {
        // The full model fixes only the pairs the problem itself orders (precedence).
        j_first_ok = !before[k][j];
        k_first_ok = !before[j][k];
      }
      if (!j_first_ok && !k_first_ok) {
        none.status = SolveStatus::kInfeasible;
        return none;
      }
      double y_lower = 0, y_upper = 1;
      if (!j_first_ok) y_upper = 0;
      if (!k_first_ok) y_lower = 1;
      if (y_lower == y_upper) ++fixed_pairs_;
      lower.push_back(y_lower);
      upper.push_back(y_upper);
      cost.push_back(0.0);
      const double m_jk = std::max(0.0, upper[j] + to_s(in.duration(j) + ejk) - lower[k]);
      const double m_kj = std::max(0.0, upper[k] + to_s(in.duration(k) + ekj) - lower[j]);
      const int cj = static_cast<int>(j), ck = static_cast<int>(k);
      if (j_first_ok && k_first_ok) {
        // (y = 1): s_j + p_j + E_jk <= s_k;  (y = 0): s_k + p_k + E_kj <= s_j.
        add_row({{cj, 1.0}, {ck, -1.0}, {y, m_jk}}, m_jk - to_s(in.duration(j) + ejk));
        add_row({{ck, 1.0}, {cj, -1.0}, {y, -m_kj}}, -to_s(in.duration(k) + ekj));
      } else if (j_first_ok) {
        add_row({{cj, 1.0}, {ck, -1.0}}, -to_s(in.duration(j) + ejk));
      } else {
        add_row({{ck, 1.0}, {cj, -1.0}}, -to_s(in.duration(k) + ekj));
      }
    }
    if (stop.should_stop()) return none;  // building a large model takes time too
  }
  const int columns = static_cast<int>(lower.size());
  CoinPackedMatrix rows(false, row_index.data(), column_index.data(), element.data(),
                        static_cast<CoinBigIndex>(element.size()));
  rows.setDimensions(static_cast<int>(row_lower.size()), columns);

  OsiClpSolverInterface lp;
  lp.messageHandler()->setLogLevel(0);
  lp.setHintParam(OsiDoReducePrint, true, OsiHintTry);
  lp.loadProblem(rows, lower.data(), upper.data(), cost.data(), row_lower.data(), row_upper.data());
  for (int c = static_cast<int>(n); c < columns; ++c) lp.setInteger(c);

  double limit = to_seconds(options_.time_limit);
  if (auto left = stop.seconds_left()) limit = std::min(limit, *left);
  limit = std::max(limit, 0.01);
  CbcModel model(lp);
  model.setLogLevel(0);
  model.messageHandler()->setLogLevel(0);
  StopHandler handler(stop);
  model.passInEventHandler(&handler);
  CbcMain0(model);
  model.setLogLevel(0);
  const std::string seconds_arg = fmt::format("{:.3f}", limit);
  const char* argv[] = {"rondo", "-log", "0", "-slog", "0", "-threads", "0", "-timeMode", "elapsed", "-seconds", seconds_arg.c_str(),
                        "-solve", "-quit"};
  CbcMain1(static_cast<int>(std::size(argv)), argv, model);

  const double* solution = model.bestSolution();
  if (solution == nullptr) {
    none.status = model.isProvenInfeasible() ? SolveStatus::kInfeasible : SolveStatus::kTimeout;
    return none;
  }
  // The order: by start time, ties broken by the pair variables.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<double> start(solution, solution + n);
  auto y_of = [&](std::size_t j, std::size_t k) {  // j before k?
    const std::size_t a = std::min(j, k), b = std::max(j, k);
    const std::size_t index = a * n - a * (a + 1) / 2 + (b - a - 1);
    const bool a_first = solution[n + index] > 0.5;
    return j == a ? a_first : !a_first;
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (std::abs(start[a] - start[b]) > 1e-6) return start[a] < start[b];
    return a != b && y_of(a, b);
  });
  const bool proved = model.isProvenOptimal() && !model.isSecondsLimitReached();
  Schedule s = in.to_schedule(order, proved ? SolveStatus::kOptimal : SolveStatus::kFeasible);
  if (s.entries.size() != n) return none;  // cannot happen for static travel
  // The bound of the model, in the objective's units (sum of ends = sum of starts + durations).
  std::int64_t durations = 0;
  for (std::size_t i = 0; i < n; ++i) durations += in.duration(i);
  const double bound = proved ? model.getObjValue() : model.getBestPossibleObjValue();
  const auto bound_ms = static_cast<std::int64_t>(std::ceil(bound * 1000.0 - 1e-6)) + durations;
  s.lower_bound = Duration{std::min(bound_ms, s.objective.count())};
  if (proved) s.lower_bound = s.objective;
  return s;
}

}  // namespace rondo::schedule
