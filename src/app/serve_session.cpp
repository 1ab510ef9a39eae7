#include "serve_session.h"

#include <fmt/format.h>
#include <malloc.h>
#include <pthread.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <functional>
#include <ostream>
#include <thread>

#include "deployment_parts.h"
#include "fenced_robot.h"
#include "request_intake.h"
#include "request_listener.h"
#include "robot_factory.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor.h"
#include "rondo/fleet/fleet.h"
#include "rondo/service/server.h"
#include "rondo/service/service_role.h"
#include "rondo/service/standby_server.h"
#include "rondo/service/stored_routines.h"
#include "rondo/sim/request_generator.h"
#include "rondo/store/events.h"
#include "rondo/store/lease.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/store.h"
#include "rondo/store/task_table.h"

namespace rondo::app {
namespace {

// The signals the service stops on, blocked in every thread and taken by one sigwait thread, so
// no work happens in a signal handler. SIGUSR1 wakes that thread when the service ends otherwise,
// SIGUSR2 when the lease is lost.
sigset_t stop_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGUSR1);
  sigaddset(&set, SIGUSR2);  // the lease thread: the lease is lost
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

namespace {

enum class ActiveEnd { kStopped, kSteppedDown };

// The lease a standby took, and the lease row as it stood just before (for the takeover's event).
struct Takeover {
  store::Lease lease;
  store::LeaseState before;
};

// A standby: answers 503 (and /healthz, /metrics) on the service's address, and tries to take the
// lease every lease_poll until it has it (returned) or a stop signal comes (nothing). `port`: the
// address's port, the one bound when it was 0, so that the active serves where the standby did.
Result<std::optional<Takeover>> wait_for_lease(const ServeRequest& request, const store::StoreLocation& where,
                                               const sigset_t& signals, service::ServiceRole& role, int& port,
                                               std::ostream& log) {
  const std::string holder = store::Lease::new_holder_name();
  RONDO_ASSIGN_OR_RETURN(store::Lease lease, store::Lease::connect(where, holder));
  RONDO_ASSIGN_OR_RETURN(store::LeaseState before, lease.read());
  RONDO_ASSIGN_OR_RETURN(const std::optional<std::int64_t> at_once, lease.try_take(request.lease_stale));
  if (at_once) return std::optional<Takeover>{Takeover{std::move(lease), before}};
  role.seen(before.epoch, before.holder, std::chrono::duration<double>(before.age).count());

  service::StandbyServer standby(role, {.host = request.host, .port = port, .deployment = request.deployment.name});
  RONDO_ASSIGN_OR_RETURN(port, standby.bind());
  log << fmt::format("rondo serve: {} standby on http://{}:{}/ (store {}; the lease is {}'s, epoch {})\n",
                     request.deployment.name, request.host, port, where.name(), before.holder, before.epoch)
      << std::flush;
  std::atomic<bool> http_done{false};
  std::thread http([&] {
    standby.run();
    http_done = true;
  });
  const ScopeExit join_http([&] {
    while (!http_done) {  // asked again until it has gone, in case it was not listening yet
      standby.stop();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    http.join();
  });
  std::string last_error;
  std::optional<store::Lease> current{std::move(lease)};
  for (;;) {
    // The wait between tries, and the stop signals: whichever comes first.
    const auto poll_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(request.lease_poll).count();
    const timespec wait{.tv_sec = static_cast<time_t>(poll_ns / 1'000'000'000),
                        .tv_nsec = static_cast<long>(poll_ns % 1'000'000'000)};
    const int sig = sigtimedwait(&signals, nullptr, &wait);
    if (sig == SIGTERM || sig == SIGINT) {
      log << fmt::format("rondo serve: {}: stopping (standby)\n", sig == SIGTERM ? "SIGTERM" : "SIGINT") << std::flush;
      return std::optional<Takeover>{};
    }
    Status tried = [&]() -> Status {
      if (!current) {
        RONDO_ASSIGN_OR_RETURN(store::Lease again, store::Lease::connect(where, holder));
        current.emplace(std::move(again));
      }
      RONDO_ASSIGN_OR_RETURN(before, current->read());
      role.seen(before.epoch, before.holder, std::chrono::duration<double>(before.age).count());
      RONDO_ASSIGN_OR_RETURN(const std::optional<std::int64_t> taken, current->try_take(request.lease_stale));
      if (taken) return {};
      return Error{ErrorCode::kConflict, ""};  // held by another: try again
    }();
    if (tried) return std::optional<Takeover>{Takeover{std::move(*current), before}};
    if (tried.error().code == ErrorCode::kConflict && tried.error().message.empty()) continue;
    // The database is gone or refused: said once, and the connection made again at the next try.
    if (tried.error().message != last_error)
      log << fmt::format("rondo serve: standby: {}; trying again\n", tried.error().message) << std::flush;
    last_error = tried.error().message;
    current.reset();
  }
}

// The lease thread of an active: renews the lease every lease_renew from the moment it is taken
// (through the restore, however long it takes); the robot's gate stays open lease_trust past each
// renewal sent. A renewal that fails, or comes too late, closes the gate, marks the role stepped
// down and, once the signal thread is up, wakes it with SIGUSR2.
class LeaseKeeper {
 public:
  LeaseKeeper(store::Lease& lease, LeaseGate& gate, service::ServiceRole& role, const ServeRequest& request)
      : lease_(lease), gate_(gate), role_(role), request_(request), thread_([this] { run(); }) {}
  ~LeaseKeeper() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  LeaseKeeper(const LeaseKeeper&) = delete;
  LeaseKeeper& operator=(const LeaseKeeper&) = delete;

  // The signal thread to wake when the lease is lost (at once if it is lost already); nothing: no
  // longer (it is about to be joined).
  void wake_on_loss(std::optional<pthread_t> waiter) {
    std::lock_guard lock(mutex_);
    waiter_ = waiter;
    if (waiter_ && lost_) pthread_kill(*waiter_, SIGUSR2);
  }
  bool lost() const {
    std::lock_guard lock(mutex_);
    return lost_;
  }
  std::string why() const {
    std::lock_guard lock(mutex_);
    return why_;
  }

 private:
  void run() {
    std::unique_lock lock(mutex_);
    while (!stop_) {
      lock.unlock();
      const auto sent = LeaseGate::Clock::now();
      const Status renewed = lease_.renew();
      const bool in_time = LeaseGate::Clock::now() < sent + request_.lease_trust && gate_.open();
      lock.lock();
      if (!renewed || !in_time) {
        gate_.close();
        lost_ = true;
        why_ = renewed ? "not renewed in time" : renewed.error().message;
        role_.stepped_down();
        if (waiter_) pthread_kill(*waiter_, SIGUSR2);
        return;
      }
      gate_.open_until(sent + request_.lease_trust);
      role_.renewed();
      wake_.wait_for(lock, request_.lease_renew, [&] { return stop_; });
    }
  }

  store::Lease& lease_;
  LeaseGate& gate_;
  service::ServiceRole& role_;
  const ServeRequest& request_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  bool lost_ = false;
  std::string why_;
  std::optional<pthread_t> waiter_;
  std::thread thread_;  // last: started once the rest is set up
};

// The executive, active: restored from the store (as after a restart), serving until a stop
// signal, or, with a lease, until the lease is lost (then it steps down: nothing more is written or
// commanded). Without a lease (SQLite) it is the only executive of its store.
Result<ActiveEnd> serve_active(const ServeRequest& request, const store::StoreLocation& where, Takeover* takeover,
                               service::ServiceRole& role, int& port, const sigset_t& signals,
                               const std::optional<std::string>& token,
                               std::ostream& log) {
  const Deployment& d = request.deployment;
  RONDO_ASSIGN_OR_RETURN(DeploymentParts parts, load_parts(d));
  RONDO_ASSIGN_OR_RETURN(store::Store db, store::Store::open(where, {.sync_commits = true}));
  // From here every write of the executive carries the lease's epoch: once another process has
  // taken the lease, the database refuses them.
  store::Lease* lease = takeover ? &takeover->lease : nullptr;
  LeaseGate gate;
  std::optional<LeaseKeeper> keeper;  // renewing from here on, through the restore
  if (lease) {
    RONDO_RETURN_IF_ERROR(store::fence_writes(db, *lease->epoch(), lease->holder()));
    gate.open_until(LeaseGate::Clock::now() + request.lease_trust);
    role.became_active(*lease->epoch());
    keeper.emplace(*lease, gate, role, request);
  }
  RONDO_ASSIGN_OR_RETURN(std::vector<store::TaskRow> stored, store::list_tasks(db));
  RONDO_RETURN_IF_ERROR(store::set_meta(db, "serve.deployment", d.name));
  RONDO_RETURN_IF_ERROR(
      store::set_meta(db, "serve.deployment_file", std::filesystem::absolute(d.file).lexically_normal().string()));

  exec::SystemClock clock(request.speed);
  exec::ExecutorOptions shared = d.executor;
  shared.dock = parts.dock;
  shared.seed = d.seed;
  // Requests are answered after their commit, not after the reschedule (docs/executor.md).
  shared.background_scheduling = true;
  shared.forget_finished = true;  // finished tasks stay only in the store: months of service do not grow
  // The deployment's robots: simulated ones, or VDA 5050 vehicles (docs/vda5050.md); with a lease,
  // commanded only while the lease is this process's. After a restart each robot is where it was
  // last known to be. Made before the fleet, which they outlive.
  std::vector<DeploymentRobot> deployed;
  std::vector<std::unique_ptr<FencedRobot>> fenced;
  std::vector<exec::Robot*> commanded;
  for (std::size_t i = 0; i < d.robots.size(); ++i) {
    const RobotSpec& spec = d.robots[i];
    map::NodeIndex start_at = parts.robots[i].start;
    if (!stored.empty()) {
      RONDO_ASSIGN_OR_RETURN(const std::optional<store::RobotState> last, store::load_robot_state(db, spec.name));
      if (last)
        if (const auto n = parts.map.find_node(last->node)) start_at = *n;
    }
    RONDO_ASSIGN_OR_RETURN(DeploymentRobot robot, make_robot(d, spec, parts, clock, start_at, d.seed + i));
    commanded.push_back(robot.robot.get());
    if (lease)
      commanded.back() =
          fenced.emplace_back(std::make_unique<FencedRobot>(*robot.robot, gate, *lease->epoch(), log)).get();
    deployed.push_back(std::move(robot));
  }
  fleet::Fleet fleet(clock, parts.map, db, d.zone, shared, {}, make_allocator(d));
  fleet.set_reservations(reservations_for(d, parts));
  fleet.set_bookings(bookings_for(d, parts));
  for (std::size_t i = 0; i < d.robots.size(); ++i) {
    exec::ExecutorOptions options = robot_options(d, d.robots[i], parts.robots[i]);
    options.background_scheduling = shared.background_scheduling;
    options.forget_finished = shared.forget_finished;
    fleet.add_robot(*commanded[i], options);
  }
  exec::Executor& executor = fleet.robot();
  exec::Robot& robot = fenced.empty() ? *deployed.front().robot : static_cast<exec::Robot&>(*fenced.front());
  // The deployment's routines with the changes made through the API (kept in the store).
  std::vector<std::string> skipped;
  RONDO_ASSIGN_OR_RETURN(std::vector<Routine> routines,
                         service::routines_to_run(db, parts.plan.routines, parts.map, d.zone, &skipped));
  for (const std::string& s : skipped)
    log << fmt::format("rondo serve: a routine added through the API is not run: {}\n", s);
  fleet.add_routines(std::move(routines));
  // A data folder that holds a run is restored (kill -9 and start again loses nothing); stored
  // tasks that the deployment, edited meanwhile, can no longer run end with that reason. The
  // deployment's one-off tasks are added to a fresh store only. A takeover is the same restore.
  if (!stored.empty())
    RONDO_RETURN_IF_ERROR(fleet.restore());
  else if (!parts.plan.tasks.empty())
    RONDO_RETURN_IF_ERROR(fleet.add_tasks(parts.plan.tasks, "deployment"));
  // Out of service when it stopped (POST /api/v1/pause), out of service again.
  RONDO_ASSIGN_OR_RETURN(const std::optional<std::string> out_of_service,
                         store::get_meta(db, service::kOutOfServiceKey));
  for (const auto& r : fleet.robots()) {
    RONDO_ASSIGN_OR_RETURN(const std::optional<std::string> own,
                           store::get_meta(db, service::out_of_service_key(r->name())));
    if (out_of_service == "1" || own == "1") r->set_out_of_service(true, false, "as before the restart");
  }
  if (lease) {
    const store::LeaseState& before = takeover->before;
    const std::string reason =
        before.holder.empty()
            ? fmt::format("{} is the active executive at epoch {} (the first)", lease->holder(), *lease->epoch())
            : fmt::format("{} is the active executive at epoch {}, after {} (epoch {}, last renewed {:.1f} s before "
                          "the takeover began)",
                          lease->holder(), *lease->epoch(), before.holder, before.epoch,
                          std::chrono::duration<double>(before.age).count());
    // About the executive process: the instance that took over (its epoch is the event's own).
    RONDO_RETURN_IF_ERROR(store::append_event(db, {.time = clock.now(),
                                                   .subject = store::Subject::kExecutive,
                                                   .about = lease->holder(),
                                                   .event = "takeover",
                                                   .code = "takeover",
                                                   .reason = reason}));
    log << fmt::format("rondo serve: {}\n", reason) << std::flush;
  }
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

  service::Server server({.clock = clock,
                          .fleet = fleet,
                          .executor = executor,
                          .robot = robot,
                          .store = db,
                          .map = parts.map,
                          .zone = d.zone,
                          .deployment = d.name,
                          .places = parts.places ? &*parts.places : nullptr,
                          .role = &role},
                         {.host = request.host, .port = port, .token = token, .threads = 2 * request.max_streams});
  RONDO_ASSIGN_OR_RETURN(port, server.bind());  // a standby again later serves on the same port
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
  std::atomic<bool> stepped_down{false};
  std::thread waiter([&] {
    int sig = 0;
    sigwait(&signals, &sig);
    if (sig == SIGUSR2) {
      stepped_down = true;
      const std::string why = keeper ? keeper->why() : "";
      log << fmt::format("rondo serve: {}: lost the lease at epoch {} ({}): stepping down; nothing more is "
                         "written or commanded\n",
                         lease ? lease->holder() : "", lease ? *lease->epoch() : 0, why)
          << std::flush;
    } else if (sig != SIGUSR1) {
      log << fmt::format("rondo serve: {}: stopping\n", sig == SIGTERM ? "SIGTERM" : "SIGINT") << std::flush;
    }
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
    if (keeper) keeper->wake_on_loss(std::nullopt);
    pthread_kill(waiter.native_handle(), SIGUSR1);
    waiter.join();
  });
  if (keeper) keeper->wake_on_loss(waiter.native_handle());
  clock.run_until(clock.now() + hours(24 * 365 * 100));
  int held_back = 0;
  for (const auto& f : fenced) held_back += f->held_back();
  if (held_back > 0)
    log << fmt::format("rondo serve: {} command(s) to the robot held back after the lease was lost\n", held_back);
  log << (stepped_down ? "rondo serve: stepped down\n" : "rondo serve: stopped\n") << std::flush;
  return stepped_down ? ActiveEnd::kSteppedDown : ActiveEnd::kStopped;
}

}  // namespace

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
  // The deployment's parts are checked before anything else (bad input: exit 2); each active
  // phase loads its own.
  RONDO_RETURN_IF_ERROR(load_parts(d));
  const store::StoreLocation where = request.store     ? *request.store
                                     : d.store         ? *d.store
                                                       : store::StoreLocation::sqlite(request.data / "rondo.sqlite");
  if (where.kind == store::StoreLocation::Kind::kSqlite) {
    std::error_code ec;
    std::filesystem::create_directories(where.file.parent_path().empty() ? "." : where.file.parent_path(), ec);
    if (ec)
      return Error::io(fmt::format("{}: cannot create the store's folder: {}", where.file.parent_path().string(),
                                   ec.message()));
    service::ServiceRole role(false);
    int port = request.port;
    RONDO_RETURN_IF_ERROR(serve_active(request, where, nullptr, role, port, signals, token, log));
    return Status{};
  }
  // PostgreSQL: the store is opened (made, migrated) once before anything, so that a bad URL or
  // an unreachable server is an error at once, as on SQLite; then standby until the lease is ours.
  RONDO_RETURN_IF_ERROR(store::Store::open(where, {.sync_commits = true}));
  service::ServiceRole role(true);
  int port = request.port;
  for (;;) {
    RONDO_ASSIGN_OR_RETURN(std::optional<Takeover> takeover, wait_for_lease(request, where, signals, role, port, log));
    if (!takeover) {
      log << "rondo serve: stopped\n";
      return Status{};
    }
    const Result<ActiveEnd> ended = serve_active(request, where, &*takeover, role, port, signals, token, log);
    if (!ended && role.active()) return ended.error();
    if (!ended)  // lost while restoring: its writes were refused, or its connection ended
      log << fmt::format("rondo serve: lost the lease while starting ({}): stepping down\n", ended.error().message);
    if (ended && *ended == ActiveEnd::kStopped) {
      takeover->lease.release();  // a standby takes over at once
      return Status{};
    }
    log << "rondo serve: standby again\n" << std::flush;
  }
}

}  // namespace rondo::app
