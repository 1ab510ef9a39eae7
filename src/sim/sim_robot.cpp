#include "rondo/sim/sim_robot.h"

#include <cmath>
#include <set>
#include <stdexcept>

#include "rondo/map/map_geometry.h"

namespace rondo::sim {

SimRobot::SimRobot(exec::Clock& clock, const map::TopoMap& map, SimWorld& world, SimRobotOptions options)
    : clock_(clock),
      map_(map),
      world_(world),
      options_(options),
      rng_(options.seed),
      sensor_rng_(options.seed ^ 0xD00A5E5502ULL),
      location_(options.start),
      battery_(options.battery ? options.battery->initial : world.battery.initial),
      battery_since_(clock.now()) {
  if (options.start >= map.node_count() || options.dock >= map.node_count()) {
    throw std::logic_error("SimRobot: start or dock is not a node of the map");
  }
  if (!world.edges) throw std::logic_error("SimRobot: the world has no edges");
  if (options.traffic) traffic_id_ = options.traffic->join(options.name, options.start, clock.now(), this);
  // The doors the sensor can see from each node: each door once, by one of its edges.
  doors_near_.resize(map.node_count());
  if (world.door_sensor.enabled) {
    for (map::NodeIndex n = 0; n < map.node_count(); ++n) {
      const map::Pose& at = map.node(n).pose;
      std::set<std::string> seen;
      for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) {
        const auto& door = map.edge(e).door;
        if (!door || seen.contains(*door)) continue;
        for (map::NodeIndex end : {map.from_index(e), map.to_index(e)}) {
          const map::Pose& p = map.node(end).pose;
          if (std::hypot(p.x - at.x, p.y - at.y) <= world.door_sensor.range_m) {
            seen.insert(*door);
            doors_near_[n].emplace_back(*door, e);
            break;
          }
        }
      }
    }
  }
}

SimRobot::~SimRobot() {
  for (const auto& [key, id] : posted_) clock_.cancel(id);
  if (options_.traffic) options_.traffic->leave(traffic_id_, clock_.now());
}

std::uint64_t SimRobot::post(Time at, std::function<void()> callback) {
  const std::uint64_t key = next_post_++;
  posted_[key] = clock_.schedule_at(at, [this, key, cb = std::move(callback)] {
    posted_.erase(key);
    cb();
  });
  return key;
}

void SimRobot::unpost(std::uint64_t key) {
  const auto it = posted_.find(key);
  if (it == posted_.end()) return;
  clock_.cancel(it->second);
  posted_.erase(it);
}

BatteryModel::Mode SimRobot::mode() const {
  if (job_ && job_->end == End::kNatural) return job_->is_edge ? BatteryModel::Mode::kMoving : BatteryModel::Mode::kActing;
  if (!job_ && location_ == options_.dock) return BatteryModel::Mode::kCharging;
  return BatteryModel::Mode::kIdle;
}

std::optional<exec::ActionSupport> SimRobot::supported_actions() const {
  if (!options_.actions) return std::nullopt;
  return exec::ActionSupport{.robot = "simulated robot " + options_.name, .actions = *options_.actions};
}

double SimRobot::battery() const {
  return battery_model().after(battery_, mode(), clock_.now() - battery_since_);
}

bool SimRobot::charging() const { return mode() == BatteryModel::Mode::kCharging; }

Duration SimRobot::charging_time() const {
  return charging_time_ + (charging() ? clock_.now() - battery_since_ : Duration{0});
}

void SimRobot::settle_battery() {
  const Time now = clock_.now();
  if (charging()) charging_time_ += now - battery_since_;
  battery_ = battery();
  battery_since_ = now;
}

void SimRobot::start(Job job) {
  job_ = std::move(job);
  job_->finish_post = post(job_->start + job_->duration, [this] { finish(); });
}

void SimRobot::drive(const exec::Route& route) {
  if (busy()) throw std::logic_error("SimRobot::drive while busy");
  if (route.edges.empty() || route.committed < 1 || route.committed > route.edges.size())
    throw std::logic_error("SimRobot::drive: a route needs 1 <= committed <= its edges");
  map::NodeIndex at = location_;
  for (map::EdgeIndex e : route.edges) {
    if (e >= map_.edge_count() || map_.from_index(e) != at)
      throw std::logic_error("SimRobot::drive: the route does not leave the robot's location edge after edge");
    at = map_.to_index(e);
  }
  route_.assign(route.edges.begin() + 1, route.edges.begin() + static_cast<std::ptrdiff_t>(route.committed));
  start_edge(route.edges.front());
}

