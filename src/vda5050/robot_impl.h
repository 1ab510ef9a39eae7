// The insides of Vda5050Robot (vda5050_robot.h), shared by vda5050_robot.cpp (lifecycle,
// messages, faults) and robot_commands.cpp (drive, actions, cancel, and how progress ends them).
// Everything here runs on the clock's thread.
#pragma once

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "rondo/vda5050/connection_watch.h"
#include "rondo/vda5050/header.h"
#include "rondo/vda5050/inbox.h"
#include "rondo/vda5050/information.h"
#include "rondo/vda5050/mqtt_client.h"
#include "rondo/vda5050/order_builder.h"
#include "rondo/vda5050/progress.h"
#include "rondo/vda5050/vda5050_robot.h"

namespace rondo::vda5050 {

// A drive(): its committed edges, answered one by one.
struct DriveJob {
  std::vector<map::EdgeIndex> committed;
  std::size_t next = 0;   // the first edge not answered yet
  Time current_since{};   // when that edge became the one to drive
};

// A run_action(): the VDA action that carries it.
struct ActionJob {
  std::string name;
  std::string action_id;
  Time sent{};
  std::optional<Time> started;
};

struct Vda5050Robot::Impl {
  Impl(exec::Clock& clock, const map::TopoMap& map, Vda5050Config config, Vda5050RobotOptions options);

  // vda5050_robot.cpp
  Status activate();
  void stop();
  void schedule_check();
  static Time wall_now();
  Status publish(Topic topic, const Json& message);
  // Posts a listener call to the clock; `ends_job`: the last callback of a command.
  void deliver(std::function<void(exec::RobotListener&)> call, bool ends_job = false);
  void ignore(const std::string& why);
  void on_connected();
  void on_connection_lost(const std::string& cause);
  void on_message(const std::string& topic, const std::string& payload);
  void on_state(State s);
  std::optional<map::Pose> position() const;
  void update_faults();

  // robot_commands.cpp
  void drive(const exec::Route& route);
  void run_action(const rondo::Action& action, Duration expected);
  void cancel();
  void handle(const ProgressEvent& e);
  void end_job(const std::string& fault_message);
  bool can_stitch_at(map::NodeIndex node) const;
  Result<Order> order_from(map::NodeIndex start, RouteSpec spec);
  Status send_order(const Order& order);
  void finish_edge(const exec::EdgeAttempt& attempt);
  void finish_action(exec::ActionOutcome outcome, const std::string& message);
  void rejected(const Rejected& r);

  exec::Clock& clock;
  const map::TopoMap& map;
  Vda5050Config config;
  Vda5050RobotOptions options;
  exec::RobotListener* listener = nullptr;
  std::shared_ptr<int> life = std::make_shared<int>(0);  // posted closures check it is still there

  HeaderCounter headers;
  Inbox inbox;
  ProgressTracker progress;
  ConnectionWatch watch;
  InformationReader information;
  std::unique_ptr<MqttClient> client;
  exec::TimerId check_timer = 0;
  exec::TimerId retry_timer = 0;

  map::NodeIndex location;
  std::optional<AgvPosition> agv_position;
  std::optional<State> last_state;
  std::optional<Factsheet> factsheet;  // the last one the vehicle sent
  double battery = 1.0;  // until the vehicle says
  bool charging = false;
  double distance_m = 0;
  std::vector<std::string> ignored;
  std::set<std::string> unknown_nodes;

  const std::string order_prefix;  // unique per run: orderIds and instant action ids
  std::uint64_t order_count = 0;
  std::uint64_t instant_count = 0;
  std::optional<Order> order;           // the last order or update the vehicle took (or may take)
  std::optional<Order> before_pending;  // what `order` was before the last one sent
  std::optional<ProgressTracker> progress_before;  // and the tracker, for a rejection
  std::variant<std::monostate, DriveJob, ActionJob> job;
  std::optional<std::string> cancel_id;
  int ending = 0;  // a command's last callback posted, not delivered yet

  std::optional<std::string> vehicle_fault;   // FATAL errors, operating mode
  std::optional<std::string> rejected_fault;  // a rejected drive, until the retry
  std::string broker_cause;
  std::optional<exec::RobotFault> reported_fault;
};

}  // namespace rondo::vda5050
