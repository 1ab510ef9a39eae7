// The executor rescheduling on a worker (ExecutorOptions::background_scheduling, `rondo serve`):
// a change asks for a reschedule and returns; the problem is built later on the clock's thread
// (one for every request made meanwhile), solved by the BackgroundScheduler while the old
// schedule keeps running, and its answer is carried out only when the book has not moved on in a
// way it does not cover. Otherwise the problem is built and solved again.
#include <fmt/format.h>

#include <algorithm>

#include "background_scheduler.h"
#include "rondo/exec/executor.h"
#include "rondo/store/batch.h"
#include "scheduling.h"
#include "task_run.h"

namespace rondo::exec {

struct Executor::Background {
  // What the problem in flight was built from.
  struct InFlight {
    std::vector<TaskId> ids;      // its tasks, as ScheduleCall::pending.ids
    std::vector<TaskId> new_ids;  // the new ones among them (asked again when it comes too late)
    std::string why;
    std::optional<TaskId> current;  // the task waited for, navigated to or acted on
    bool waiting = false;           //   and whether it was waited for
  };

  std::unique_ptr<BackgroundScheduler> worker;
  bool wanted = false;          // a reschedule was asked for since the last problem was built
  bool launch_posted = false;   // launch_background() is posted
  bool changed = false;         // a change the problem in flight does not cover
  std::vector<TaskId> new_ids;  // asked for since the last problem
  std::vector<std::string> whys;
  std::uint64_t generation = 0;  // problems built
  std::optional<InFlight> in_flight;
  // The models handed to the worker, shared by every problem until they change (a copy of every
  // edge's online state for each reschedule cost the clock's thread more than the rest of it).
  std::shared_ptr<const plan::LearnedEdgeModels> models;
  std::shared_ptr<bool> alive = std::make_shared<bool>(true);  // for callbacks posted to the clock

