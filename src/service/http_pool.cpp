#include "http_pool.h"

#include <algorithm>
#include <system_error>
#include <utility>

namespace rondo::service {

HttpPool::HttpPool(std::size_t max_threads, std::chrono::milliseconds idle_exit, std::atomic<std::size_t>* gauge,
                   StartThread start_thread)
    : max_threads_(std::max<std::size_t>(1, max_threads)),
      idle_exit_(idle_exit),
      gauge_(gauge),
      start_thread_(start_thread ? std::move(start_thread)
                                 : [](std::function<void()> body) { return std::thread(std::move(body)); }) {}

HttpPool::~HttpPool() {
  shutdown();
}

void HttpPool::enqueue(std::function<void()> fn) {
  std::unique_lock lock(mutex_);
  if (shutdown_) return;
  jobs_.push_back(std::move(fn));
  if (idle_ < jobs_.size() && workers_.size() < max_threads_) {
    // Started under the lock: the thread's first look at the queue waits for `*self` to be set.
    const Worker self = workers_.emplace(workers_.end());
    try {
      *self = start_thread_([this, self] { work(self); });
      ++started_;
    } catch (const std::system_error&) {
      // No thread to be had (the process's limit). The job waits for a running thread; with
      // none, it runs here, on httplib's accepting thread.
      workers_.erase(self);
      if (workers_.empty()) {
        std::function<void()> job = std::move(jobs_.back());
        jobs_.pop_back();
        lock.unlock();
        job();
        lock.lock();
      }
    }
    if (gauge_) *gauge_ = workers_.size();
  }
  lock.unlock();
  work_.notify_one();
  lock.lock();
  join_finished(lock);
}

void HttpPool::shutdown() {
  std::unique_lock lock(mutex_);
  shutdown_ = true;
  work_.notify_all();
  ended_.wait(lock, [this] { return workers_.empty(); });
  join_finished(lock);
}

std::size_t HttpPool::threads() const {
  std::lock_guard lock(mutex_);
  return workers_.size();
}

std::size_t HttpPool::started() const {
  std::lock_guard lock(mutex_);
  return started_;
}

void HttpPool::wait_threads_at_most(std::size_t n) const {
  std::unique_lock lock(mutex_);
  ended_.wait(lock, [&] { return workers_.size() <= n; });
}

void HttpPool::wait_idle_at_least(std::size_t n) const {
  std::unique_lock lock(mutex_);
  ended_.wait(lock, [&] { return idle_ >= n; });
}

void HttpPool::work(Worker self) {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (!jobs_.empty()) {
      std::function<void()> fn = std::move(jobs_.front());
      jobs_.pop_front();
      lock.unlock();
      fn();
      fn = nullptr;  // the job's captures go on this thread, outside the lock
      lock.lock();
      continue;
    }
    if (shutdown_) break;
    ++idle_;
    ended_.notify_all();
    const bool woken = work_.wait_for(lock, idle_exit_, [this] { return shutdown_ || !jobs_.empty(); });
    --idle_;
    if (!woken) break;  // idle for idle_exit: end (a later connection starts a thread again)
  }
  // The handle goes to finished_: the next enqueue() or shutdown() joins it (a thread cannot join
  // itself). Nothing of the pool is touched after the unlock below.
  finished_.push_back(std::move(*self));
  workers_.erase(self);
  if (gauge_) *gauge_ = workers_.size();
  ended_.notify_all();
}

void HttpPool::join_finished(std::unique_lock<std::mutex>& lock) {
  std::vector<std::thread> done = std::exchange(finished_, {});
  lock.unlock();
  for (std::thread& t : done) t.join();
  lock.lock();
}

}  // namespace rondo::service
