// HttpPool: the HTTP threads of `rondo serve`, started when needed and ended when idle.
#include "http_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <future>
#include <mutex>

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

}  // namespace
}  // namespace rondo::service
