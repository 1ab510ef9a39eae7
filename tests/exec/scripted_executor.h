// A fleet of one: the executor on a ScriptedRobot (scripted_robot.h) on the scenario map, at the
// dock, at 08:00 on a Monday: the fixture of the scripted-robot tests.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "rondo/exec/executor.h"
#include "rondo/fleet/fleet.h"
#include "scenario.h"
#include "scripted_robot.h"

namespace rondo::exec::testing {

// The scenario map with the executor on a ScriptedRobot at the dock, at 08:00 on a Monday.
class ScriptedExecutor {
 public:
  // `dock`: the map's dock node (the office map's is "ChargingPoint").
  explicit ScriptedExecutor(ExecutorOptions options = {}, map::TopoMap map = scenario_map(), ExecutorParts parts = {},
                            const std::string& dock = "Dock")
      : map_(std::move(map)),
        zone_(TimeZone::named("Europe/London").value()),
        clock_(zone_.parse_time("2026-11-23T08:00").value()),
        db_(fresh_db_path()),
        store_(store::Store::open(db_, {.sync_commits = false}).value()),
        robot_(clock_, map_, *map_.find_node(dock)) {
    options.dock = *map_.find_node(dock);
    options.refit_at.reset();
    options_ = options;
    fleet_ = std::make_unique<fleet::Fleet>(clock_, map_, store_, zone_, options, std::move(parts.models));
    executor_ = &fleet_->add_robot(robot_, options, std::move(parts.scheduler));
  }
  // The executive is killed and started again on the same store (Fleet::restore): the robot
  // stops what the dead executive asked of it and stays where it is; the clock keeps its time but
  // none of the dead executive's timers.
  void kill_and_restart() {
    fleet_.reset();
    if (robot_.driving()) robot_.finish_edge(EdgeOutcome::kCancelled, seconds(1));
    if (robot_.acting()) robot_.finish_action(ActionOutcome::kCancelled, "the executive died");
    settle();
    clock_.clear();  // the dead executive's timers die with it
    fleet_ = std::make_unique<fleet::Fleet>(clock_, map_, store_, zone_, options_);
    executor_ = &fleet_->add_robot(robot_, options_);
    ASSERT_TRUE(fleet_->restore().ok());
    fleet_->start();
  }
  ~ScriptedExecutor() {
    fleet_.reset();
    std::error_code ec;
    std::filesystem::remove(db_, ec);
  }
  fleet::Fleet& fleet() { return *fleet_; }
  Executor& executor() { return *executor_; }  // the fleet's one robot
  ScriptedRobot& robot() { return robot_; }
  store::Store& store() { return store_; }
  SimClock& clock() { return clock_; }
  const map::TopoMap& map() const { return map_; }
  Time at(const std::string& local) const { return zone_.parse_time("2026-11-23T" + local).value(); }
  void run_until(const std::string& local) { clock_.run_until(at(local)); }
  void settle() { clock_.run_until(clock_.now()); }  // delivers what was posted, time stands still
  // Answers every edge with success after 20 s until the robot stands at `node`.
  void drive_to(const std::string& node) {
    const map::NodeIndex target = *map_.find_node(node);
    for (int guard = 0; robot_.location() != target && guard < 50; ++guard) {
      settle();
      ASSERT_TRUE(robot_.driving()) << "the executor asked for no edge on the way to " << node;
      clock_.run_until(clock_.now() + seconds(20));
      robot_.finish_edge(EdgeOutcome::kSucceeded, seconds(20));
      settle();
    }
  }
  // From memory, or from the store for a finished task that has left it (forget_finished).
  std::string state(const std::string& id) const { return to_string(executor_->book().state_of(id).value()); }
  std::string code_of(const std::string& id, const std::string& event) const {
    return last_event_field(store_, id, event, &store::Event::code);
  }
  std::string reason_of(const std::string& id, const std::string& event) const {
    return last_event_field(store_, id, event, &store::Event::reason);
  }

 protected:
  map::TopoMap map_;
  TimeZone zone_;
  SimClock clock_;
  std::filesystem::path db_;
  store::Store store_;
  ScriptedRobot robot_;
  ExecutorOptions options_;
  std::unique_ptr<fleet::Fleet> fleet_;
  Executor* executor_ = nullptr;
};

}  // namespace rondo::exec::testing