void SimRobot::rescue_if_stranded() {
  if (battery_ > 0 || location_ == options_.dock || !battery_model().rescue_after) {
    empty_since_.reset();
    return;
  }
  const Time now = clock_.now();
  if (!empty_since_) empty_since_ = now;
  if (now - *empty_since_ < *battery_model().rescue_after) return;
  location_ = options_.dock;  // carried back onto the charger: the command fails, from the dock
  if (options_.traffic) options_.traffic->carry(traffic_id_, location_, now);
  empty_since_.reset();
  ++rescues_;
}

void SimRobot::start_edge(map::EdgeIndex edge) {
  settle_battery();
  rescue_if_stranded();
  Job job{.is_edge = true, .edge = edge, .start = clock_.now()};
  if (fault_) {
    job.success = false;
    job.end = End::kFault;
    job.message = fault_->message;
  } else if (battery_ > 0) {
    if (options_.traffic && options_.traffic->blocker(traffic_id_, edge)) return hold(std::move(job));
    sample_edge(job);
  } else {
    job.success = false;  // an empty battery: the robot cannot move
  }
  start(std::move(job));
}

void SimRobot::sample_edge(Job& job) {
  const Time now = clock_.now();
  const EdgeSample s = world_.edges->sample_edge(job.edge, now, rng_);
  job.success = s.success;
  job.duration = s.duration;
  if (options_.speed != 1.0)
    job.duration =
        Duration{static_cast<Duration::rep>(std::llround(static_cast<double>(s.duration.count()) / options_.speed))};
  job.duration += now - job.start;  // the time it was held up
  if (options_.traffic) {
    options_.traffic->enter(traffic_id_, job.edge, now);
    job.entered = true;
  }
}

void SimRobot::hold(Job job) {
  Traffic& traffic = *options_.traffic;
  traffic.hold(traffic_id_, job.edge, job.start);
  job_ = std::move(job);
  job_->held = true;
  job_->hold_timeout_post = post(job_->start + traffic.options().hold_timeout, [this] {
    job_->hold_timeout_post = 0;
    give_up_hold();
  });
}

void SimRobot::on_way_may_be_clear() {
  if (!job_ || !job_->held || job_->recheck_post != 0) return;
  // Not from inside the traffic's call: on the clock, after what moves now.
  job_->recheck_post = post(clock_.now(), [this] {
    job_->recheck_post = 0;
    look_again();
  });
}

void SimRobot::look_again() {
  if (!job_ || !job_->held || options_.traffic->blocker(traffic_id_, job_->edge)) return;  // still held up
  leave_hold(HoldUp::End::kPassed);
  sample_edge(*job_);
  job_->finish_post = post(job_->start + job_->duration, [this] { finish(); });
}

void SimRobot::give_up_hold() {
  const std::optional<Blocker> blocker = options_.traffic->blocker(traffic_id_, job_->edge);
  if (!blocker) return look_again();  // cleared at this very moment
  leave_hold(HoldUp::End::kTimedOut);
  job_->success = false;
  job_->message = blocker->text();
  job_->duration = clock_.now() - job_->start;
  job_->finish_post = post(clock_.now(), [this] { finish(); });
}

void SimRobot::leave_hold(HoldUp::End how) {
  if (!job_ || !job_->held) return;
  options_.traffic->end_hold(traffic_id_, clock_.now(), how);
  unpost(job_->hold_timeout_post);
  unpost(job_->recheck_post);
  job_->hold_timeout_post = job_->recheck_post = 0;
  job_->held = false;
}

void SimRobot::run_action(const Action& action, Duration expected) {
  if (busy()) throw std::logic_error("SimRobot::run_action while busy");
  settle_battery();
  rescue_if_stranded();
  Job job{.is_edge = false, .action = action.name, .start = clock_.now()};
  ActionSample s{.success = false};
  if (fault_) {
    job.end = End::kFault;
    job.message = fault_->message;
  } else if (battery_ > 0) {
    // A person's confirmation takes its own time, whatever the executor expects.
    const Duration mean = world_.confirmation.at(action.name, map_.node(location_).name).value_or(expected);
    s = world_.actions.sample(action, mean, rng_);
    if (!s.success) job.message = "simulated failure of '" + action.name + "'";
  } else {
    job.message = "battery empty";
  }
  job.success = s.success;
  job.duration = s.duration;
  if (s.non_interruptible > Duration{0}) {
    // Posted before the finish, so at equal times the span's end arrives before the result.
    post(job.start, [this] { notify_interruptible(false); });
    job.interruptible_post = post(job.start + s.non_interruptible, [this] {
      job_->interruptible_post = 0;
      notify_interruptible(true);
    });
  }
  start(std::move(job));
}

