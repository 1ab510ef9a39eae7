// A finished task read back from the store: the record the book had of it (restore after a
// restart, and TaskBook::lookup() of a task that has left memory).
#include <fmt/format.h>

#include "rondo/core/document.h"
#include "rondo/core/task_codec.h"
#include "rondo/exec/task_book.h"

namespace rondo::exec {
namespace {

Result<Task> decode_stored(const store::TaskRow& row, const TimeZone& zone) {
  RONDO_ASSIGN_OR_RETURN(
      Document doc, Document::parse(row.task.dump(), DocumentFormat::kJson, fmt::format("stored task {}", row.id)));
  return decode_task(doc.root(), &zone);
}

Outcome stored_outcome(const std::optional<store::Event>& e) {
  if (!e) return Outcome::kNone;
  return parse_outcome(e->code).value_or(Outcome::kNone);
}

}  // namespace

Result<TaskRecord> record_of(const store::StoredTask& stored, const TimeZone& zone) {
  const store::TaskRow& row = stored.row;
  auto task = decode_stored(row, zone);
  if (!task) return Error::storage(fmt::format("stored task {}: {}", row.id, task.error().message));
  if (task->id != row.id)
    return Error::storage(fmt::format("stored task {}: its JSON names the id '{}'", row.id, task->id));
  auto state = parse_task_state(row.state);
  if (!state) return Error::storage(fmt::format("stored task {}: {}", row.id, state.error().message));
  TaskRecord r{.task = std::move(*task),
               .robot = row.robot,
               .state = *state,
               .outcome = stored_outcome(stored.last_transition),
               .reason = stored.last_transition ? stored.last_transition->reason : std::string(),
               .source = row.source,
               .added = row.created};
  if (is_final(r.state)) {
    r.ended = stored.last_transition ? stored.last_transition->time : row.updated;
    // What it was planned to do (a task not finished is planned again by the next schedule).
    r.planned_start = row.planned_start;
    r.planned_end = row.planned_end;
  }
  // Its progress: a re-run goes on after the actions already done; a door it waited for.
  TaskBook::read_progress(row.progress, r);
  if (r.state == TaskState::kQueued && stored.dropped_for_now)
    r.dropped_for_now = std::make_pair(stored_outcome(stored.dropped_for_now), stored.dropped_for_now->reason);
  return r;
}

}  // namespace rondo::exec
