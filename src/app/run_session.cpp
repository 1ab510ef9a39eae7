#include "run_session.h"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <fstream>
#include <functional>
#include <ostream>
#include <span>

#include "deployment_parts.h"
#include "request_intake.h"
#include "robot_factory.h"
#include "rondo/core/atomic_file.h"
#include "rondo/core/task_codec.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor.h"
#include "rondo/fleet/fleet.h"
#include "rondo/map/map_geometry.h"
#include "rondo/service/stored_routines.h"
#include "rondo/sim/request_generator.h"
#include "rondo/sim/rng.h"
#include "rondo/sim/sim_world.h"
#include "rondo/store/events.h"
#include "rondo/store/read_back.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/store.h"
#include "rondo/store/traversal_log.h"
#include "run_folder.h"
#include "run_report.h"
#include "traffic_report.h"

namespace rondo::app {
namespace {

// This process's CPU time, in seconds.
double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

Status write_file(const std::filesystem::path& file, const std::string& text) {
  return write_file_atomically(file, text);
}

std::string date_text(std::chrono::year_month_day d) {
  return fmt::format("{:04d}-{:02d}-{:02d}", static_cast<int>(d.year()), static_cast<unsigned>(d.month()),
                     static_cast<unsigned>(d.day()));
}

void draw_progress(std::ostream& out, int done, int total) {
  constexpr int kWidth = 30;
  const int filled = total > 0 ? done * kWidth / total : kWidth;
  out << fmt::format("\r  day {:>3}/{} [{}{}]", done, total, std::string(static_cast<std::size_t>(filled), '#'),
                     std::string(static_cast<std::size_t>(kWidth - filled), ' '))
      << std::flush;
}

// Everything one run needs, alive for the whole run.
struct Session {
  DeploymentParts parts;
  RunFolder folder;
};

// The whole deployment is loaded and checked before the run folder is touched: a deployment that
// fails validation leaves --out as it was.
Result<Session> open_session(const RunRequest& request, Time start) {
  RONDO_ASSIGN_OR_RETURN(DeploymentParts parts, load_parts(request.deployment));
  RONDO_ASSIGN_OR_RETURN(RunFolder folder, open_run_folder(request, start));
  return Session{std::move(parts), std::move(folder)};
}

// The figures that a restart would lose if they came from the executor (it only knows what
// happened since it started): the edge attempts and the distance, from the traversal log.
// A traversal without a robot's name (an older store) is the first robot's.
void navigation_from_log(const map::TopoMap& map, std::span<const Traversal> log, Time from, Time to,
                         const std::string& first_robot, RunFigures& figures) {
  for (const Traversal& t : log) {
    if (t.start < from || t.start >= to) continue;
    ++figures.navigation_attempts;
    if (!t.success) continue;
    ++figures.navigation_successes;
    if (const auto e = map.find_edge(t.edge_id)) {
      const double metres = map::edge_length(map, *e);
      figures.distance_m += metres;
      figures.distance_by_robot[t.robot.empty() ? first_robot : t.robot] += metres;
    }
  }
}

// Battery readings at empty, over every robot.
std::size_t empty_readings(const fleet::Fleet& fleet) {
  std::size_t n = 0;
  for (const auto& robot : fleet.robots()) n += robot->battery_figures().empty_readings;
  return n;
}

// A finished run is not run again: its report is read back.
Result<RunResult> finished_run(const RunRequest& request) {
  RunResult result;
  result.already_finished = true;
  std::ifstream in(request.out / "report.json");
  if (in) result.report = Json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (result.report.is_discarded()) result.report = Json::object();
  return result;
}

// The seed of the deployment's i-th simulated robot: the first has the deployment's own (a fleet of
// one draws as it always did), the others a stream of their own.
std::uint64_t robot_seed(std::uint64_t seed, std::size_t i) {
  if (i == 0) return seed;
  std::uint64_t mix = seed + 0x9E3779B97F4A7C15ULL * static_cast<std::uint64_t>(i);
  return sim::splitmix64(mix);
}

// Where and when a run goes on. A run that was stopped (killed, a power cut) goes on from the
// latest thing its store holds, with each robot at its last known node, up to the same end.
struct Resume {
  bool resumed = false;  // the store held something of this run
  Time at{};
  std::vector<map::NodeIndex> robot_at;  // per robot of the deployment
  std::vector<std::uint64_t> robot_seed;
};

Result<Resume> resume_point(const RunRequest& request, const store::Store& db, Time start,
                            const DeploymentParts& parts) {
  const Deployment& d = request.deployment;
  RONDO_ASSIGN_OR_RETURN(const store::StoredRun stored, store::read_back(db, d.robots.front().name));
  std::optional<Time> stored_until = stored.latest();
  Resume r;
  for (std::size_t i = 0; i < d.robots.size(); ++i) {
    r.robot_at.push_back(parts.robots[i].start);
    r.robot_seed.push_back(robot_seed(d.seed, i));
    RONDO_ASSIGN_OR_RETURN(const std::optional<store::RobotState> state, store::load_robot_state(db, d.robots[i].name));
    if (!state) continue;
    if (const auto n = parts.map.find_node(state->node)) r.robot_at[i] = *n;
    stored_until = stored_until ? std::max(*stored_until, state->updated) : state->updated;
  }
  r.resumed = stored_until.has_value();
  r.at = request.realtime ? std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now())
                          : std::max(start, stored_until.value_or(start));
  // A resumed world is seeded from the seed and the time it resumes at: its draws from then on are
  // its own, but the same for the same kill.
  if (r.resumed)
    for (std::uint64_t& seed : r.robot_seed) {
      std::uint64_t mix = seed ^ static_cast<std::uint64_t>(r.at.time_since_epoch().count());
      seed = sim::splitmix64(mix);
    }
  return r;
}

// Spans on the charger for the day pictures, sampled once a minute (reads only: the run is the
// same with or without it).
class ChargerSpans {
 public:
  ChargerSpans(exec::Clock& clock, const exec::Robot& robot) : clock_(clock), robot_(robot) {}
  void start(Time at) {
    clock_.schedule_at(at, [this] { sample(); });
  }
  // The spans that overlap [from, to), the one still going cut at `to`.
  std::vector<std::pair<Time, Time>> between(Time from, Time to) const {
    std::vector<std::pair<Time, Time>> out;
    for (const auto& [a, b] : spans_)
      if (b > from && a < to) out.emplace_back(a, b);
    if (since_) out.emplace_back(*since_, to);
    return out;
  }

