// A live service for the API tests: the G4S example's map and simulated world (or another
// example's, LiveOptions::deployment), an executor on a SystemClock that starts at
// LiveOptions::start and runs on its own thread, and a service::Server on an ephemeral loopback port,
// with an httplib client pointed at it. Conditions are awaited with generous deadlines.
#pragma once

#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "deployment.h"
#include "deployment_parts.h"
#include "rondo/core/document.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor.h"
#include "rondo/fleet/fleet.h"
#include "rondo/service/server.h"
#include "rondo/sim/sim_robot.h"
#include "rondo/store/store.h"

namespace rondo::test {

struct LiveOptions {
  std::optional<std::string> token = std::nullopt;
  std::size_t body_limit = 1 << 20;
  Duration read_timeout = seconds(5);
  double speed = 1.0;
  int threads = 16;
  Duration answer_timeout = seconds(30);
  std::string deployment = "examples/g4s/deployment.yaml";  // under the source tree
  // Where the service's clock starts: a Wednesday morning (UTC), whatever the machine's date, so
  // that "tomorrow", today's schedule and an hour from now never straddle a midnight by chance.
  std::string start = "2026-11-25T10:00:00Z";
  // The actions the robot says it runs (Robot::supported_actions), as a vehicle's factsheet
  // lists them; nothing: it does not say (the simulated robot runs any action).
  std::optional<std::vector<std::string>> robot_actions = std::nullopt;
  // More simulated robots in the same world, by name (a fleet); the first is always "robot".
  std::vector<std::string> more_robots = {};
};

class LiveService {
 public:
  // `data`: the folder of rondo.sqlite (kept across instances to test a restart).
  LiveService(const std::filesystem::path& data, LiveOptions o = {});
  ~LiveService();

  int port() const { return port_; }
  httplib::Client client() const;
  httplib::Headers auth() const;
  exec::SystemClock& clock() { return clock_; }
  const map::TopoMap& map() const { return parts_.map; }
  service::Server& server() { return *server_; }
  store::Store& store() { return store_; }  // use it only on the clock's thread (on_clock)
  fleet::Fleet& fleet() { return *fleet_; }          // read it only on the clock's thread (on_clock)
  exec::Executor& executor() { return *executor_; }  // read it only on the clock's thread (on_clock)
  // Runs `f` on the clock's thread and waits (for reading the executor in a test).
  void on_clock(const std::function<void()>& f);

  // A standard task at WayPoint2 whose window opens `from_now` after the clock's now.
  std::string task_body(const std::string& id, Duration from_now = hours(1), Duration width = hours(2),
                        Duration duration = minutes(2)) const;

 private:
  app::DeploymentParts parts_;
  store::Store store_;
  exec::SystemClock clock_;
  std::unique_ptr<sim::SimRobot> sim_;
  std::vector<std::unique_ptr<sim::SimRobot>> more_;  // LiveOptions::more_robots
  std::unique_ptr<exec::Robot> with_actions_;  // LiveOptions::robot_actions: the simulated robot saying so
  exec::Robot* robot_ = nullptr;               // the one the executor drives
  std::unique_ptr<fleet::Fleet> fleet_;
  exec::Executor* executor_ = nullptr;
  std::unique_ptr<service::Server> server_;
  std::optional<std::string> token_;
  int port_ = 0;
  std::thread clock_thread_, http_thread_;
};

// Parses a response body, failing the test (and returning null) when it is not JSON.
Json body_of(const httplib::Result& r);

// Waits until `done` holds, for up to `deadline` (generous: the machine may be slow).
bool eventually(const std::function<bool()>& done, Duration deadline = seconds(30));

}  // namespace rondo::test
