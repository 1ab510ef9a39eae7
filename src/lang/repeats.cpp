// A sentence said again: its command against the ids the executive holds (command.h, settle_ids).
#include <fmt/format.h>

#include "rondo/lang/command.h"

namespace rondo::lang {
namespace {

constexpr int kMostSayings = 100;  // "~2" .. "~100"

// The command's ids with "~n" after them (n > 1): the tasks', their delivery jobs', the tasks they
// come after (all made by the same sentence), and the routines' names.
Command renamed(const Command& c, int n) {
  if (n == 1) return c;
  const std::string tail = fmt::format("~{}", n);
  Command out = c;
  for (Task& t : out.tasks) {
    t.id += tail;
    if (t.delivery) t.delivery->job += tail;
    for (TaskId& a : t.after) a += tail;
  }
  for (Routine& r : out.routines) r.name += tail;
  return out;
}

}  // namespace

bool same_routine(const Routine& said, const Routine& held) {
  Routine as_held = said;
  if (said.first_day && held.first_day && *held.first_day <= *said.first_day) as_held.first_day = held.first_day;
  return as_held == held;
}

Result<std::vector<std::string>> settle_ids(Command& c, const std::function<Held(const Task&)>& task_held,
                                            const std::function<Held(const Routine&)>& routine_held) {
  if (c.tasks.empty() && c.routines.empty()) return std::vector<std::string>{};
  for (int n = 1; n <= kMostSayings; ++n) {
    Command candidate = renamed(c, n);
    bool free = true;
    bool same = true;
    std::vector<std::string> ids;
    for (const Task& t : candidate.tasks) {
      const Held h = task_held(t);
      free = free && h == Held::kFree;
      same = same && h == Held::kSame;
      ids.push_back(t.id);
    }
    for (const Routine& r : candidate.routines) {
      const Held h = routine_held(r);
      free = free && h == Held::kFree;
      same = same && h == Held::kSame;
      ids.push_back(r.name);
    }
    if (same) return ids;
    if (free) {
      c = std::move(candidate);
      return std::vector<std::string>{};
    }
  }
  return Error{ErrorCode::kConflict,
               fmt::format("'{}' and {} more ids after it are all taken", c.tasks.empty() ? c.routines.front().name
                                                                                            : c.tasks.front().id,
                           kMostSayings - 1)};
}

}  // namespace rondo::lang
