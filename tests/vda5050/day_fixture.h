// A short day of rondo driving a real VDA 5050 peer: Debian's mosquitto on a free loopback port,
// the virtual vehicle of vda-5050-lib 1.4.0 (tests/vda5050/peer) standing on the G4S dock, and
// `rondo run --realtime --speed S --for D` (run_deployment, on a thread of its own) with a
// deployment whose robot is that vehicle. A spy on the broker validates every order and
// instantActions message rondo sends against the official schemas and records the vehicle's
// states; the run's event log and traversal log are read from its store while it runs.
//
//   std::string why;
//   auto day = VdaDay::start(why);        // nullptr (and why) when mosquitto or node is absent
//   day->run({.tasks = {...}});           // in the background
//   day->wait_for_event("succeeded", 60s);
//   day->wait_run_done(60s);
//
// The vehicle drives at 1 m/s with a time-lapse equal to rondo's speed, so durations in the
// traversal log are in rondo's clock: an edge of L metres takes about L seconds there.
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"
#include "rondo/vda5050/messages.h"
#include "rondo/vda5050/mqtt_client.h"
#include "vda5050/processes.h"
#include "vda5050/schema_check.h"

namespace rondo::vda5050::testing {

using namespace std::chrono_literals;

inline constexpr double kVehicleSpeed = 1.0;  // m/s

struct DayTask {
  std::string id;
  std::string node;
  std::string action_yaml = "{name: noop, args: {duration: 3}}";  // 3 s on the vehicle
  std::chrono::minutes release_in{-1};  // its window opens this long after the start (rondo's clock)
};

struct DayOptions {
  std::vector<DayTask> tasks;
  double speed = 10;                // rondo's clock and the vehicle's time-lapse
  std::string run_for = "3m";       // on rondo's clock
  std::string executor_yaml = "{}";  // the deployment's executor section
  std::string offline_after = "20s";
  std::string robot_yaml = "";  // more keys of the robot section, e.g. ", information: [...]"
};

struct EventRow {
  std::int64_t time_ms = 0;
  std::string subject, task_id, event, code, reason;
};

struct TraversalRow {
  std::string edge_id;
  std::int64_t start_ms = 0;
  std::int64_t duration_ms = 0;
  bool success = false;
};

// What the spy saw on the vehicle's topics. Thread-safe.
class Spy {
 public:
  void on_message(const std::string& topic, const std::string& payload);
  std::vector<std::string> problems() const;  // schema violations of rondo's messages
  int orders() const;
  int instant_actions() const;
  std::optional<State> last_state() const;
  // How many distinct actions of this type the vehicle reported FINISHED.
  int finished_actions(const std::string& action_type) const;
  // Whether the vehicle reported a cancelOrder FINISHED.
  bool cancel_finished() const;

 private:
  mutable std::mutex mutex_;
  SchemaCheck order_raw_ = SchemaCheck::load("order", Strictness::kSchema);
  SchemaCheck order_standard_ = SchemaCheck::load("order", Strictness::kStandardShape);
  SchemaCheck instant_raw_ = SchemaCheck::load("instantActions", Strictness::kSchema);
  SchemaCheck instant_standard_ = SchemaCheck::load("instantActions", Strictness::kStandardShape);
  std::vector<std::string> problems_;
  int orders_ = 0;
  int instants_ = 0;
  std::optional<State> last_state_;
  std::vector<std::pair<std::string, std::string>> finished_;  // (type, id)
  bool cancel_finished_ = false;
};

class VdaDay {
 public:
  static std::unique_ptr<VdaDay> start(std::string& why);
  ~VdaDay();

  // Writes the deployment and starts the run in the background.
  void run(const DayOptions& options);
  bool wait_run_done(std::chrono::milliseconds deadline);
  // The run's result: "" when it succeeded, else its error.
  std::string run_error() const;

  // The event log and traversal log so far (empty before the store exists).
  std::vector<EventRow> events() const;
  std::vector<TraversalRow> traversals() const;
  // Every event as one line, for failure messages.
  std::string event_text() const;
  // Until an event whose name or code is `event` (and whose reason has `reason_has`) is logged.
  bool wait_for_event(const std::string& event, std::chrono::milliseconds deadline, const std::string& reason_has = "");
  std::vector<EventRow> events_named(const std::string& event) const;

  // The vehicle: started at the dock by start(); killed and started again by the fault tests.
  void start_vehicle(const std::string& node, double x, double y, double theta);
  void kill_vehicle();
  // SIGSTOP / SIGCONT: the vehicle falls silent with its connection open (no last will).
  void freeze_vehicle(bool frozen);
  // The vehicle publishes a state whose information[] is `entries` (a JSON array), once it is
  // ready; true when it said it did within `deadline`.
  bool tell_information(const Json& entries, std::chrono::milliseconds deadline);
  Broker& broker() { return *broker_; }
  Spy& spy() { return *spy_; }
  const Spy& spy() const { return *spy_; }
  MqttClient& spy_client() { return *spy_client_; }
  const map::TopoMap& map() const { return *map_; }
  const std::filesystem::path& dir() const { return dir_; }
  double speed() const { return speed_; }

 private:
  VdaDay() = default;
  std::string node_;
  std::unique_ptr<Broker> broker_;
  std::unique_ptr<map::TopoMap> map_;
  std::unique_ptr<ChildProcess> vehicle_;
  std::unique_ptr<Spy> spy_;
  std::unique_ptr<MqttClient> spy_client_;
  std::filesystem::path dir_;
  double speed_ = 10;
  std::thread run_thread_;
  mutable std::mutex run_mutex_;
  bool run_done_ = false;
  std::string run_error_;
};

}  // namespace rondo::vda5050::testing