 private:
  void sample() {
    const bool on = robot_.charging();
    if (on && !since_) since_ = clock_.now();
    if (!on && since_) {
      spans_.emplace_back(*since_, clock_.now());
      since_.reset();
    }
    clock_.schedule_after(minutes(1), [this] { sample(); });
  }

  exec::Clock& clock_;
  const exec::Robot& robot_;
  std::vector<std::pair<Time, Time>> spans_;
  std::optional<Time> since_;
};

// Each robot's picture of the day: days/<date>.svg for a fleet of one, days/<date>-<robot>.svg for
// each robot of a larger one.
Status draw_day(const fleet::Fleet& fleet, const std::vector<std::unique_ptr<ChargerSpans>>& chargers,
                const RunRequest& request, const std::string& date, int day, Time from, Time to) {
  const Deployment& d = request.deployment;
  for (std::size_t i = 0; i < fleet.robots().size(); ++i) {
    const exec::Executor& executor = *fleet.robots()[i];
    const bool one = fleet.robots().size() == 1;
    const std::string title = one ? fmt::format("{} — {} (day {})", d.name, date, day + 1)
                                  : fmt::format("{} — {} — {} (day {})", d.name, executor.name(), date, day + 1);
    DayPicture picture = day_picture(executor, title, from, to, d.zone, /*every_task=*/one);
    picture.charging = chargers[i]->between(from, to);
    const std::string file = one ? date + ".svg" : fmt::format("{}-{}.svg", date, executor.name());
    RONDO_RETURN_IF_ERROR(write_file(request.out / "days" / file, render_day_svg(picture)));
  }
  return Status{};
}

}  // namespace

