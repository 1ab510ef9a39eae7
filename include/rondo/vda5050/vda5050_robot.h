// A VDA 5050 vehicle as the executor's robot (exec::Robot): rondo is its master control over
// MQTT (docs/vda5050.md). One Vda5050Robot per vehicle; nothing here assumes one vehicle per
// broker.
//
//   auto robot = Vda5050Robot::create(clock, map, config, {.start = dock});
//   (*robot)->set_listener(&executor);
//   executor.start();                  // activate(): connects; a fault until the vehicle is there
//
// - drive(route) becomes an order: the committed edges are the base (released), the rest of the
//   route the horizon. The next drive() from the node where the base ends is an order update
//   stitched there (same orderId, orderUpdateId + 1), which extends the base and replaces the
//   horizon. A drive from anywhere else (after a cancel, a dropped order, a restarted vehicle) is
//   a new order, whose first node is where the vehicle stands: no heading asked for, and a
//   deviation range wide enough to cover the vehicle's reported position.
// - run_action() is an update (or a new order) of one node, the one where the vehicle stands,
//   with the action on it (blockingType HARD, its arguments as actionParameters); the vehicle's
//   actionStates finish it.
// - cancel() sends the instant action cancelOrder; what runs ends as cancelled only when the
//   vehicle reports that action FINISHED (a FAILED one: the order goes on).
// - Faults (on_fault / on_ready): the vehicle offline (connection topic, silence past
//   offline_after, rondo's own broker connection lost), an error of level FATAL, an operatingMode
//   other than AUTOMATIC, and an order the vehicle rejected for a drive (the fault then lasts
//   `retry_rejected_after`, after which the executor tries again from where the vehicle is). A
//   running edge or action that a fault interrupts ends with kRobotFault (not learning data). The
//   vehicle may go on meanwhile; its states move location() as they come.
// - Rejections (validationError, orderError, orderUpdateError, noRouteError) reach the event log
//   in the vehicle's words: a rejected drive as the fault's message, a rejected action as the
//   failed action's message.
// - Every MQTT event reaches the robot through Clock::post(), so everything here, and every
//   listener callback, runs on the clock's thread. Paho reconnects and re-subscribes by itself;
//   after each (re)connect the robot asks the vehicle for its state (stateRequest) and its
//   factsheet (factsheetRequest); the actions a factsheet lists are supported_actions(), so the
//   executor refuses a task with any other action when it is submitted.
// - The vehicle is always interruptible (VDA 5050 has no such notion): on_interruptible_changed
//   is never called.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/robot.h"
#include "rondo/map/topo_map.h"
#include "rondo/vda5050/config.h"
#include "rondo/vda5050/topics.h"

namespace rondo::vda5050 {

struct Vda5050RobotOptions {
  map::NodeIndex start = 0;  // where the vehicle is taken to be until its first state says
  std::string client_id{};   // "" -> "rondo-<interface>-<manufacturer>-<serial>"
  Duration retry_rejected_after = seconds(30);  // rondo's clock
  Duration check_every = seconds(2);            // silence check, rondo's clock
  // Called with every message published (topic, JSON), after it was sent: for tests that
  // validate them against the schemas, and for benchmarks.
  std::function<void(Topic, const Json&)> on_published{};
};

class Vda5050Robot final : public exec::Robot {
 public:
  // Errors: a broker address Paho cannot take, a start node outside the map.
  static Result<std::unique_ptr<Vda5050Robot>> create(exec::Clock& clock, const map::TopoMap& map,
                                                      Vda5050Config config, Vda5050RobotOptions options);
  ~Vda5050Robot() override;
  Vda5050Robot(const Vda5050Robot&) = delete;
  Vda5050Robot& operator=(const Vda5050Robot&) = delete;

  void set_listener(exec::RobotListener* listener) override;
  Status activate() override;
  void deactivate() override;
  map::NodeIndex location() const override;
  std::optional<map::Pose> position() const override;
  bool busy() const override;
  void drive(const exec::Route& route) override;
  void run_action(const rondo::Action& action, Duration expected) override;
  void cancel() override;
  double battery() const override;
  bool charging() const override;
  std::optional<exec::RobotFault> fault() const override;
  // The actions the vehicle's factsheet lists (protocolFeatures.agvActions); nothing before a
  // factsheet came, or when it lists none (vda-5050-lib 1.4.0's is a header only).
  std::optional<exec::ActionSupport> supported_actions() const override;

  // Metres of edges the vehicle reported passed (succeeded attempts), for the run report.
  double distance_m() const;
  // Messages from the vehicle ignored so far (malformed, another vehicle, out of order), with
  // the reason; the robot also reports each as an Observation "vda5050_ignored".
  const std::vector<std::string>& ignored() const;

  struct Impl;  // src/vda5050/robot_impl.h

 private:
  explicit Vda5050Robot(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace rondo::vda5050
