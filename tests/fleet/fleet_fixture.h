// A fleet of scripted robots (tests/exec/scripted_robot.h) on the scenario map, at 08:00 on a
// Monday: each robot is named, starts where the test says, and docks at Dock.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rondo/fleet/fleet.h"
#include "rondo/store/task_table.h"
#include "rondo/traffic/reservations.h"
#include "scenario.h"
#include "scripted_robot.h"

namespace rondo::fleet::testing {

using exec::testing::ScriptedRobot;

class ScriptedFleet {
 public:
  struct RobotAt {
    std::string name;
    std::string node;
    std::string dock{};  // its own dock; empty: the scenario's Dock
  };
  // `allocator` makes the fleet's allocator (again at each restart); empty: the fleet's default.
  // `map`: the scenario map unless given; `reserve`: the robots reserve their way, `plan_around`:
  // they plan around each other's stops (docs/traffic.md).
  explicit ScriptedFleet(const std::vector<RobotAt>& robots, std::function<std::unique_ptr<Allocator>()> allocator = {},
                         std::optional<map::TopoMap> map = std::nullopt, bool reserve = false, bool plan_around = false)
      : allocator_(std::move(allocator)),
        map_(map ? std::move(*map) : exec::testing::scenario_map()),
        zone_(TimeZone::named("Europe/London").value()),
        clock_(zone_.parse_time("2026-11-23T08:00").value()),
        db_(exec::testing::fresh_db_path()),
        store_(store::Store::open(db_, {.sync_commits = false}).value()) {
    for (const RobotAt& r : robots) {
      robots_.push_back(std::make_unique<ScriptedRobot>(clock_, map_, *map_.find_node(r.node)));
      names_.push_back(r.name);
      docks_.push_back(r.dock.empty() ? "Dock" : r.dock);
    }
    if (reserve) reservations_ = std::make_unique<traffic::Reservations>(map_);
    if (plan_around) bookings_ = std::make_unique<traffic::Bookings>(map_);
    make_fleet();
  }
  // The executive is killed and started again on the same store (Fleet::restore): the robots stop
  // what the dead executive asked of them and stay where they are; the clock keeps its time but
  // none of the dead executive's timers.
  void kill_and_restart() {
    fleet_.reset();
    clock_.clear();  // the dead executive's timers die with it
    for (auto& r : robots_) {
      if (r->driving()) r->finish_edge(exec::EdgeOutcome::kCancelled, seconds(1));
      if (r->acting()) r->finish_action(exec::ActionOutcome::kCancelled, "the executive died");
    }
    settle();  // the robots' answers find no listener
    make_fleet();
    ASSERT_TRUE(fleet_->restore().ok());
    fleet_->start();
  }
  ~ScriptedFleet() {
    fleet_.reset();
    std::error_code ec;
    std::filesystem::remove(db_, ec);
  }
  Fleet& fleet() { return *fleet_; }
  ScriptedRobot& robot(std::size_t i) { return *robots_.at(i); }
  exec::SimClock& clock() { return clock_; }
  store::Store& store() { return store_; }
  const map::TopoMap& map() const { return map_; }
  const traffic::Reservations& reservations() const { return *reservations_; }
  const traffic::Bookings& bookings() const { return *bookings_; }
  Time at(const std::string& local) const { return zone_.parse_time("2026-11-23T" + local).value(); }
  void settle() { clock_.run_until(clock_.now()); }
  // The robot a task is allocated to.
  std::string robot_of(const std::string& id) const { return fleet_->book().at(id).robot; }

 private:
  void make_fleet() {
    exec::ExecutorOptions shared;
    shared.dock = *map_.find_node("Dock");
    shared.refit_at.reset();
    fleet_ = std::make_unique<Fleet>(clock_, map_, store_, zone_, shared, nullptr,
                                     allocator_ ? allocator_() : std::unique_ptr<Allocator>{});
    fleet_->set_reservations(reservations_.get());
    fleet_->set_bookings(bookings_.get());
    for (std::size_t i = 0; i < robots_.size(); ++i) {
      exec::ExecutorOptions own = shared;
      own.robot_name = names_[i];
      own.dock = *map_.find_node(docks_[i]);
      fleet_->add_robot(*robots_[i], own);
    }
  }

  std::function<std::unique_ptr<Allocator>()> allocator_;
  map::TopoMap map_;
  TimeZone zone_;
  exec::SimClock clock_;
  std::filesystem::path db_;
  store::Store store_;
  std::vector<std::unique_ptr<ScriptedRobot>> robots_;
  std::vector<std::string> names_;
  std::vector<std::string> docks_;
  std::unique_ptr<traffic::Reservations> reservations_;  // outlives the fleet
  std::unique_ptr<traffic::Bookings> bookings_;          // outlives the fleet
  std::unique_ptr<Fleet> fleet_;
};

}  // namespace rondo::fleet::testing
