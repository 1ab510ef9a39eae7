// A command in words said again, against the running fleet (docs/commands.md, "Saying it
// again"): lang::settle_ids with the fleet's tasks and routines as what holds the ids. Used by
// POST /api/v1/commands and by the request queue's intake (`rondo task add --data`).
//
//   auto repeated = settle_against_fleet(command, fleet);   // on the clock's thread
//   if (repeated && !repeated->empty()) ...  // "already queued: <ids>": nothing to add
//   // else command's ids are free (renamed "~2", ... when a different task held them)
#pragma once

#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/fleet/fleet.h"
#include "rondo/lang/command.h"

namespace rondo::service {

// An id is held the same by a task that is not over and equal to the one said, or by a routine
// lang::same_routine() finds the same; a task the store cannot read back counts as another's.
Result<std::vector<std::string>> settle_against_fleet(lang::Command& command, const fleet::Fleet& fleet);

// "already queued: a, b"
std::string already_queued_text(const std::vector<std::string>& ids);

}  // namespace rondo::service
