// The event log's names: every EventKind has a name of its own that parses back, none is also the
// name of a task state (a state change is named by its state; one word means one thing in the
// log), and the outcome codes parse back too.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "rondo/core/task.h"
#include "rondo/exec/event_kind.h"
#include "rondo/exec/outcome.h"

namespace rondo::exec {
namespace {

TEST(EventKind, EveryKindHasItsOwnNameThatParsesBack) {
  std::set<std::string> names;
  for (const EventKind kind : all_event_kinds()) {
    const std::string name(to_string(kind));
    EXPECT_FALSE(name.empty());
    EXPECT_TRUE(names.insert(name).second) << "two kinds named '" << name << "'";
    EXPECT_EQ(parse_event_kind(name), kind) << name;
  }
  EXPECT_FALSE(parse_event_kind("no such event"));
  EXPECT_FALSE(parse_event_kind(""));
}

TEST(EventKind, NoKindIsNamedLikeATaskState) {
  for (const TaskState state :
       {TaskState::kQueued, TaskState::kWaiting, TaskState::kNavigating, TaskState::kActing, TaskState::kSucceeded,
        TaskState::kFailed, TaskState::kCancelled, TaskState::kPreempted, TaskState::kDropped})
    EXPECT_FALSE(parse_event_kind(to_string(state))) << to_string(state);
}

TEST(Outcome, EveryCodeParsesBack) {
  for (const Outcome code : all_outcomes()) EXPECT_EQ(parse_outcome(to_string(code)), code) << to_string(code);
}

}  // namespace
}  // namespace rondo::exec
