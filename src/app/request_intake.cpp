#include "request_intake.h"

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "rondo/core/task_codec.h"
#include "rondo/lang/command.h"
#include "rondo/store/requests.h"

namespace rondo::app {
namespace {

std::string about(const store::RequestRow& r) {
  return fmt::format("request {}", r.id);
}

// Refuses a request that cannot be carried out: its event and its mark, in one transaction.
void reject(exec::Executor& executor, Time now, const store::RequestRow& r, const std::string& why) {
  executor.reject_request({r.id, now, "rejected: " + why}, fmt::format("'{}': {}", r.sentence, why));
}

// The tasks the cancellation names that are not final yet, in the order they were added.
std::vector<TaskId> named_tasks(const exec::Executor& executor, const lang::Cancellation& c) {
  std::vector<TaskId> ids;
  for (const TaskId& id : executor.task_order()) {
    const exec::TaskRecord& r = executor.tasks().at(id);
    if (!is_final(r.state) && lang::matches(c, r.task)) ids.push_back(id);
  }
  return ids;
}

void take_cancel(exec::Executor& executor, store::Store& db, Time now, const store::RequestRow& r,
                 std::vector<std::string>& errors) {
  auto c = lang::decode_cancellation(r.body);
  if (!c) return reject(executor, now, r, c.error().message);
  const std::vector<TaskId> ids = named_tasks(executor, *c);
  if (ids.empty()) return reject(executor, now, r, "no task that is not over yet matches it");
  int cancelled = 0;
  for (const TaskId& id : ids) {
    // Cancelling one half of a job may have ended the other already.
    if (is_final(executor.tasks().at(id).state)) continue;
    if (executor.cancel_task(id, fmt::format("{} '{}'", about(r), r.sentence))) ++cancelled;
  }
  if (auto ok = store::take_request(db, {r.id, now, fmt::format("applied: {} task(s) cancelled", cancelled)}); !ok)
    errors.push_back(ok.error().message);
}

void take_tasks(exec::Executor& executor, Time now, const store::RequestRow& r) {
  auto file = parse_task_file(r.body.dump(), DocumentFormat::kJson, about(r));
  if (!file) return reject(executor, now, r, file.error().message);
  if (!file->routines.empty())
    return reject(executor, now, r, "routines cannot be queued (add them to the deployment or through the API)");
  if (file->tasks.empty()) return reject(executor, now, r, "it holds no task");
  const std::size_t n = file->tasks.size();
  const store::RequestTaken taken{r.id, now, fmt::format("added {} task(s)", n)};
  // A refusal (an unknown node, an id already taken) is written and marked by the executor.
  (void)executor.add_tasks(std::move(file->tasks), "words", &taken);
}

}  // namespace

Result<int> RequestIntake::take_waiting() {
  RONDO_ASSIGN_OR_RETURN(const std::vector<store::RequestRow> waiting, store::waiting_requests(store_));
  std::vector<std::string> errors;
  for (const store::RequestRow& r : waiting) {
    const Time now = clock_.now();
    if (r.body.contains("cancel"))
      take_cancel(executor_, store_, now, r, errors);
    else
      take_tasks(executor_, now, r);
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
