// Balance (issue 38, "Balance"; Open-RMF's users ask for it in rmf_task#127: "I have 5 robots, and
// I always see 1 of it working"): an allocator that spreads work and battery across the robots,
// around any other allocator.
//
//   auto inner = std::make_unique<FleetSchedulerAllocator>();
//   BalancedAllocator balanced(std::move(inner));            // the deployment's `balance: true`
//
// Before the inner allocator sees a batch of units, each unit's eligible robots are narrowed:
// - work: a robot's load is the time it has spent on tasks so far (ExecutorStats::busy) plus the
//   remaining time of the tasks it has planned; the fleet's share after the batch is the mean load
//   of the able robots plus the batch's work spread over them. A robot whose load is above that
//   share by more than `work_margin` is passed over;
// - battery: a robot whose charge is below the best charge among the unit's robots by more than
//   `battery_margin` is passed over.
// A unit keeps every robot it had when the narrowing would leave it none, and a unit eligible on
// one robot only is left alone. Inside what is left, the inner allocator decides as always (the
// fleet scheduler's sum of end times already spreads a busy fleet's work; what balance adds is for
// a light load, where one robot near every task would otherwise do them all).
// Off by default: it sends a robot that is farther (docs/fleet.md, "Balance", gives what it costs).
#pragma once

#include <memory>

#include "rondo/fleet/allocator.h"

namespace rondo::fleet {

struct BalanceOptions {
  Duration work_margin = minutes(30);
  double battery_margin = 0.2;  // of a full charge
};

class BalancedAllocator final : public Allocator {
 public:
  explicit BalancedAllocator(std::unique_ptr<Allocator> inner, BalanceOptions options = {})
      : inner_(std::move(inner)), options_(options) {}
  std::vector<Allocation> allocate(const std::vector<AllocationUnit>& units,
                                   const std::vector<const exec::Executor*>& robots,
                                   const exec::Building& building) override;
  const Allocator& inner() const { return *inner_; }

 private:
  std::unique_ptr<Allocator> inner_;
  BalanceOptions options_;
};

// The narrowing alone, for tests: `units` with each one's eligible robots as BalancedAllocator
// gives them to its inner allocator. `loads` and `charges` per robot of `robots` (the same order).
std::vector<AllocationUnit> balanced_units(const std::vector<AllocationUnit>& units, const std::vector<Duration>& loads,
                                           const std::vector<double>& charges, const std::vector<bool>& able,
                                           const BalanceOptions& options);

}  // namespace rondo::fleet
