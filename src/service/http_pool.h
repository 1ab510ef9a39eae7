// The HTTP threads of `rondo serve` (internal to rondo::service): cpp-httplib's TaskQueue, with
// threads started when a connection finds none idle and ended after a while without work.
//
// httplib's own ThreadPool starts all its threads at once and keeps them: `rondo serve` has 128
// (twice --streams), and a request handed to the next of them in turn leaves malloc's per-thread
// cache (tcache) and the touched stack of every one of them in the service's resident memory, so
// the memory grows with how many threads have served a request yet, not with what the service
// holds (docs/operations.md, "Memory over time", session 16). This pool holds as many threads as
// connections were open at once lately: one or two for requests one after another. A thread idle
// for `idle_exit` ends (its tcache goes back to the arena, its stack pages to the system), so a
// burst of event streams does not keep its threads for the months the service runs. At most
// `max_threads` at once, as before: event streams hold one each (server.h, ServerOptions::threads).
#pragma once

#include <httplib.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <list>
#include <mutex>
#include <thread>
#include <vector>

namespace rondo::service {

class HttpPool final : public httplib::TaskQueue {
 public:
  // Starts a thread running `body` (std::thread's constructor; tests give one that fails, as it
  // does with std::system_error at the process's thread limit).
  using StartThread = std::function<std::thread(std::function<void()> body)>;
  // `gauge` (optional) follows threads(), for /metrics.
  HttpPool(std::size_t max_threads, std::chrono::milliseconds idle_exit, std::atomic<std::size_t>* gauge = nullptr,
           StartThread start_thread = nullptr);
  ~HttpPool() override;
  HttpPool(const HttpPool&) = delete;
  HttpPool& operator=(const HttpPool&) = delete;

  // Queues `fn`; starts a thread for it when fewer threads wait than jobs do and fewer than
  // max_threads run. Ignored after shutdown() (httplib never does that). Never throws: when no
  // thread can be started, `fn` waits for a running one, or with none runs here (an exception
  // would end httplib's accepting thread, and the process with it).
  void enqueue(std::function<void()> fn) override;
  // Runs the queued jobs, then ends and joins every thread.
  void shutdown() override;

  // Threads running now, and started in all (tests; the metrics).
  std::size_t threads() const;
  std::size_t started() const;
  // Block until at most `n` threads run (the idle ones have ended), or at least `n` wait for work
  // (tests: what the next enqueue() finds, without sleeping).
  void wait_threads_at_most(std::size_t n) const;
  void wait_idle_at_least(std::size_t n) const;

 private:
  using Worker = std::list<std::thread>::iterator;
  void work(Worker self);
  void join_finished(std::unique_lock<std::mutex>& lock);

  const std::size_t max_threads_;
  const std::chrono::milliseconds idle_exit_;
  std::atomic<std::size_t>* const gauge_;
  const StartThread start_thread_;
  mutable std::mutex mutex_;
  std::condition_variable work_;           // a job was queued, or shutdown
  mutable std::condition_variable ended_;  // a thread ended or went idle
  std::deque<std::function<void()>> jobs_;
  std::list<std::thread> workers_;     // running
  std::vector<std::thread> finished_;  // ended, to be joined
  std::size_t idle_ = 0, started_ = 0;
  bool shutdown_ = false;
};

}  // namespace rondo::service
