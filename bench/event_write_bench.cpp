// The sustained event-write rate of a store (issue 40): the event log of a `rondo run` of an
// example, appended again to a fresh store of either backend as the executor writes it, one
// synced commit per event, and in batches of 50 (store::Batch, as a background answer or a group
// of submissions is written), for a given wall time. A measurement, never a test.
//
//   build/rondo run examples/g4s/deployment.yaml --days 7 --out /tmp/g4s
//   build/bench/bench_event_write /tmp/g4s/rondo.sqlite /tmp/target.sqlite [SECONDS]
//   build/bench/bench_event_write /tmp/g4s/rondo.sqlite 'postgresql:///bench?host=/tmp/pg&port=5432' [SECONDS]
//
// The run's tasks go in first, under a fresh id for each round (not timed), so that every task
// event finds its task; the events keep their kind, subject, code and reason, in their order.
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

#include "rondo/store/batch.h"
#include "rondo/store/events.h"
#include "rondo/store/read_back.h"
#include "rondo/store/store.h"
#include "rondo/store/task_table.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Rate {
  long events = 0;
  double seconds = 0;
};

// Appends the source's events round after round (each round's tasks added first, untimed) until
// `seconds` of timed writing have passed; `batch` events per commit.
rondo::Result<Rate> replay(rondo::store::Store& target, const rondo::store::StoredRun& run, double seconds, int batch,
                           const std::string& prefix) {
  Rate rate;
  for (int round = 0; rate.seconds < seconds; ++round) {
    const std::string tag = fmt::format("{}{}-", prefix, round);
    std::vector<rondo::store::TaskRow> rows;
    for (const rondo::store::StoredTask& t : run.tasks) {
      rondo::store::TaskRow r = t.row;
      r.id = tag + r.id;
      rows.push_back(std::move(r));
    }
    RONDO_RETURN_IF_ERROR(rondo::store::add_tasks(target, rows));
    const auto start = Clock::now();
    std::size_t i = 0;
    while (i < run.events.size()) {
      rondo::store::Batch b(target);
      for (int k = 0; k < batch && i < run.events.size(); ++k, ++i) {
        rondo::store::Event e = run.events[i];
        if (e.subject == rondo::store::Subject::kTask) {
          if (e.code == "added") continue;  // add_tasks wrote it
          e.task_id = tag + e.task_id;
        }
        RONDO_RETURN_IF_ERROR(rondo::store::append_event(target, e));
        ++rate.events;
      }
      RONDO_RETURN_IF_ERROR(b.commit());
    }
    rate.seconds += std::chrono::duration<double>(Clock::now() - start).count();
  }
  return rate;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    fmt::print(stderr, "usage: bench_event_write SOURCE.sqlite TARGET(file|postgresql://...) [SECONDS]\n");
    return 2;
  }
  const double seconds = argc > 3 ? std::atof(argv[3]) : 10.0;
  auto source = rondo::store::Store::open(rondo::store::StoreLocation::sqlite(argv[1]), {.sync_commits = false});
  if (!source) {
    fmt::print(stderr, "{}\n", source.error().message);
    return 1;
  }
  auto run = rondo::store::read_back(*source, "robot");
  auto where = rondo::store::StoreLocation::parse(argv[2]);
  if (!run || !where) {
    fmt::print(stderr, "{}\n", !run ? run.error().message : where.error().message);
    return 1;
  }
  auto target = rondo::store::Store::open(*where, {.sync_commits = true});
  if (!target) {
    fmt::print(stderr, "{}\n", target.error().message);
    return 1;
  }
  fmt::print("bench_event_write: {} tasks, {} events a round from {}; into {}, synced commits\n", run->tasks.size(),
             run->events.size(), argv[1], target->name());
  for (const int batch : {1, 50}) {
    auto rate = replay(*target, *run, seconds, batch, fmt::format("b{}-", batch));
    if (!rate) {
      fmt::print(stderr, "{}\n", rate.error().message);
      return 1;
    }
    fmt::print("{} event(s) a commit: {} events in {:.1f} s: {:.0f} events/s\n", batch, rate->events, rate->seconds,
               static_cast<double>(rate->events) / rate->seconds);
  }
  return 0;
}
