#include "serve_session.h"

#include <fmt/format.h>
#include <malloc.h>
#include <pthread.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <ostream>
#include <thread>

#include "deployment_parts.h"
#include "request_intake.h"
#include "request_listener.h"
#include "robot_factory.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor.h"
#include "rondo/fleet/fleet.h"
#include "rondo/service/server.h"
#include "rondo/service/stored_routines.h"
#include "rondo/sim/request_generator.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/store.h"
#include "rondo/store/task_table.h"

namespace rondo::app {
namespace {

// The signals the service stops on, blocked in every thread and taken by one sigwait thread, so
// no work happens in a signal handler. SIGUSR1 wakes that thread when the service ends otherwise.
sigset_t stop_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGUSR1);
  return set;
}

// glibc's malloc keeps what is freed in the arena of the thread that freed it: after a burst of
// requests on many HTTP threads, a service that holds no more than before still shows the burst
// in its resident memory. Once a minute of wall time the free pages go back to the system
// (docs/operations.md, "Memory over time"); it takes well under a millisecond on the clock's thread.
void trim_heap_every(exec::Clock& clock, Duration period) {
  ::malloc_trim(0);
  clock.schedule_after(period, [&clock, period] { trim_heap_every(clock, period); });
}

// Runs `f` when the scope is left, also by an exception.
class ScopeExit {
 public:
  explicit ScopeExit(std::function<void()> f) : f_(std::move(f)) {}
  ~ScopeExit() { f_(); }
  ScopeExit(const ScopeExit&) = delete;
  ScopeExit& operator=(const ScopeExit&) = delete;

 private:
  std::function<void()> f_;
};

}  // namespace

void schedule_people(exec::Clock& clock, fleet::Fleet& fleet, sim::RequestGenerator& people, sim::Rng& rng,
                     const TimeZone& zone, Time from) {
  const auto day = zone.local_date(from);
  const Time to = zone.at(std::chrono::year_month_day{std::chrono::sys_days{day} + std::chrono::days{1}}, Duration{0});
  for (sim::Request& r : people.between(from, to, rng))
    clock.schedule_at(r.at, [&fleet, tasks = r.tasks()]() mutable {
      if (!fleet.book().known(tasks.front().id)) (void)fleet.add_tasks(std::move(tasks), "request");
    });
  clock.schedule_at(
      to, [&clock, &fleet, &people, &rng, &zone, to] { schedule_people(clock, fleet, people, rng, zone, to); });
}