Result<RunResult> run_deployment(const RunRequest& request, std::ostream& progress_to) {
  const auto wall_start = std::chrono::steady_clock::now();
  const Deployment& d = request.deployment;
  const Time first_start = request.realtime ? std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now())
                                            : d.zone.at(d.start, Duration{0});
  RONDO_ASSIGN_OR_RETURN(Session s, open_session(request, first_start));
  if (s.folder.finished) return finished_run(request);
  const map::TopoMap& map = s.parts.map;
  store::Store& db = *s.folder.store;

  const Time start = s.folder.start;
  RONDO_ASSIGN_OR_RETURN(const Resume resume, resume_point(request, db, start, s.parts));
  const bool resumed = resume.resumed;
  const Time resume_at = resume.at;

  exec::SimClock sim_clock(resume_at);
  exec::SystemClock system_clock(request.speed);
  exec::Clock& clock = request.realtime ? static_cast<exec::Clock&>(system_clock) : sim_clock;
  exec::ExecutorOptions shared = d.executor;
  shared.dock = s.parts.dock;
  shared.seed = d.seed;
  // Every robot of the deployment (made before the fleet, which they outlive), each with its runner.
  std::vector<DeploymentRobot> deployed;
  std::vector<std::unique_ptr<ChargerSpans>> chargers;
  for (std::size_t i = 0; i < d.robots.size(); ++i) {
    RONDO_ASSIGN_OR_RETURN(DeploymentRobot robot,
                           make_robot(d, d.robots[i], s.parts, clock, resume.robot_at[i], resume.robot_seed[i]));
    chargers.push_back(std::make_unique<ChargerSpans>(clock, *robot.robot));
    deployed.push_back(std::move(robot));
  }
  fleet::Fleet fleet(clock, map, db, d.zone, shared, {}, make_allocator(d));
  fleet.set_reservations(reservations_for(d, s.parts));
  fleet.set_bookings(bookings_for(d, s.parts));
  for (std::size_t i = 0; i < d.robots.size(); ++i)
    fleet.add_robot(*deployed[i].robot, robot_options(d, d.robots[i], s.parts.robots[i]));
  exec::Executor& executor = fleet.robot();
  std::unique_ptr<exec::RobotListener> listener;
  if (request.wrap_listener) {
    listener = request.wrap_listener(executor);
    deployed.front().robot->set_listener(listener.get());
  }
  // The deployment's routines, with those that queued requests added (kept in the store).
  std::vector<std::string> skipped;
  RONDO_ASSIGN_OR_RETURN(std::vector<Routine> routines,
                         service::routines_to_run(db, s.parts.plan.routines, map, d.zone, &skipped));
  for (const std::string& why : skipped)
    progress_to << fmt::format("rondo run: a routine a request added is not run: {}\n", why);
  fleet.add_routines(std::move(routines));
  if (resumed) RONDO_RETURN_IF_ERROR(fleet.restore());
  // The deployment's one-off tasks, unless a previous start already stored them.
  std::vector<Task> one_off;
  for (const Task& t : s.parts.plan.tasks)
    if (!fleet.book().contains(t.id)) one_off.push_back(t);
  if (!one_off.empty()) RONDO_RETURN_IF_ERROR(fleet.add_tasks(std::move(one_off), "deployment"));
  // Requests queued by `rondo task add --data`: taken at start, and on the system clock every
  // half second of wall time as well.
  RequestIntake intake(clock, fleet, db);
  if (auto taken = intake.take_waiting(); !taken) return taken.error();
  fleet.start();
  if (request.realtime) intake.poll_every(intake_period(request.speed));
  // Said once the executor is running (scripts/crash-test waits for it before it aims a kill).
  if (!request.progress)
    progress_to << fmt::format("rondo run: {} the run in {} at {}\n", resumed ? "resumed" : "started",
                               request.out.string(), format_time(resume_at))
                << std::flush;

  for (const auto& charger : chargers) charger->start(resume_at);

  // People's requests come from their own stream, drawn day by day from the start as in an
  // uninterrupted run; a resumed run posts those after it resumes that are not stored yet.
  sim::Rng people_rng(d.seed * 0x9E3779B97F4A7C15ULL + 17);
  const auto run_until = [&](Time t) {
    if (request.realtime)
      system_clock.run_until(t);
    else
      sim_clock.run_until(t);
  };
  auto today = d.zone.local_date(start);
  // run.json: the cost of each simulated day, in wall and in CPU seconds (the CPU time does not
  // move with the machine's other load); null for a day that an earlier attempt ran.
  Json day_wall_seconds = Json::array(), day_cpu_seconds = Json::array();
  const Time end_at = request.run_for ? start + *request.run_for : Time::max();
  int days_flat = 0;  // days on which the robot read an empty battery
  for (int day = 0; day < d.days; ++day) {
    const auto day_wall_start = std::chrono::steady_clock::now();
    const double day_cpu_start = process_cpu_seconds();
    const auto tomorrow = std::chrono::year_month_day{std::chrono::sys_days{today} + std::chrono::days{1}};
    const Time day_from = std::max(start, d.zone.at(today, Duration{0}));
    const Time day_to = std::min(d.zone.at(tomorrow, Duration{0}), end_at);
    const bool done_before = resumed && day_to <= resume_at;  // its picture is already drawn
    if (s.parts.people) {
      for (sim::Request& r : s.parts.people->between(day_from, day_to, people_rng)) {
        if (resumed && (r.at < resume_at || fleet.book().contains(r.task.id))) continue;
        clock.schedule_at(
            r.at, [&fleet, tasks = r.tasks()]() mutable { (void)fleet.add_tasks(std::move(tasks), "request"); });
      }
    }
    if (done_before) {
      day_wall_seconds.push_back(nullptr);  // run by an earlier attempt
      day_cpu_seconds.push_back(nullptr);
    } else {
      const std::size_t empty_before = empty_readings(fleet);
      run_until(day_to);
      if (empty_readings(fleet) > empty_before) ++days_flat;
      day_wall_seconds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - day_wall_start).count());
      day_cpu_seconds.push_back(process_cpu_seconds() - day_cpu_start);
      RONDO_RETURN_IF_ERROR(draw_day(fleet, chargers, request, date_text(today), day, day_from, day_to));
    }
    if (request.progress) draw_progress(progress_to, day + 1, d.days);
    today = tomorrow;
    if (day_to >= end_at) break;
  }
  if (request.progress) progress_to << "\n";
  const Time end = request.realtime || request.run_for ? clock.now() : d.zone.at(today, Duration{0});

  RunResult result;
  result.resumed = resumed;
  RONDO_ASSIGN_OR_RETURN(const std::vector<Traversal> log, store::find_traversals(db));
  RunFigures figures{.from = start, .to = end, .charging = Duration{0}};
  for (std::size_t i = 0; i < deployed.size(); ++i) {
    const Duration charging = deployed[i].charging_time();
    figures.charging += charging;
    figures.charging_by_robot[d.robots[i].name] = charging;
  }
  navigation_from_log(map, log, start, end, d.robots.front().name, figures);
  result.report = run_report(fleet, figures);
  // The simulated truth beside what was learned of it (not for a real vehicle, which has no world).
  if (s.parts.world && result.report.contains("loading_times"))
    for (Json& t : result.report["loading_times"])
      if (auto truth = s.parts.world->confirmation.at(t["action"].get<std::string>(), t["place"].get<std::string>()))
        t["truth_s"] = to_seconds(*truth);
  result.report["battery"]["days_flat"] = days_flat;
  // The simulated battery's true costs beside the learned ones.
  if (s.parts.world) {
    const sim::BatteryModel& b = s.parts.world->battery;
    result.report["battery"]["truth"] = Json{{"per_km", b.per_metre * 1000},
                                             {"moving_per_hour", b.moving_per_hour},
                                             {"acting_per_hour", b.acting_per_hour},
                                             {"idle_per_hour", b.idle_per_hour},
                                             {"charging_per_hour", b.charging_per_hour}};
  }
  result.report["deployment"] = d.name;
  result.report["seed"] = d.seed;
  result.report["days"] = d.days;
  result.report["travel_table"] = travel_table(map, log, start, d.days, fleet.zone());
  // Several simulated robots in one building: their meetings (since this start, on a resumed run).
  if (s.parts.traffic) result.report["traffic"] = traffic_report(*s.parts.traffic);
  if (s.parts.reservations)
    result.report["traffic"]["reservations"] =
        reservation_report(*s.parts.reservations, fleet.building().traffic_waits, clock.now());
  if (s.parts.bookings) result.report["traffic"]["plan_around"] = plan_around_report(fleet.building().deferrals);
  if (d.reference) result.report["reference"] = reference_figures(*d.reference, result.report, d.days);
  RONDO_ASSIGN_OR_RETURN(const std::vector<store::Event> events, store::read_events(db));
  result.report["weeks"] = weekly_summary(log, events, start, end);
  result.write_errors = static_cast<int>(fleet.write_errors().size());
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  RONDO_RETURN_IF_ERROR(write_file(request.out / "report.json", result.report.dump(2) + "\n"));
  Json run{{"wall_seconds", result.wall_seconds},
           {"cpu_seconds", process_cpu_seconds()},
           {"simulated_days", d.days},
           {"day_wall_seconds", day_wall_seconds},
           {"day_cpu_seconds", day_cpu_seconds},
           {"realtime", request.realtime},
           {"resumed", resumed},
           {"store_write_errors", fleet.write_errors()}};
  RONDO_RETURN_IF_ERROR(write_file(request.out / "run.json", run.dump(2) + "\n"));
  RONDO_RETURN_IF_ERROR(mark_finished(db));
  return result;
}

}  // namespace rondo::app
