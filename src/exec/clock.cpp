#include "rondo/exec/clock.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

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

bool PostBox::put(std::function<void()> callback) {
  std::lock_guard lock(mutex_);
  const bool was_empty = callbacks_.empty();
  callbacks_.push_back(std::move(callback));
  return was_empty;
}

std::vector<std::function<void()>> PostBox::take() {
  std::lock_guard lock(mutex_);
  return std::exchange(callbacks_, {});
}

void PostBox::put_back(std::vector<std::function<void()>> callbacks) {
  if (callbacks.empty()) return;
  std::lock_guard lock(mutex_);
  callbacks.insert(callbacks.end(), std::make_move_iterator(callbacks_.begin()),
                   std::make_move_iterator(callbacks_.end()));
  callbacks_ = std::move(callbacks);
}

bool PostBox::empty() const {
  std::lock_guard lock(mutex_);
  return callbacks_.empty();
}

TimerId SimClock::schedule_at(Time at, std::function<void()> callback) {
  return queue_.push(at < now_ ? now_ : at, std::move(callback));
}

bool SimClock::run_posted() {
  std::vector<std::function<void()>> posted = posted_.take();
  for (auto& callback : posted) callback();
  return !posted.empty();
}

bool SimClock::step() {
  if (run_posted()) return true;
  if (queue_.empty()) return false;
  now_ = queue_.next_time();
  queue_.pop()();
  return true;
}

void SimClock::run_until(Time end) {
  for (;;) {
    if (run_posted()) continue;
    if (queue_.empty() || queue_.next_time() > end) break;
    step();
  }
  if (end > now_) now_ = end;
}

SystemClock::Sources SystemClock::system_sources() {
  return {.wall = [] { return std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now()); },
          .steady = [] { return Steady::now(); }};
}

SystemClock::SystemClock(double speed, Sources sources)
    : speed_(speed), sources_(std::move(sources)), wall_start_(sources_.wall()), steady_start_(sources_.steady()) {
  if (!(speed > 0) || !std::isfinite(speed)) throw std::invalid_argument("SystemClock: speed must be above zero");
}

Time SystemClock::now() const {
  if (speed_ == 1.0) return sources_.wall();
  const auto elapsed = std::chrono::duration<double, std::milli>(steady_now() - steady_start_) * speed_;
  return wall_start_ + std::chrono::duration_cast<Duration>(elapsed);
}

TimerId SystemClock::schedule_at(Time at, std::function<void()> callback) {
  const Duration ahead = std::max(Duration{0}, at - now());
  const auto real = std::chrono::duration_cast<Steady::duration>(std::chrono::duration<double, std::milli>(ahead) / speed_);
  return queue_.push(as_key(steady_now() + real), std::move(callback));
}

void SystemClock::post(std::function<void()> callback) {
  {
    std::lock_guard lock(wake_mutex_);
    (void)posted_.put(std::move(callback));
  }
  wake_.notify_one();
}

void SystemClock::stop() {
  {
    std::lock_guard lock(wake_mutex_);
    stop_ = true;
  }
  wake_.notify_all();
}

bool SystemClock::stopped() const {
  std::lock_guard lock(wake_mutex_);
  return stop_;
}

std::size_t SystemClock::run_due() {
  std::size_t ran = 0;
  for (auto& callback : posted_.take()) {
    callback();
    ++ran;
  }
  while (!queue_.empty() && queue_.next_time() <= as_key(steady_now())) {
    queue_.pop()();
    ++ran;
  }
  return ran;
}

void SystemClock::run_until(Time end) {
  while (!stopped()) {
    // The callbacks posted so far, until one of them stops the clock (`rondo serve` halts the
    // robot and stops in one: what was posted after it, a message from the vehicle, the robot's
    // report of it, must not reach an executor whose robot is gone).
    std::vector<std::function<void()>> posted = posted_.take();
    for (auto it = posted.begin(); it != posted.end(); ++it) {
      (*it)();
      if (stopped()) {
        posted_.put_back({std::make_move_iterator(it + 1), std::make_move_iterator(posted.end())});
        return;
      }
    }
    if (!queue_.empty() && queue_.next_time() <= as_key(steady_now())) {
      queue_.pop()();
      continue;
    }
    const Time t = now();
    if (t >= end) return;
    // Wake at the next timer or when now() reaches `end`, whichever is first, or when posted to.
    const auto to_end = std::chrono::duration_cast<Steady::duration>(
        std::chrono::duration<double, std::milli>(end - t) / speed_);
    Steady::time_point until = steady_now() + to_end;
    if (!queue_.empty()) {
      const Steady::time_point next{std::chrono::duration_cast<Steady::duration>(queue_.next_time().time_since_epoch())};
      until = std::min(until, next);
    }
    std::unique_lock lock(wake_mutex_);
    wake_.wait_until(lock, until, [&] { return stop_ || !posted_.empty(); });
  }
}

}  // namespace rondo::exec
