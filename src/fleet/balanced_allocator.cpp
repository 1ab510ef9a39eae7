#include "rondo/fleet/balanced_allocator.h"

#include <algorithm>
#include <string>

namespace rondo::fleet {
namespace {

Duration work_of(const AllocationUnit& unit) {
  Duration work{0};
  for (const Task* t : unit.tasks) work += t->duration;
  return work;
}

Duration load_of(const exec::Executor& robot, const exec::Building& building) {
  Duration load = robot.stats().busy;
  for (const TaskId& id : robot.activity().planned)
    if (const exec::TaskRecord* r = building.book.find(id)) load += r->remaining();
  return load;
}

}  // namespace

std::vector<AllocationUnit> balanced_units(const std::vector<AllocationUnit>& units, const std::vector<Duration>& loads,
                                           const std::vector<double>& charges, const std::vector<bool>& able,
                                           const BalanceOptions& options) {
  Duration total{0}, batch{0};
  std::size_t working = 0;
  for (std::size_t r = 0; r < loads.size(); ++r)
    if (able[r]) {
      total += loads[r];
      ++working;
    }
  for (const AllocationUnit& u : units) batch += work_of(u);
  std::vector<AllocationUnit> out = units;
  if (working == 0) return out;
  const Duration share = (total + batch) / static_cast<std::int64_t>(working);
  for (AllocationUnit& u : out) {
    if (u.eligible.size() < 2) continue;
    double best_charge = 0;
    for (const std::size_t r : u.eligible) best_charge = std::max(best_charge, charges[r]);
    std::vector<std::size_t> kept;
    for (const std::size_t r : u.eligible)
      if (loads[r] <= share + options.work_margin && charges[r] >= best_charge - options.battery_margin)
        kept.push_back(r);
    if (!kept.empty()) u.eligible = std::move(kept);
  }
  return out;
}

std::vector<Allocation> BalancedAllocator::allocate(const std::vector<AllocationUnit>& units,
                                                    const std::vector<const exec::Executor*>& robots,
                                                    const exec::Building& building) {
  std::vector<Duration> loads;
  std::vector<double> charges;
  std::vector<bool> able;
  for (const exec::Executor* r : robots) {
    loads.push_back(load_of(*r, building));
    charges.push_back(r->robot().battery());
    able.push_back(r->able());
  }
  const std::vector<AllocationUnit> narrowed = balanced_units(units, loads, charges, able, options_);
  std::vector<Allocation> out = inner_->allocate(narrowed, robots, building);
  for (std::size_t u = 0; u < units.size() && u < out.size(); ++u) {
    std::string passed;
    for (const std::size_t r : units[u].eligible)
      if (std::find(narrowed[u].eligible.begin(), narrowed[u].eligible.end(), r) == narrowed[u].eligible.end())
        passed += (passed.empty() ? "" : ", ") + robots[r]->name();
    if (!passed.empty()) out[u].why += "; for balance, passed over " + passed;
  }
  return out;
}

}  // namespace rondo::fleet
