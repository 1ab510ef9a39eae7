// HttpPool: the HTTP threads of `rondo serve`, started when needed and ended when idle.
#include "http_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <future>
#include <mutex>
#include <system_error>
#include <thread>

namespace rondo::service {
namespace {

using std::chrono::hours;
using std::chrono::milliseconds;

TEST(HttpPool, StartsNoThreadUntilAJobComes) {
  std::atomic<std::size_t> gauge{99};
  HttpPool pool(8, hours(1), &gauge);
  EXPECT_EQ(pool.threads(), 0u);
  EXPECT_EQ(pool.started(), 0u);
  EXPECT_EQ(gauge.load(), 99u);  // untouched until a thread starts
}

TEST(HttpPool, JobsOneAfterAnotherShareOneThread) {
  std::atomic<std::size_t> gauge{0};
  HttpPool pool(128, hours(1), &gauge);
  for (int i = 0; i < 20; ++i) {
    std::promise<void> done;
    pool.enqueue([&done] { done.set_value(); });
    done.get_future().wait();
    pool.wait_idle_at_least(1);  // the thread is back waiting, as it is between two requests
  }
  EXPECT_EQ(pool.started(), 1u);
  EXPECT_EQ(pool.threads(), 1u);
  EXPECT_EQ(gauge.load(), 1u);
}

// Jobs that wait for each other: as many threads as jobs at once, up to the bound; a job beyond
// it waits for a thread to come free.
TEST(HttpPool, ConcurrentJobsGetThreadsUpToTheBound) {
  HttpPool pool(3, hours(1));
  std::mutex m;
  std::condition_variable cv;
  int running = 0, finished = 0;
  bool release = false;
  auto job = [&] {
    std::unique_lock lock(m);
    ++running;
    cv.notify_all();
    cv.wait(lock, [&] { return release; });
    ++finished;
    cv.notify_all();
  };
  for (int i = 0; i < 4; ++i) pool.enqueue(job);
  {
    std::unique_lock lock(m);
    cv.wait(lock, [&] { return running == 3; });
  }
  EXPECT_EQ(pool.threads(), 3u);
  EXPECT_EQ(pool.started(), 3u);
  {
    std::unique_lock lock(m);
    EXPECT_EQ(running, 3);  // the fourth waits for a thread
    release = true;
    cv.notify_all();
    cv.wait(lock, [&] { return finished == 4; });
  }
  EXPECT_EQ(pool.started(), 3u);
}

TEST(HttpPool, AnIdleThreadEndsAndALaterJobStartsAnother) {
  std::atomic<std::size_t> gauge{0};
  HttpPool pool(8, milliseconds(0), &gauge);
  std::promise<void> first;
  pool.enqueue([&first] { first.set_value(); });
  first.get_future().wait();
  pool.wait_threads_at_most(0);
  EXPECT_EQ(pool.threads(), 0u);
  EXPECT_EQ(gauge.load(), 0u);
  std::promise<void> second;
  pool.enqueue([&second] { second.set_value(); });
  second.get_future().wait();
  EXPECT_EQ(pool.started(), 2u);
}

TEST(HttpPool, ShutdownRunsTheQueuedJobsAndEndsEveryThread) {
  HttpPool pool(1, hours(1));
  std::promise<void> go;
  std::shared_future<void> gate = go.get_future().share();
  std::atomic<int> ran{0};
  pool.enqueue([gate, &ran] {
    gate.wait();
    ++ran;
  });
  for (int i = 0; i < 3; ++i) pool.enqueue([&ran] { ++ran; });
  go.set_value();
  pool.shutdown();
  EXPECT_EQ(ran.load(), 4);
  EXPECT_EQ(pool.threads(), 0u);
  pool.enqueue([&ran] { ++ran; });  // after shutdown: ignored
  EXPECT_EQ(ran.load(), 4);
}

// At the process's thread limit std::thread throws. Before, the exception left enqueue() and
// ended httplib's accepting thread (std::terminate), and the emptied worker slot it left held
// shutdown() for ever. Now the job waits for a running thread, or with none runs at once.
TEST(HttpPool, NoThreadToBeHadRunsTheJobOnARunningThreadOrAtOnce) {
  std::atomic<bool> refuse{true};
  const HttpPool::StartThread start = [&refuse](std::function<void()> body) {
    if (refuse) throw std::system_error(std::make_error_code(std::errc::resource_unavailable_try_again));
    return std::thread(std::move(body));
  };
  HttpPool pool(4, hours(1), nullptr, start);
  const std::thread::id here = std::this_thread::get_id();
  std::thread::id ran_on;
  pool.enqueue([&ran_on] { ran_on = std::this_thread::get_id(); });
  EXPECT_EQ(ran_on, here);  // no thread running: at once, on the caller's
  EXPECT_EQ(pool.threads(), 0u);

  refuse = false;
  std::promise<void> go;
  std::shared_future<void> gate = go.get_future().share();
  std::promise<std::thread::id> first;
  pool.enqueue([gate, &first] {
    gate.wait();
    first.set_value(std::this_thread::get_id());
  });
  refuse = true;
  std::promise<std::thread::id> second;
  pool.enqueue([&second] { second.set_value(std::this_thread::get_id()); });  // waits for the one thread
  EXPECT_EQ(pool.threads(), 1u);
  go.set_value();
  const std::thread::id worker = first.get_future().get();
  EXPECT_NE(worker, here);
  EXPECT_EQ(second.get_future().get(), worker);
  pool.shutdown();
  EXPECT_EQ(pool.threads(), 0u);
}

}  // namespace
}  // namespace rondo::service
