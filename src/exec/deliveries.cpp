#include "deliveries.h"

#include <algorithm>

namespace rondo::exec {

void Deliveries::add(const Task& task) {
  if (!task.delivery) return;
  Job& j = jobs_[task.delivery->job];
  open_.insert(task.delivery->job);
  if (task.delivery->role == DeliveryRole::kPickup) {
    j.pickup = task.id;
    j.pickup_place = task.start_node;
    j.picked = task.delivery;
  } else {
    j.drops.push_back(task.id);
  }
}

const Deliveries::Job* Deliveries::job(const std::string& name) const {
  const auto it = jobs_.find(name);
  return it == jobs_.end() ? nullptr : &it->second;
}

bool Deliveries::is_on_board(const TaskBook& book, const std::string& name) const {
  const Job* j = job(name);
  if (!j || !j->pickup || book.state_of(*j->pickup) != TaskState::kSucceeded) return false;
  return std::none_of(j->drops.begin(), j->drops.end(),
                      [&](const TaskId& d) { return book.state_of(d) == TaskState::kSucceeded; });
}

void Deliveries::forget_settled(const TaskBook& book) {
  std::erase_if(jobs_, [&](const auto& entry) {
    const auto& [name, j] = entry;
    if (open_.contains(name)) return false;
    const bool gone = (!j.pickup || !book.contains(*j.pickup)) &&
                      std::none_of(j.drops.begin(), j.drops.end(), [&](const TaskId& d) { return book.contains(d); });
    return gone && !is_on_board(book, name);
  });
}

std::vector<OnBoard> Deliveries::on_board(const TaskBook& book) const {
  std::vector<OnBoard> out;
  for (const auto& [name, j] : jobs_) {
    if (!is_on_board(book, name)) continue;
    const Delivery& d = *j.picked;
    out.push_back({.job = name, .object = d.object, .appearance = d.appearance, .load = d.load,
                   .picked_up_by = *j.pickup});
  }
  return out;
}

}  // namespace rondo::exec
