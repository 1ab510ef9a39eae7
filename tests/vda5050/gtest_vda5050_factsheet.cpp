// A vehicle's factsheet says which actions it runs: Vda5050Robot asks for it after connecting
// (factsheetRequest) and reads protocolFeatures.agvActions, and the executor then refuses, when it
// is submitted, a task with an action the vehicle does not list, naming the action and the vehicle
// (before, such a task was driven to its place and failed there: "order action is not executable").
// Before any factsheet, or with one that lists no actions, every task is taken as before. The
// vehicle is scripted here (an MQTT client that answers factsheetRequest), through a real
// mosquitto: vda-5050-lib's virtual vehicle sends a header-only factsheet (docs/vda5050.md).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>

#include "rondo/exec/clock.h"
#include "rondo/exec/executor.h"
#include "rondo/fleet/fleet.h"
#include "rondo/map/map_loader.h"
#include "rondo/store/store.h"
#include "rondo/vda5050/mqtt_client.h"
#include "rondo/vda5050/vda5050_robot.h"
#include "test_files.h"
#include "vda5050/processes.h"

namespace rondo::vda5050 {
namespace {

using namespace std::chrono_literals;
using testing::Broker;

constexpr auto kDeadline = 60s;  // generous: the machine may be busy

// The factsheet of acme/agv-9: it runs noop, pick and drop.
std::string factsheet_json() {
  return R"({"headerId":0,"timestamp":"2026-12-01T10:00:00Z","version":"2.0.0","manufacturer":"acme",
    "serialNumber":"agv-9","typeSpecification":{"seriesName":"scripted","agvKinematic":"DIFF","agvClass":"CARRIER",
    "maxLoadMass":10,"localizationTypes":["NATURAL"],"navigationTypes":["AUTONOMOUS"]},
    "protocolFeatures":{"optionalParameters":[],"agvActions":[
      {"actionType":"noop","actionScopes":["NODE"]},{"actionType":"pick","actionScopes":["NODE"]},
      {"actionType":"drop","actionScopes":["NODE"]}]}})";
}

Task visit(const std::string& id, const std::string& action, Time now) {
  Task t;
  t.id = id;
  t.activity = "a visit";
  t.window = TimeWindow{now + hours(1), now + hours(3)};
  t.duration = minutes(2);
  t.start_node = "WayPoint2";
  t.actions = {Action{action, {}}};
  return t;
}

TEST(Vda5050Factsheet, ATaskWithAnActionTheVehicleDoesNotListIsRefusedWhenSubmitted) {
  std::string why;
  auto broker = Broker::start(why);
  if (!broker) GTEST_SKIP() << why;
  rondo::test::remove_at_exit(broker->dir());
  const auto dir = rondo::test::fresh_dir("rondo-vda5050-factsheet", "store");

  auto map = map::load_map("examples/g4s/map.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  const map::NodeIndex dock = *map->find_node("ChargingPoint");
  exec::SystemClock clock;
  const auto pump = [&](const std::function<bool()>& done) {
    return testing::wait_until(
        [&] {
          clock.run_due();
          return done();
        },
        std::chrono::duration_cast<std::chrono::milliseconds>(kDeadline));
  };

  // The scripted vehicle: it answers every factsheetRequest with its factsheet.
  std::atomic<int> asked{0};
  int vehicle_connected = 0;  // on the clock's thread, as the handlers run
  std::unique_ptr<MqttClient> vehicle;
  MqttHandlers handlers{
      .message =
          [&](const std::string&, const std::string& payload) {
            const Json j = Json::parse(payload, nullptr, false);
            if (j.is_discarded() || !j.contains("actions")) return;
            for (const Json& a : j["actions"]) {
              if (a.value("actionType", "") != "factsheetRequest") continue;
              ++asked;
              (void)vehicle->publish(
                  {.topic = "uagv/v2/acme/agv-9/factsheet", .payload = factsheet_json(), .qos = 1, .retained = false});
            }
          },
      .connected = [&] { ++vehicle_connected; },
      .connection_lost = nullptr};
  auto created = MqttClient::create({.broker = broker->url(), .client_id = "scripted-agv-9", .will = std::nullopt},
                                    std::move(handlers), [&clock](std::function<void()> f) { clock.post(std::move(f)); });
  ASSERT_TRUE(created.ok()) << created.error().message;
  vehicle = std::move(*created);
  vehicle->subscribe("uagv/v2/acme/agv-9/instantActions", 1);
  vehicle->start();
  // Subscribed before the robot connects and asks.
  ASSERT_TRUE(pump([&] { return vehicle_connected > 0; })) << "the scripted vehicle did not connect";

  auto robot = Vda5050Robot::create(
      clock, *map,
      {.broker = broker->url(),
       .topics = {.interface_name = "uagv", .manufacturer = "acme", .serial_number = "agv-9"},
       .map_id = "g4s_y2",
       .offline_after = seconds(30),
       .compat = {}},
      {.start = dock});
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  auto db = store::Store::open(dir / "rondo.sqlite", {.sync_commits = false});
  ASSERT_TRUE(db.ok()) << db.error().message;
  fleet::Fleet executor(clock, *map, *db, TimeZone::utc(), {.dock = dock});
  executor.add_robot(**robot, {.dock = dock});

  // Nothing known yet: every action is taken, as before.
  EXPECT_FALSE((*robot)->supported_actions().has_value());
  ASSERT_TRUE(executor.add_task(visit("check-before", "check", clock.now()), "api").ok());

  ASSERT_TRUE((*robot)->activate().ok());
  ASSERT_TRUE(pump([&] { return (*robot)->supported_actions().has_value(); }))
      << "no factsheet; the vehicle was asked " << asked << " time(s)";
  EXPECT_GE(asked, 1);
  EXPECT_EQ((*robot)->supported_actions()->actions, (std::vector<std::string>{"noop", "pick", "drop"}));

  Status refused = executor.add_task(visit("check-after", "check", clock.now()), "api");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::kInvalidInput);
  EXPECT_EQ(refused.error().message,
            "task check-after: vehicle acme/agv-9 (its factsheet) cannot run the action 'check'; it runs: noop, pick, "
            "drop");
  EXPECT_FALSE(executor.task("check-after").value().has_value());  // nothing was added
  EXPECT_TRUE(executor.add_task(visit("noop-after", "noop", clock.now()), "api").ok());
  (*robot)->deactivate();
  vehicle->stop();
}

}  // namespace
}  // namespace rondo::vda5050