Status serve_deployment(const ServeRequest& request, std::ostream& log) {
  const Deployment& d = request.deployment;
  if (!(request.speed > 0) || request.speed > 1e6)
    return Error::invalid(fmt::format("--speed: {} is not between 0 (excluded) and 1000000", request.speed));
  if (request.max_streams < 1 || request.max_streams > 4096)
    return Error::invalid(fmt::format("--streams: {} is not from 1 to 4096", request.max_streams));
  std::optional<std::string> token;
  if (request.token_file) {
    RONDO_ASSIGN_OR_RETURN(std::string t, service::load_token_file(*request.token_file));
    token = std::move(t);
  } else if (!service::is_loopback_host(request.host)) {
    return Error::invalid(fmt::format("--listen {}: a host other than loopback needs --token-file", request.host));
  }
  // Two malloc arenas, not one per HTTP thread up to eight per core: a burst spread over many
  // threads leaves its freed memory in many arenas, which the service would keep for good.
  ::mallopt(M_ARENA_MAX, 2);
  // A fixed mmap threshold: blocks of 128 KiB and more (the nightly refit's tables, the planners'
  // larger arrays) get pages of their own that go back when freed. glibc would otherwise raise the
  // threshold after the first such block is freed, and later ones would come from the heap, where
  // they leave holes when freed (docs/operations.md, "Memory over time": what the soak measured).
  ::mallopt(M_MMAP_THRESHOLD, 128 * 1024);
  // Blocked before any thread starts (the robot's, the scheduler's worker, HTTP): they inherit
  // it, so only the sigwait thread below takes them.
  const sigset_t signals = stop_signals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  RONDO_ASSIGN_OR_RETURN(DeploymentParts parts, load_parts(d));
  const store::StoreLocation where = request.store     ? *request.store
                                     : d.store         ? *d.store
                                                       : store::StoreLocation::sqlite(request.data / "rondo.sqlite");
  if (where.kind == store::StoreLocation::Kind::kSqlite) {
    std::error_code ec;
    std::filesystem::create_directories(where.file.parent_path().empty() ? "." : where.file.parent_path(), ec);
    if (ec)
      return Error::io(fmt::format("{}: cannot create the store's folder: {}", where.file.parent_path().string(),
                                   ec.message()));
  }
  RONDO_ASSIGN_OR_RETURN(store::Store db, store::Store::open(where, {.sync_commits = true}));
  RONDO_ASSIGN_OR_RETURN(std::vector<store::TaskRow> stored, store::list_tasks(db));
  RONDO_RETURN_IF_ERROR(store::set_meta(db, "serve.deployment", d.name));
  RONDO_RETURN_IF_ERROR(
      store::set_meta(db, "serve.deployment_file", std::filesystem::absolute(d.file).lexically_normal().string()));

  exec::SystemClock clock(request.speed);
  // After a restart the robot is where it was last known to be.
  map::NodeIndex start_at = parts.dock;
  if (!stored.empty()) {
    RONDO_ASSIGN_OR_RETURN(const std::optional<store::RobotState> last,
                           store::load_robot_state(db, d.executor.robot_name));
    if (last)
      if (const auto n = parts.map.find_node(last->node)) start_at = *n;
  }
  // The deployment's robot: the simulated one, or a VDA 5050 vehicle (docs/vda5050.md).
  RONDO_ASSIGN_OR_RETURN(DeploymentRobot deployed, make_robot(d, parts, clock, start_at, d.seed));
  exec::Robot& robot = *deployed.robot;
  exec::ExecutorOptions options = d.executor;
  options.dock = parts.dock;
  options.seed = d.seed;
  // Requests are answered after their commit, not after the reschedule (docs/executor.md).
  options.background_scheduling = true;
  options.forget_finished = true;  // finished tasks stay only in the store: months of service do not grow
  fleet::Fleet fleet(clock, parts.map, db, d.zone, options);
  exec::Executor& executor = fleet.add_robot(robot, options);
  // The deployment's routines with the changes made through the API (kept in the store).
  std::vector<std::string> skipped;
  RONDO_ASSIGN_OR_RETURN(std::vector<Routine> routines,
                         service::routines_to_run(db, parts.plan.routines, parts.map, d.zone, &skipped));
  for (const std::string& s : skipped)
    log << fmt::format("rondo serve: a routine added through the API is not run: {}\n", s);
  fleet.add_routines(std::move(routines));
  // A data folder that holds a run is restored (kill -9 and start again loses nothing); stored
  // tasks that the deployment, edited meanwhile, can no longer run end with that reason. The
  // deployment's one-off tasks are added to a fresh store only.
  if (!stored.empty())
    RONDO_RETURN_IF_ERROR(fleet.restore());
  else if (!parts.plan.tasks.empty())
    RONDO_RETURN_IF_ERROR(fleet.add_tasks(parts.plan.tasks, "deployment"));
  // Out of service when it stopped (POST /api/v1/pause), out of service again.
  RONDO_ASSIGN_OR_RETURN(const std::optional<std::string> out_of_service,
                         store::get_meta(db, service::kOutOfServiceKey));
  if (out_of_service == "1") executor.set_out_of_service(true, false, "as before the restart");
  fleet.start();
  // Requests queued by `rondo task add --data` (while it was down, and from now on): read again
  // every half second of wall time; on PostgreSQL as soon as each is committed (LISTEN/NOTIFY),
  // with a poll once a minute of wall time in case a notification was missed.
  RequestIntake intake(clock, fleet, db);
  std::unique_ptr<RequestListener> listener;
  if (db.is_postgres()) {
    RONDO_ASSIGN_OR_RETURN(listener, RequestListener::start(clock, intake, db.location(), log));
    intake.poll_every(120 * intake_period(request.speed));
  } else {
    intake.poll_every(intake_period(request.speed));
  }
  trim_heap_every(clock, std::max(Duration{1}, Duration{static_cast<Duration::rep>(60'000.0 * request.speed)}));
  sim::Rng people_rng(d.seed * 0x9E3779B97F4A7C15ULL + 17);
  if (parts.people) schedule_people(clock, fleet, *parts.people, people_rng, d.zone, clock.now());

  service::Server server(
      {.clock = clock,
       .fleet = fleet,
       .executor = executor,
       .robot = robot,
       .store = db,
       .map = parts.map,
       .zone = d.zone,
       .deployment = d.name,
       .places = parts.places ? &*parts.places : nullptr},
      {.host = request.host, .port = request.port, .token = token, .threads = 2 * request.max_streams});
  RONDO_ASSIGN_OR_RETURN(const int port, server.bind());
  log << fmt::format("rondo serve: {} on http://{}:{}/ (speed {}, store {}, {})\n", d.name, request.host, port,
                     request.speed, db.name(), token ? "writes need the token" : "writes open on loopback")
      << std::flush;

  // The HTTP thread and the signal thread are joined whichever way this function is left: a
  // std::thread destroyed while it can still be joined ends the process (std::terminate), which
  // is how an exception on the clock's thread once became "terminated without an exception".
  std::atomic<bool> http_done{false};
  std::thread http([&server, &http_done] {
    server.run();
    http_done = true;
  });
  // No new requests; the ones in progress are answered (while the clock still runs). Asked again
  // until the server has gone, in case the signal came before it was listening.
  const auto end_http = [&] {
    if (!http.joinable()) return;
    while (!http_done) {
      server.stop();
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    http.join();
  };
  const ScopeExit join_http([&] { end_http(); });
  std::thread waiter([&] {
    int sig = 0;
    sigwait(&signals, &sig);
    if (sig != SIGUSR1)
      log << fmt::format("rondo serve: {}: stopping\n", sig == SIGTERM ? "SIGTERM" : "SIGINT") << std::flush;
    end_http();
    // The last callback the executive runs: what was posted after it stays unrun (SystemClock::stop).
    clock.post([&] {
      robot.deactivate();  // halts the robot where it is; a vehicle's MQTT client disconnects
      clock.stop();
    });
  });
  // SIGUSR1 wakes the signal thread when the clock's loop ends otherwise (an exception); a no-op
  // when a signal already woke it.
  const ScopeExit join_waiter([&] {
    pthread_kill(waiter.native_handle(), SIGUSR1);
    waiter.join();
  });
  clock.run_until(clock.now() + hours(24 * 365 * 100));
  log << "rondo serve: stopped\n";
  return Status{};
}

}  // namespace rondo::app