  ~Background() { *alive = false; }
};

void Executor::BackgroundDeleter::operator()(Background* b) const {
  delete b;
}

namespace {

// The reasons of a merged reschedule, as one: the first few and how many more.
std::string merged_why(const std::vector<std::string>& whys) {
  constexpr std::size_t kShown = 3;
  std::string out;
  for (std::size_t i = 0; i < whys.size() && i < kShown; ++i) out += (i == 0 ? "" : "; ") + whys[i];
  if (whys.size() > kShown) out += fmt::format(" and {} more", whys.size() - kShown);
  return out;
}

}  // namespace

void Executor::reschedule_in_background(std::vector<TaskId> new_ids, const std::string& why) {
  if (!background_) {
    background_.reset(new Background);
    background_->worker = std::make_unique<BackgroundScheduler>(
        clock_, map_, *scheduler_,
        BackgroundScheduler::Options{.polls = options_.scheduler_polls,
                                     .budget = options_.background_budget,
                                     .min_interval = options_.background_interval,
                                     .slot_width = options_.slot_width,
                                     .route_threshold = options_.route_threshold,
                                     .seed = options_.seed},
        [this](ScheduleAnswer answer) { background_answered(std::move(answer)); },
        [this] {
          if (background_->wanted) launch_background();
        });
  }
  Background& bg = *background_;
  for (TaskId& id : new_ids)
    if (std::find(bg.new_ids.begin(), bg.new_ids.end(), id) == bg.new_ids.end()) bg.new_ids.push_back(std::move(id));
  if (std::find(bg.whys.begin(), bg.whys.end(), why) == bg.whys.end()) bg.whys.push_back(why);
  bg.wanted = true;
  if (bg.launch_posted || !bg.worker->ready()) return;  // the worker's ready callback launches it
  bg.launch_posted = true;
  // Posted, not built now: the other requests already waiting for the clock join this problem.
  clock_.post([this, alive = bg.alive] {
    if (!*alive) return;
    background_->launch_posted = false;
    launch_background();
  });
}

void Executor::launch_background() {
  Background& bg = *background_;
  if (!bg.wanted || !bg.worker->ready()) return;
  bg.wanted = false;
  bg.changed = false;
  std::vector<TaskId> new_ids = std::move(bg.new_ids);
  bg.new_ids.clear();
  // A task asked for while the worker was busy may have ended since (cancelled, or its delivery
  // cancelled) and, with forget_finished, left the book: it is no longer the scheduler's.
  std::erase_if(new_ids, [this](const TaskId& id) { return book_.finished(id); });
  const std::string why = merged_why(bg.whys);
  bg.whys.clear();
  std::vector<TaskId> held_over;
  std::optional<ScheduleCall> call = prepare_schedule(new_ids, why, &held_over);
  if (!held_over.empty()) {  // the next problem takes them (the ready callback launches it)
    for (TaskId& id : held_over) bg.new_ids.push_back(std::move(id));
    bg.whys.push_back(why);
    bg.wanted = true;
  }
  if (!call) return;
  bg.in_flight = Background::InFlight{.ids = call->pending.ids,
                                      .new_ids = std::move(new_ids),
                                      .why = why,
                                      .current = current_task(),
                                      .waiting = run_ && run_->waiting()};
  ++bg.generation;
  if (!bg.models || bg.models->version() != models_.version())
    bg.models = std::make_shared<const plan::LearnedEdgeModels>(models_);
  bg.worker->submit({.generation = bg.generation, .problem = std::move(call->problem), .models = bg.models});
}

void Executor::background_book_changed() {
  if (background_) background_->changed = true;
}

void Executor::background_answered(ScheduleAnswer answer) {
  Background& bg = *background_;
  stats_.background_travel_policies = answer.travel_policies;
  if (!bg.in_flight || answer.generation != bg.generation) return;
  Background::InFlight f = std::move(*bg.in_flight);
  bg.in_flight.reset();
  ++stats_.background_runs;
  // Still valid: the same task runs (or is waited for), each of its tasks that has not ended
  // still waits to run, and no change it does not cover came meanwhile. New tasks added meanwhile
  // are not in it; the reschedule they asked for follows. A task that ended meanwhile (cancelled,
  // failed) is left out when the answer is applied: the others' times stay reachable without it,
  // and its end asked for a reschedule of its own. Were it to make the answer stale, a load that
  // cancels tasks within a solve's time of their acceptance would make every answer stale, and a
  // takeover, which starts with no schedule, would never send the robot anywhere.
  const bool waiting = run_ && run_->waiting();
  bool valid = !bg.changed && current_task() == f.current && waiting == f.waiting;
  for (const TaskId& id : f.ids) {
    if (!valid) break;
    if (book_.finished(id)) continue;
    // A task blocked by a door seen closed meanwhile is no longer the scheduler's to place.
    valid = !blocked(id) && (current_task() != id || waiting);
  }
  std::erase_if(f.new_ids, [this](const TaskId& id) { return book_.finished(id); });
  if (!valid) {
    ++stats_.background_stale;
    // Asked again, with what came meanwhile (the ready callback launches it).
    for (TaskId& id : f.new_ids)
      if (book_.contains(id) && !is_final(book_.at(id).state) &&
          std::find(bg.new_ids.begin(), bg.new_ids.end(), id) == bg.new_ids.end())
        bg.new_ids.push_back(std::move(id));
    if (std::find(bg.whys.begin(), bg.whys.end(), f.why) == bg.whys.end()) bg.whys.insert(bg.whys.begin(), f.why);
    bg.wanted = true;
    return;
  }
  {
    // Every event of the answer (a "scheduled" per moved task, drops) in one commit: requests
    // waiting for the clock's thread wait for one sync, not one per task.
    store::Batch batch(store_);
    finish_schedule(f.ids, std::move(f.new_ids), answer.result, f.why);
    if (Status ok = batch.commit(); !ok) book_.write_error(ok.error().message);
  }
  kick();
}

}  // namespace rondo::exec
