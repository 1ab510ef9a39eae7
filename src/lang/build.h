// From what a sentence says to core's values: the window of a one-off task, a routine's daily
// window and days, ids. Internal to rondo::lang.
#pragma once

#include <string>

#include "rondo/core/routine.h"
#include "rondo/core/task.h"
#include "rondo/lang/command.h"
#include "timing.h"

namespace rondo::lang::detail {

// What one task of the command does, before its timing is applied.
struct Job {
  std::string verb;      // "check", "patrol", "visit": the action name and the id's head
  std::string activity;  // for people: "check office A-123"
  std::string node;      // where
  Duration duration{0};  // the verb's default; "for ..." overrides it
};

// The local date and minute of `now`, "2026-11-23T10:00": the tail of the ids a command makes.
std::string id_tag(const CommandContext& ctx);

// A one-off task's kind and window: on-demand with "now", else a window on the day named
// (today by default) from the time words. Errors for a window already past or too short.
Status apply_one_off(const Timing& timing, const CommandContext& ctx, Task& task);

// The routine for `job` ("every ..."): daily window, `every`, days, first day today.
Result<Routine> make_routine(const Timing& timing, const CommandContext& ctx, const Job& job, int priority);

}  // namespace rondo::lang::detail
