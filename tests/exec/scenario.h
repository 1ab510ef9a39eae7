// A small simulated deployment for the executor's scenario tests: a fleet of one, the real Executor
// driving the real SimRobot on a SimClock, in a parametric world given as YAML, with a store in a
// fresh file.
//
//   Scenario s(kCalmWorld);
//   s.fleet().add_task(task("a", "Office", s.at("09:00"), s.at("10:00"), minutes(5)), "test");
//   s.run_until("12:00");
//   EXPECT_EQ(s.final_state("a"), "succeeded");
//
// Map: Dock -- Hall -- Office, Hall -- Kitchen, Hall -- Lab; every edge 10 m (20 s at 0.5 m/s).
#pragma once

#include <algorithm>

#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/task.h"
#include "rondo/core/timezone.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor.h"
#include "rondo/fleet/fleet.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/sim_robot.h"
#include "rondo/sim/sim_world.h"
#include "rondo/store/events.h"
#include "rondo/store/store.h"
#include "test_files.h"

namespace rondo::exec::testing {

// No noise, no failures, no bursts: time and outcomes are exactly what the map says.
inline constexpr const char* kCalmWorld = R"(
kind: parametric
speed: 0.5
failure_probability: 0
noise: {sigma: 0, tail_probability: 0}
actions:
  default: {sigma: 0, failure_probability: 0, overrun_probability: 0}
)";

inline map::TopoMap scenario_map() {
  std::vector<map::Node> nodes = {{.name = "Dock", .pose = {0, 0, 0}},
                                  {.name = "Hall", .pose = {10, 0, 0}},
                                  {.name = "Office", .pose = {20, 0, 0}},
                                  {.name = "Kitchen", .pose = {10, 10, 0}},
                                  {.name = "Lab", .pose = {10, -10, 0}}};
  std::vector<map::Edge> edges;
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{
           {"Dock", "Hall"}, {"Hall", "Office"}, {"Hall", "Kitchen"}, {"Hall", "Lab"}}) {
    edges.push_back({.id = a + "_" + b, .from = a, .to = b, .action = "move_base"});
    edges.push_back({.id = b + "_" + a, .from = b, .to = a, .action = "move_base"});
  }
  return map::TopoMap::build("scenario", std::move(nodes), std::move(edges)).value();
}

inline std::filesystem::path fresh_db_path() {
  static std::atomic<int> counter{0};
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "scenario";
  std::replace(name.begin(), name.end(), '/', '_');  // parameterised tests: Suite/Test/Param
  // The process's own folder, removed at its exit with the store's -wal and -shm files.
  auto dir = std::filesystem::temp_directory_path() / ("rondo-exec-tests-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  if (!std::getenv("RONDO_KEEP_TEST_DB")) rondo::test::remove_at_exit(dir);
  auto file = dir / (name + "-" + std::to_string(counter++) + ".sqlite");
  std::filesystem::remove(file);
  return file;
}

// A field of the task's last event named `event` in the store; "" when there is none.
inline std::string last_event_field(const store::Store& store, const std::string& id, const std::string& event,
                                    std::string store::Event::*field) {
  std::string value;
  const std::vector<store::Event> events = store::read_events_of(store, id).value();
  for (const store::Event& e : events)
    if (e.event == event) value = e.*field;
  return value;
}

class Scenario {
 public:
  explicit Scenario(const std::string& world_yaml, ExecutorOptions options = {},
                    const std::string& start = "2026-11-23T08:00")
      : map_(scenario_map()),
        zone_(TimeZone::named("Europe/London").value()),
        clock_(zone_.parse_time(start).value()),
        db_(fresh_db_path()),
        store_(store::Store::open(db_, {.sync_commits = false}).value()) {
    auto doc = Document::parse(world_yaml, DocumentFormat::kYaml, "world.yaml").value();
    world_ = std::make_unique<sim::SimWorld>(sim::decode_world(doc, ".", map_, zone_).value());
    const map::NodeIndex dock = *map_.find_node("Dock");
    robot_ = std::make_unique<sim::SimRobot>(clock_, map_, *world_, sim::SimRobotOptions{.start = dock, .dock = dock});
    options.dock = dock;
    fleet_ = std::make_unique<fleet::Fleet>(clock_, map_, store_, zone_, options);
    executor_ = &fleet_->add_robot(*robot_, options);
  }
  ~Scenario() {
    fleet_.reset();
    robot_.reset();
    std::error_code ec;
    if (!std::getenv("RONDO_KEEP_TEST_DB")) std::filesystem::remove(db_, ec);
  }

  fleet::Fleet& fleet() { return *fleet_; }
  Executor& executor() { return *executor_; }  // the fleet's one robot
  sim::SimRobot& robot() { return *robot_; }
  SimClock& clock() { return clock_; }
  const map::TopoMap& map() const { return map_; }
  store::Store& store() { return store_; }
  Time at(const std::string& local_time) const { return zone_.parse_time("2026-11-23T" + local_time).value(); }
  void run_until(const std::string& local_time) { clock_.run_until(at(local_time)); }

  std::vector<store::Event> events_of(const std::string& id) const {
    return store::read_events_of(store_, id).value();
  }
  std::vector<store::Event> all_events() const { return store::read_events(store_).value(); }
  std::string final_state(const std::string& id) const {
    auto it = executor_->tasks().find(id);
    return it == executor_->tasks().end() ? "unknown" : to_string(it->second.state);
  }
  // The reason and the code of the task's last event named `event`; "" when there is none.
  std::string reason_of(const std::string& id, const std::string& event) const {
    return last_event_field(store_, id, event, &store::Event::reason);
  }
  std::string code_of(const std::string& id, const std::string& event) const {
    return last_event_field(store_, id, event, &store::Event::code);
  }
  // The order in which tasks reached `state`, from the event log.
  std::vector<std::string> order_of(const std::string& state) const {
    std::vector<std::string> ids;
    for (const auto& e : all_events())
      if (e.event == state) ids.push_back(e.task_id);
    return ids;
  }

 private:
  map::TopoMap map_;
  TimeZone zone_;
  SimClock clock_;
  std::filesystem::path db_;
  store::Store store_;
  std::unique_ptr<sim::SimWorld> world_;
  std::unique_ptr<sim::SimRobot> robot_;
  std::unique_ptr<fleet::Fleet> fleet_;
  Executor* executor_ = nullptr;
};

inline Task task(const std::string& id, const std::string& node, Time release, Time deadline, Duration duration,
                 int priority = 1, bool interruptible = true) {
  Task t;
  t.id = id;
  t.activity = "work at " + node;
  t.window = TimeWindow{release, deadline};
  t.duration = duration;
  t.priority = priority;
  t.start_node = node;
  t.interruptible = interruptible;
  t.actions = {Action{.name = "work", .args = {}}};
  return t;
}

inline Task on_demand(const std::string& id, const std::string& node, Duration duration, int priority = 5) {
  Task t;
  t.id = id;
  t.activity = "asked for at " + node;
  t.kind = TaskKind::kOnDemand;
  t.duration = duration;
  t.priority = priority;
  t.start_node = node;
  t.actions = {Action{.name = "talk", .args = {}}};
  return t;
}

}  // namespace rondo::exec::testing
