#include "rondo/service/said_again.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace rondo::service {

Result<std::vector<std::string>> settle_against_fleet(lang::Command& command, const fleet::Fleet& fleet) {
  const auto task_held = [&fleet](const Task& said) {
    auto found = fleet.task(said.id);
    if (!found) return lang::Held::kOther;
    if (!*found) return lang::Held::kFree;
    const exec::TaskRecord& held = **found;
    return !is_final(held.state) && held.task == said ? lang::Held::kSame : lang::Held::kOther;
  };
  const auto routine_held = [&fleet](const Routine& said) {
    for (const Routine& r : fleet.routines()) {
      if (r.name == said.name) return lang::same_routine(said, r) ? lang::Held::kSame : lang::Held::kOther;
    }
    return lang::Held::kFree;
  };
  return lang::settle_ids(command, task_held, routine_held);
}

std::string already_queued_text(const std::vector<std::string>& ids) {
  return fmt::format("already queued: {}", fmt::join(ids, ", "));
}

}  // namespace rondo::service
