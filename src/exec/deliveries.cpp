#include "deliveries.h"

#include <algorithm>

namespace rondo::exec {

void Deliveries::add(const Task& task) {
  if (!task.delivery) return;
  Job& j = jobs_[task.delivery->job];
  open_.insert(task.delivery->job);
  if (task.delivery->role == DeliveryRole::kPickup)
    j.pickup = task.id;
  else
    j.drops.push_back(task.id);
}

const Deliveries::Job* Deliveries::job(const std::string& name) const {
  const auto it = jobs_.find(name);
  return it == jobs_.end() ? nullptr : &it->second;
}

bool Deliveries::is_on_board(const TaskBook& book, const std::string& name) const {
  const Job* j = job(name);
  if (!j || !j->pickup || book.at(*j->pickup).state != TaskState::kSucceeded) return false;
  return std::none_of(j->drops.begin(), j->drops.end(),
                      [&](const TaskId& d) { return book.at(d).state == TaskState::kSucceeded; });
}

std::vector<OnBoard> Deliveries::on_board(const TaskBook& book) const {
  std::vector<OnBoard> out;
  for (const auto& [name, j] : jobs_) {
    if (!is_on_board(book, name)) continue;
    const Delivery& d = *book.at(*j.pickup).task.delivery;
    out.push_back({.job = name, .object = d.object, .appearance = d.appearance, .load = d.load,
                   .picked_up_by = *j.pickup});
  }
  return out;
}

}  // namespace rondo::exec
