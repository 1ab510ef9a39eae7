// Improvement of a feasible task order by segment relocation (or-opt, segments of 1..3 tasks moved
// forward or backward) and iterated perturbation. Private to src/schedule.
//
// Move evaluation: the moved part is simulated; where the new order rejoins the old one (the
// unchanged suffix), a delay beyond the suffix's forward slack rejects the move in O(1) (static
// travel), a non-negative delay with no gain so far rejects it as non-improving in O(1), and
// otherwise the change in the objective is propagated only until the old start times resume.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "instance.h"
#include "rondo/schedule/stop_condition.h"

namespace rondo::schedule::detail {

class OrderImprover {
 public:
  OrderImprover(const Instance& instance, std::uint64_t seed);

  // Descends to a local optimum. Precondition: `order` is feasible. Returns its objective.
  std::int64_t descend(std::vector<std::size_t>& order, const StopCondition& stop);
  // Perturb-and-descend until `stop`, keeping the best order in `best`. Returns its objective.
  std::int64_t iterate(std::vector<std::size_t>& best, const StopCondition& stop, std::int64_t max_rounds);

 private:
  void load(const std::vector<std::size_t>& order);
  void retime(std::size_t from);
  // Objective change of continuing the old order at position q after (time t, last task prev).
  // False when infeasible or (with `need_gain`) provably not improving given `delta`.
  bool propagate(std::size_t q, std::int64_t t, std::size_t prev, std::int64_t& delta, bool need_gain) const;
  // Simulates `tasks` after (t, prev); adds (end - old_end) to delta; false when infeasible.
  bool simulate(const std::size_t* tasks, std::size_t count, const std::int64_t* old_ends, std::int64_t& t,
                std::size_t& prev, std::int64_t& delta) const;
  bool try_forward(std::size_t i, std::size_t len, bool random_accept);
  bool try_backward(std::size_t i, std::size_t len, bool random_accept);
  bool accept(std::vector<std::size_t> candidate);
  bool perturb_once();

  const Instance& in_;
  std::mt19937_64 rng_;
  std::size_t n_;
  std::vector<std::size_t> order_;
  std::vector<std::int64_t> start_, end_, slack_;
  std::int64_t objective_ = 0;
  std::size_t backward_reach_ = 60;
};

}  // namespace rondo::schedule::detail
