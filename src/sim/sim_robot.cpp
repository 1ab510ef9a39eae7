#include "rondo/sim/sim_robot.h"

#include <stdexcept>

#include "rondo/map/map_geometry.h"

namespace rondo::sim {

SimRobot::SimRobot(exec::Clock& clock, const map::TopoMap& map, SimWorld& world, SimRobotOptions options)
    : clock_(clock),
      map_(map),
      world_(world),
      options_(options),
      rng_(options.seed),
      location_(options.start),
      battery_(world.battery.initial),
      battery_since_(clock.now()) {
  if (options.start >= map.node_count() || options.dock >= map.node_count()) {
    throw std::logic_error("SimRobot: start or dock is not a node of the map");
  }
  if (!world.edges) throw std::logic_error("SimRobot: the world has no edges");
}

SimRobot::~SimRobot() {
  for (const auto& [key, id] : posted_) clock_.cancel(id);
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
  if (job_ && !job_->cancelled) return job_->is_edge ? BatteryModel::Mode::kMoving : BatteryModel::Mode::kActing;
  if (!job_ && location_ == options_.dock) return BatteryModel::Mode::kCharging;
  return BatteryModel::Mode::kIdle;
}

double SimRobot::battery() const {
  return world_.battery.after(battery_, mode(), clock_.now() - battery_since_);
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

void SimRobot::traverse(map::EdgeIndex edge) {
  if (busy()) throw std::logic_error("SimRobot::traverse while busy");
  if (edge >= map_.edge_count() || map_.from_index(edge) != location_) {
    throw std::logic_error("SimRobot::traverse: the edge does not leave the robot's location");
  }
  settle_battery();
  Job job{.is_edge = true, .edge = edge, .start = clock_.now()};
  if (battery_ > 0) {
    const EdgeSample s = world_.edges->sample_edge(edge, job.start, rng_);
    job.success = s.success;
    job.duration = s.duration;
  } else {
    job.success = false;  // an empty battery: the robot cannot move
  }
  start(std::move(job));
}

void SimRobot::run_action(const Action& action, Duration expected) {
  if (busy()) throw std::logic_error("SimRobot::run_action while busy");
  settle_battery();
  Job job{.is_edge = false, .action = action.name, .start = clock_.now()};
  ActionSample s{.success = false};
  if (battery_ > 0) {
    s = world_.actions.sample(action, expected, rng_);
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

void SimRobot::cancel() {
  if (!job_ || job_->cancelled) return;
  settle_battery();
  unpost(job_->finish_post);
  job_->cancelled = true;
  job_->success = false;
  job_->duration = clock_.now() - job_->start;
  if (job_->interruptible_post != 0) {
    unpost(job_->interruptible_post);
    job_->interruptible_post = 0;
    post(clock_.now(), [this] { notify_interruptible(true); });
  }
  job_->finish_post = post(clock_.now(), [this] { finish(); });
}

void SimRobot::finish() {
  settle_battery();
  const Job job = std::move(*job_);
  job_.reset();
  if (job.is_edge && job.success && !job.cancelled) {
    location_ = map_.to_index(job.edge);
    distance_m_ += map::edge_length(map_, job.edge);
  }
  deliver(job);
}

void SimRobot::deliver(const Job& job) {
  if (listener_ == nullptr) return;
  if (job.is_edge) {
    listener_->on_edge_finished(
        {.edge = job.edge, .start = job.start, .duration = job.duration, .success = job.success, .cancelled = job.cancelled});
    return;
  }
  exec::ActionResult result{.name = job.action, .start = job.start, .duration = job.duration};
  if (job.cancelled) {
    result.outcome = exec::ActionOutcome::kCancelled;
    result.message = "cancelled";
  } else if (!job.success) {
    result.outcome = exec::ActionOutcome::kFailed;
    result.message = job.message;
  }
  listener_->on_action_finished(result);
}

void SimRobot::notify_interruptible(bool interruptible) {
  if (listener_ != nullptr) listener_->on_interruptible_changed(interruptible);
}

}  // namespace rondo::sim
