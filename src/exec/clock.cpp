#include "rondo/exec/clock.h"

#include <chrono>
#include <stdexcept>
#include <thread>

namespace rondo::exec {

TimerId EventQueue::push(Time at, std::function<void()> callback) {
  const TimerId id = next_id_++;
  events_.emplace(Key{at, id}, std::move(callback));
  due_.emplace(id, at);
  return id;
}

void EventQueue::cancel(TimerId id) {
  const auto it = due_.find(id);
  if (it == due_.end()) return;
  events_.erase(Key{it->second, id});
  due_.erase(it);
}

Time EventQueue::next_time() const {
  if (events_.empty()) throw std::logic_error("EventQueue::next_time on an empty queue");
  return events_.begin()->first.at;
}

std::function<void()> EventQueue::pop() {
  if (events_.empty()) throw std::logic_error("EventQueue::pop on an empty queue");
  auto node = events_.extract(events_.begin());
  due_.erase(node.key().id);
  return std::move(node.mapped());
}

TimerId SimClock::schedule_at(Time at, std::function<void()> callback) {
  return queue_.push(at < now_ ? now_ : at, std::move(callback));
}

bool SimClock::step() {
  if (queue_.empty()) return false;
  now_ = queue_.next_time();
  queue_.pop()();
  return true;
}

void SimClock::run_until(Time end) {
  while (!queue_.empty() && queue_.next_time() <= end) step();
  if (end > now_) now_ = end;
}

Time SystemClock::now() const {
  return std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now());
}

TimerId SystemClock::schedule_at(Time at, std::function<void()> callback) {
  return queue_.push(at, std::move(callback));
}

void SystemClock::run_until(Time end) {
  for (;;) {
    const Time next = queue_.empty() ? end : std::min(end, queue_.next_time());
    const Time t = now();
    if (next > t) std::this_thread::sleep_for(next - t);
    if (queue_.empty() || queue_.next_time() > end) {
      if (now() >= end) return;
      continue;
    }
    queue_.pop()();
  }
}


}  // namespace rondo::exec
