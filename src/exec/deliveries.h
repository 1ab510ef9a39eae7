// Delivery jobs (MISSION.md §5) as the executor keeps them: each job's pickup and drop tasks, and
// what is on board, which follows from their states (a job's object is on board from its pickup's
// success until a drop of the job succeeds), so it is as durable as the task book and comes back
// with it after a restart.
//
//   Deliveries jobs;
//   jobs.add(task);                                  // every task the book accepts
//   std::vector<OnBoard> now = jobs.on_board(book);
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "rondo/core/task.h"
#include "rondo/exec/executor_types.h"
#include "rondo/exec/task_book.h"

namespace rondo::exec {

class Deliveries {
 public:
  struct Job {
    std::optional<TaskId> pickup;
    std::vector<TaskId> drops;  // the job's drop, and any return of its object made later
    // Of the pickup, kept here since a finished pickup leaves the task book's memory.
    std::string pickup_place{};
    std::optional<Delivery> picked{};
  };

  // Records a delivery task (others are ignored); its job is open until close().
  void add(const Task& task);
  // The jobs not settled yet: an object to pick up, on board, or a drop pending.
  const std::set<std::string>& open() const { return open_; }
  void close(const std::string& job) { open_.erase(job); }
  // Forgets a job that went to another robot (nothing of it on board here).
  void hand_over(const std::string& job) {
    jobs_.erase(job);
    open_.erase(job);
  }
  const Job* job(const std::string& name) const;
  // The objects on board now, in job order.
  std::vector<OnBoard> on_board(const TaskBook& book) const;
  bool is_on_board(const TaskBook& book, const std::string& job) const;
  // Forgets the settled jobs (closed, nothing on board) whose tasks have all left the book's
  // memory (TaskBook::forget_finished).
  void forget_settled(const TaskBook& book);

 private:
  std::map<std::string, Job> jobs_;
  std::set<std::string> open_;
};

}  // namespace rondo::exec
