// Commands in words (docs/commands.md): one English sentence to what a task file holds (tasks and
// routines, built with core's Task and Routine) or to a request to cancel tasks.
//
//   CommandContext ctx{.places = &places, .zone = london, .now = *parse_time("2026-11-23T10:00:00Z")};
//   Result<Command> c = parse_command(
//       "deliver the green book from the librarian's desk in room A-110 to the desk in room A-114", ctx);
//   // c->tasks: a pickup at A-110-Desk and a drop at A-114-Desk, one delivery job, drop after pickup
//   Result<Command> x = parse_command("cancel the delivery of the red letter", ctx);
//   // x->cancel: {what: delivery, object: "red letter"}; matches(*x->cancel, task) finds the tasks
//
// A sentence outside the grammar, or a place that does not resolve, is an Error naming the word
// or phrase (kNotFound for places, with the nearest known ones; kInvalidInput otherwise). The
// parser never guesses: an ambiguous split of the words is an error too.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/routine.h"
#include "rondo/core/task.h"
#include "rondo/core/time.h"
#include "rondo/core/timezone.h"
#include "rondo/lang/places.h"

namespace rondo::lang {

// Which tasks "cancel ..." means.
struct Cancellation {
  enum class What {
    kDelivery,  // "cancel the delivery of the red letter": both halves of the jobs carrying `object`
    kActivity,  // "cancel the check of A-123": tasks doing `activity` (an action name) at `nodes`
    kTask,      // "cancel task check-a-123@2026-11-23T10:00": the task `id` (or a routine's instances)
  };
  What what = What::kDelivery;
  std::string object;              // kDelivery: normalised description, e.g. "red letter"
  std::string activity;            // kActivity: "check", "patrol" or "visit"
  std::vector<std::string> nodes;  // kActivity: where
  std::string id;                  // kTask
  bool operator==(const Cancellation&) const = default;
};

// What one sentence means: tasks and routines (a task file's contents), or a cancellation.
struct Command {
  std::vector<Task> tasks;
  std::vector<Routine> routines;
  std::optional<Cancellation> cancel;
  bool operator==(const Command&) const = default;
};

struct CommandContext {
  const Places* places = nullptr;   // required
  TimeZone zone = TimeZone::utc();  // local times ("before 15:00", "today") are read in it
  Time now{};                       // what "now" and "today" mean
};

// The longest sentence read, in bytes; a longer one is an error.
inline constexpr std::size_t kMaxSentence = 2000;

Result<Command> parse_command(std::string_view sentence, const CommandContext& ctx);

// Whether the task is one the cancellation names. A routine instance ("name@...") matches a kTask
// cancellation of its routine's name.
bool matches(const Cancellation& c, const Task& task);

// Who holds an id (or a routine's name) that a command made, as the executive that would add it
// sees it: nobody; the same task (routine) still to do, so that the command was said before; or
// anything else (another task, a task that is over, a routine of other times).
enum class Held { kFree, kSame, kOther };

// A sentence said again (docs/commands.md, "Saying it again"). Its ids are those of the first
// saying when it comes in the same minute, so against what the executive holds a command is:
// - a repeat, when every task (routine) of it is held by the same one still to do: the ids (names)
//   it repeats are returned, and there is nothing to add;
// - new otherwise: nothing is returned, and the command's ids are made free of every id held,
//   by the first "~N" (N = 2, 3, ...) after them all (a delivery's job and `after` alike) that
//   leaves every one of them free, or held by the same one (then it is a repeat of those).
// A cancellation is always new. kConflict when 100 such ids are all held by others.
Result<std::vector<std::string>> settle_ids(Command& c, const std::function<Held(const Task&)>& task_held,
                                            const std::function<Held(const Routine&)>& routine_held);

// Whether routine `held` is what `said` asks for: equal, except that one held since an earlier
// first day covers a later one (the same routine said again on another day).
bool same_routine(const Routine& said, const Routine& held);

// {"cancel": {"what": "delivery", "object": "red letter"}} and the like (docs/commands.md).
Json encode(const Cancellation& c);
// The reverse of encode(): kInvalidInput naming the field when `j` is not such an object.
Result<Cancellation> decode_cancellation(const Json& j);
const char* to_string(Cancellation::What what);

}  // namespace rondo::lang