void SimRobot::cancel() { stop_job(End::kCancelled, "cancelled"); }

void SimRobot::stop_job(End end, std::string message) {
  route_.clear();
  if (!job_ || job_->end != End::kNatural) return;
  settle_battery();
  leave_hold(HoldUp::End::kStopped);
  unpost(job_->finish_post);
  job_->end = end;
  job_->message = std::move(message);
  job_->success = false;
  job_->duration = clock_.now() - job_->start;
  if (job_->interruptible_post != 0) {
    unpost(job_->interruptible_post);
    job_->interruptible_post = 0;
    post(clock_.now(), [this] { notify_interruptible(true); });
  }
  job_->finish_post = post(clock_.now(), [this] { finish(); });
}

void SimRobot::inject_fault(exec::RobotFault fault) {
  fault_ = fault;
  // The fault is reported first, then the result of what it cut short.
  post(clock_.now(), [this, fault] {
    if (listener_ != nullptr) listener_->on_fault(fault);
  });
  stop_job(End::kFault, fault.message);
}

void SimRobot::clear_fault() {
  if (!fault_) return;
  fault_.reset();
  post(clock_.now(), [this] {
    if (listener_ != nullptr) listener_->on_ready();
  });
}

void SimRobot::finish() {
  settle_battery();
  const Job job = std::move(*job_);
  job_.reset();
  if (job.is_edge) {
    if (job.success && job.end == End::kNatural) {
      location_ = map_.to_index(job.edge);
      const double metres = map::edge_length(map_, job.edge);
      distance_m_ += metres;
      battery_ = battery_model().after_distance(battery_, metres);
    }
    if (job.entered) options_.traffic->arrive(traffic_id_, location_, clock_.now());
    // The rest of the committed route goes on after a success; anything else ends the drive.
    if (job.success && job.end == End::kNatural && !route_.empty()) {
      const map::EdgeIndex next = route_.front();
      route_.erase(route_.begin());
      start_edge(next);
    } else {
      route_.clear();
    }
    sense_doors();
  }
  deliver(job);
}

void SimRobot::deliver(const Job& job) {
  if (listener_ == nullptr) return;
  if (job.is_edge) {
    exec::EdgeAttempt a{.edge = job.edge, .start = job.start, .duration = job.duration};
    switch (job.end) {
      case End::kNatural: a.outcome = job.success ? exec::EdgeOutcome::kSucceeded : exec::EdgeOutcome::kFailed; break;
      case End::kCancelled: a.outcome = exec::EdgeOutcome::kCancelled; break;
      case End::kFault: a.outcome = exec::EdgeOutcome::kRobotFault; break;
    }
    if (job.end != End::kNatural || !job.message.empty()) a.message = job.message;
    listener_->on_edge_finished(a);
    return;
  }
  exec::ActionResult result{.name = job.action, .start = job.start, .duration = job.duration};
  if (job.end == End::kCancelled) {
    result.outcome = exec::ActionOutcome::kCancelled;
    result.message = job.message;
  } else if (job.end == End::kFault) {
    result.outcome = exec::ActionOutcome::kRobotFault;
    result.message = job.message;
  } else if (!job.success) {
    result.outcome = exec::ActionOutcome::kFailed;
    result.message = job.message;
  }
  listener_->on_action_finished(result);
}

void SimRobot::sense_doors() {
  if (listener_ == nullptr || !world_.door_sensor.enabled) return;
  const Time now = clock_.now();
  for (const auto& [door, edge] : doors_near_[location_]) {
    if (sensor_rng_.bernoulli(world_.door_sensor.miss_rate)) continue;
    const std::optional<bool> closed = world_.edges->closed_at(edge, now);
    if (!closed) continue;  // a world that does not know its doors shows nothing
    listener_->on_observation({.what = "door_open", .where = door, .when = now, .value = *closed ? 0.0 : 1.0});
  }
}

void SimRobot::notify_interruptible(bool interruptible) {
  if (listener_ != nullptr) listener_->on_interruptible_changed(interruptible);
}

}  // namespace rondo::sim
