#include "request_intake.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <string>
#include <vector>

#include "rondo/core/task_codec.h"
#include "rondo/lang/command.h"
#include "rondo/service/said_again.h"
#include "rondo/service/stored_routines.h"
#include "rondo/store/requests.h"

namespace rondo::app {
namespace {

std::string about(const store::RequestRow& r) {
  return fmt::format("request {}", r.id);
}

// Refuses a request that cannot be carried out: its event and its mark, in one transaction.
void reject(fleet::Fleet& fleet, Time now, const store::RequestRow& r, const std::string& why) {
  fleet.reject_request({r.id, now, "rejected: " + why}, fmt::format("'{}': {}", r.sentence, why));
}

// The tasks the cancellation names that are not final yet, in the order they were added.
std::vector<TaskId> named_tasks(const fleet::Fleet& fleet, const lang::Cancellation& c) {
  std::vector<TaskId> ids;
  for (const TaskId& id : fleet.task_order()) {
    const exec::TaskRecord& r = fleet.tasks().at(id);
    if (!is_final(r.state) && lang::matches(c, r.task)) ids.push_back(id);
  }
  return ids;
}

void take_cancel(fleet::Fleet& fleet, store::Store& db, Time now, const store::RequestRow& r,
                 std::vector<std::string>& errors) {
  auto c = lang::decode_cancellation(r.body);
  if (!c) return reject(fleet, now, r, c.error().message);
  const std::vector<TaskId> ids = named_tasks(fleet, *c);
  if (ids.empty()) return reject(fleet, now, r, "no task that is not over yet matches it");
  int cancelled = 0;
  for (const TaskId& id : ids) {
    // Cancelling one half of a job may have ended the other already.
    if (is_final(fleet.tasks().at(id).state)) continue;
    if (fleet.cancel_task(id, fmt::format("{} '{}'", about(r), r.sentence))) ++cancelled;
  }
  if (auto ok = store::take_request(db, {r.id, now, fmt::format("applied: {} task(s) cancelled", cancelled)}); !ok)
    errors.push_back(ok.error().message);
}

// Routines are added to the fleet as POST /api/v1/routines adds them, and kept in the store
// (service/stored_routines.h) in the transaction that marks the request taken.
void take_routines(fleet::Fleet& fleet, store::Store& db, Time now, const store::RequestRow& r, TaskFile file,
                   std::vector<std::string>& errors) {
  if (!file.tasks.empty()) return reject(fleet, now, r, "it holds both tasks and routines");
  // A routine's times of day are local: in another zone than the deployment's they would not mean
  // what was said.
  if (!file.zone || file.zone->name() != fleet.zone().name())
    return reject(fleet, now, r,
                  fmt::format("its times are in {}, the deployment's in {}", file.zone ? file.zone->name() : "no zone",
                              fleet.zone().name()));
  std::vector<std::string> names;
  for (const Routine& routine : file.routines) names.push_back(routine.name);
  auto kept = service::stored_with_added(db, file.routines);
  if (!kept) {
    errors.push_back(kept.error().message);  // left waiting: read again next time
    return;
  }
  const std::string outcome = fmt::format("added {} routine(s): {}", names.size(), fmt::join(names, ", "));
  const store::RequestTaken taken{r.id, now, outcome, {{service::kStoredRoutinesKey, *kept}}};
  // A refusal (a name already taken, a node not on the map) is written and marked by the fleet.
  if (auto ok = fleet.add_routines_now(std::move(file.routines), taken, fmt::format("'{}': {}", r.sentence, outcome));
      !ok && ok.error().code != ErrorCode::kInvalidInput)
    errors.push_back(ok.error().message);
}

void take_tasks(fleet::Fleet& fleet, store::Store& db, Time now, const store::RequestRow& r,
                std::vector<std::string>& errors) {
  auto file = parse_task_file(r.body.dump(), DocumentFormat::kJson, about(r));
  if (!file) return reject(fleet, now, r, file.error().message);
  // The same sentence again (queued twice before the executive took the first): nothing to add.
  // Another that made the same ids gets its own ("~2" after them).
  lang::Command said{std::move(file->tasks), std::move(file->routines), std::nullopt};
  auto repeated = service::settle_against_fleet(said, fleet);
  if (!repeated) return reject(fleet, now, r, repeated.error().message);
  if (!repeated->empty()) {
    if (auto ok = store::take_request(db, {r.id, now, service::already_queued_text(*repeated)}); !ok)
      errors.push_back(ok.error().message);
    return;
  }
  file->tasks = std::move(said.tasks);
  file->routines = std::move(said.routines);
  if (!file->routines.empty()) return take_routines(fleet, db, now, r, std::move(*file), errors);
  if (file->tasks.empty()) return reject(fleet, now, r, "it holds no task");
  const std::size_t n = file->tasks.size();
  const store::RequestTaken taken{r.id, now, fmt::format("added {} task(s)", n)};
  // A refusal (an unknown node, an id already taken) is written and marked by the fleet.
  (void)fleet.add_tasks(std::move(file->tasks), "words", &taken);
}

}  // namespace

Result<int> RequestIntake::take_waiting() {
  RONDO_ASSIGN_OR_RETURN(const std::vector<store::RequestRow> waiting, store::waiting_requests(store_));
  std::vector<std::string> errors;
  for (const store::RequestRow& r : waiting) {
    const Time now = clock_.now();
    if (r.body.contains("cancel"))
      take_cancel(fleet_, store_, now, r, errors);
    else
      take_tasks(fleet_, store_, now, r, errors);
  }
  if (!errors.empty()) return Error::storage(errors.front());
  return static_cast<int>(waiting.size());
}

void RequestIntake::poll_every(Duration period) {
  (void)take_waiting();  // a queue that cannot be read now is read again next period
  clock_.schedule_after(period, [this, period] { poll_every(period); });
}

Duration intake_period(double speed) {
  return std::max(Duration{1}, Duration{static_cast<Duration::rep>(500.0 * speed)});
}

}  // namespace rondo::app
