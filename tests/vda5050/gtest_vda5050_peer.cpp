// rondo's VDA 5050 layer against a vehicle we did not write: the virtual AGV of the npm package
// vda-5050-lib 1.4.0 (tests/vda5050/peer), through Debian's mosquitto, on the G4S example map.
// An order over three edges (two released, one horizon), the update that releases the rest at
// the decision point, the node action run by the vehicle, and a cancel in the middle of an edge
// that is finished only when the vehicle reports FINISHED. Every message we send validates
// against the official schemas. Durations are measured on the test's clock; the vehicle drives
// at `kSpeed` with time-lapse `kTimeLapse`, so an edge of length L takes L / kSpeed / kTimeLapse.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>

#include "rondo/map/map_geometry.h"
#include "rondo/map/map_loader.h"
#include "rondo/vda5050/connection_watch.h"
#include "rondo/vda5050/decode.h"
#include "rondo/vda5050/encode.h"
#include "rondo/vda5050/header.h"
#include "rondo/vda5050/inbox.h"
#include "rondo/vda5050/mqtt_client.h"
#include "rondo/vda5050/order_builder.h"
#include "rondo/vda5050/progress.h"
#include "test_files.h"
#include "vda5050/event_queue.h"
#include "vda5050/processes.h"
#include "vda5050/schema_check.h"

namespace rondo::vda5050 {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

constexpr double kSpeed = 1.0;    // m/s, the virtual vehicle's
constexpr double kTimeLapse = 4;  // its time-lapse factor
constexpr auto kDeadline = 60s;   // generous: the machine may be busy

// What the vehicle last said, for failure messages.
std::string describe(const std::optional<State>& s) {
  if (!s) return "no state";
  std::string out = "order '" + s->order_id + "' update " + std::to_string(s->order_update_id) + ", last node " +
                    s->last_node_id + " (" + std::to_string(s->last_node_sequence_id) + "), " +
                    std::to_string(s->node_states.size()) + " nodes and " + std::to_string(s->edge_states.size()) +
                    " edges left, driving " + (s->driving ? "yes" : "no");
  for (const VehicleError& e : s->errors) out += "; error " + e.error_type + ": " + e.error_description;
  for (const ActionState& a : s->action_states) out += "; action " + a.action_id + " " + to_string(a.action_status);
  return out;
}

Time now() {
  return std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now());
}

// Master control for one vehicle, as the later Vda5050Robot will be: topics, headers, inbox,
// progress, and every outgoing message checked against the schemas.
struct Master {
  Topics topics{.interface_name = "uagv", .manufacturer = "acme", .serial_number = "agv-7"};
  Compatibility compat{.vda5050_lib_1_4 = true};  // the peer is vda-5050-lib 1.4.0
  HeaderCounter headers{"acme", "agv-7"};
  Inbox inbox{"acme", "agv-7"};
  ProgressTracker progress;
  testing::EventQueue queue;
  std::unique_ptr<MqttClient> client;
  testing::SchemaCheck order_schema = testing::SchemaCheck::load("order", testing::Strictness::kStandardShape);
  testing::SchemaCheck instant_schema = testing::SchemaCheck::load("instantActions", testing::Strictness::kSchema);

  std::optional<ConnectionState> connection;
  std::optional<State> last_state;
  std::optional<Factsheet> factsheet;
  int states = 0;
  std::vector<std::string> ignored;
  std::vector<ProgressEvent> events;
  bool connected = false;

  void on_message(const std::string& topic, const std::string& payload) {
    auto which = topics.parse(topic);
    if (which == Topic::kConnection) {
      auto c = decode_connection(payload);
      if (!c) return ignored.push_back(c.error().message);
      if (auto ok = inbox.admit(*c); !ok) return ignored.push_back(ok.error().message);
      connection = c->connection_state;
    } else if (which == Topic::kFactsheet) {
      auto f = decode_factsheet(payload, compat);
      if (!f) return ignored.push_back(f.error().message);
      if (auto ok = inbox.admit(Topic::kFactsheet, f->header); !ok) return ignored.push_back(ok.error().message);
      factsheet = std::move(*f);
    } else if (which == Topic::kState) {
      auto s = decode_state(payload);
      if (!s) return ignored.push_back(s.error().message);
      if (auto ok = inbox.admit(Topic::kState, s->header); !ok) return ignored.push_back(ok.error().message);
      ++states;
      for (ProgressEvent& e : progress.observe(*s, now())) events.push_back(std::move(e));
      last_state = std::move(*s);
    }
  }

  void send(const Order& order) {
    Json j = encode_order(headers.next(Topic::kOrder, now()), order);
    EXPECT_EQ(order_schema.problems(j), "");
    progress.order_sent(order, now());
    ASSERT_TRUE(
        client->publish({.topic = topics.of(Topic::kOrder), .payload = j.dump(), .qos = 1, .retained = false}).ok());
  }

  void instant(const Action& action) {
    Json j = encode_instant_actions(headers.next(Topic::kInstantActions, now()), InstantActions{.actions = {action}},
                                    compat);
    EXPECT_EQ(instant_schema.problems(j), "");
    ASSERT_TRUE(
        client->publish({.topic = topics.of(Topic::kInstantActions), .payload = j.dump(), .qos = 1, .retained = false})
            .ok());
  }

  void cancel(const std::string& action_id) {
    Json j = encode_instant_actions(headers.next(Topic::kInstantActions, now()),
                                    InstantActions{.actions = {cancel_order_action(action_id)}}, compat);
    // The compatibility key is extra; everything else is the standard shape.
    EXPECT_EQ(instant_schema.problems(j), "");
    progress.cancel_sent(action_id, now());
    ASSERT_TRUE(
        client->publish({.topic = topics.of(Topic::kInstantActions), .payload = j.dump(), .qos = 1, .retained = false})
            .ok());
  }

  template <class T>
  std::vector<T> all() const {
    std::vector<T> out;
    for (const ProgressEvent& e : events) {
      if (const T* t = std::get_if<T>(&e)) out.push_back(*t);
    }
    return out;
  }
};

// A path of `edges` edges that never steps straight back, starting anywhere.
std::vector<map::NodeIndex> some_path(const map::TopoMap& m, std::size_t edges, double min_length) {
  for (map::NodeIndex start = 0; start < m.node_count(); ++start) {
    std::vector<map::NodeIndex> route{start};
    std::vector<map::EdgeIndex> used;
    while (route.size() <= edges) {
      std::optional<map::EdgeIndex> next;
      for (map::EdgeIndex e : m.out_edges(route.back())) {
        const bool back = route.size() >= 2 && m.to_index(e) == route[route.size() - 2];
        if (!back && map::edge_length(m, e) >= min_length) {
          next = e;
          break;
        }
      }
      if (!next) break;
      route.push_back(m.to_index(*next));
    }
    if (route.size() == edges + 1) return route;
  }
  return {};
}

double expected_seconds(const map::TopoMap& m, const std::string& edge_id) {
  return map::edge_length(m, *m.find_edge(edge_id)) / kSpeed / kTimeLapse;
}

// Connects master control to the broker and subscribes to the vehicle's topics.
void connect(Master& master, const testing::Broker& broker) {
  auto client =
      MqttClient::create({.broker = broker.url(),
                          .client_id = "rondo-master-agv-7",
                          .will = std::nullopt,
                          .keep_alive = seconds(5),
                          .min_retry = seconds(1),
                          .max_retry = seconds(2)},
                         {.message = [&](const std::string& t, const std::string& p) { master.on_message(t, p); },
                          .connected = [&] { master.connected = true; },
                          .connection_lost = [&](const std::string&) { master.connected = false; }},
                         master.queue.poster());
  ASSERT_TRUE(client.ok()) << client.error().message;
  master.client = std::move(*client);
  for (Topic t : {Topic::kState, Topic::kConnection, Topic::kFactsheet}) {
    master.client->subscribe(master.topics.of(t), 1);
  }
  master.client->start();
  ASSERT_TRUE(master.queue.run_until([&] { return master.connected; }, kDeadline));
}

// The virtual vehicle standing on `at`.
std::unique_ptr<testing::ChildProcess> start_vehicle(const std::string& node, const testing::Broker& broker,
                                                     const map::Node& at, const fs::path& log) {
  // Numbers as --name=value: a negative value would otherwise read as an option.
  auto arg = [](const char* name, double v) { return std::string("--") + name + "=" + std::to_string(v); };
  return std::make_unique<testing::ChildProcess>(
      std::vector<std::string>{
          node, "tests/vda5050/peer/virtual_agv.js", "--broker", broker.url(), "--interface", "uagv", "--manufacturer",
          "acme", "--serial", "agv-7", "--map", "g4s_y2", "--node", at.name, arg("x", at.pose.x), arg("y", at.pose.y),
          arg("theta", std::remainder(at.pose.yaw, 2 * M_PI)), arg("speed", kSpeed), arg("time-lapse", kTimeLapse)},
      log);
}

// Until the vehicle has said ONLINE and sent a state (a fatal failure if it died meanwhile).
void wait_online(Master& master, testing::ChildProcess& agv, const fs::path& log) {
  ASSERT_TRUE(master.queue.run_until(
                  [&] {
                    return (master.connection == ConnectionState::kOnline && master.last_state.has_value()) ||
                           !agv.running();
                  },
                  kDeadline) &&
              agv.running())
      << "no ONLINE and state from the vehicle; its log: " << log;
}

// node, or "" (and the test is skipped by the caller) when it is not installed.
std::string node_program() {
  return testing::find_program({"/usr/bin/node", "/usr/local/bin/node"});
}

TEST(Vda5050Peer, OrderUpdateActionsAndCancelAgainstVdaLib) {
  std::string why;
  const std::string node = node_program();
  if (node.empty()) GTEST_SKIP() << "node is not installed (scripts/setup installs it)";
  auto broker = testing::Broker::start(why);
  if (!broker) GTEST_SKIP() << why;
  rondo::test::remove_at_exit(broker->dir());
  ASSERT_TRUE(fs::exists("tests/vda5050/peer/node_modules/vda-5050-lib"))
      << "the peer is not installed: run scripts/setup (npm ci in tests/vda5050/peer)";

  auto map = map::load_map("examples/g4s/map.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  const std::vector<map::NodeIndex> route = some_path(*map, 3, 2.0);
  ASSERT_EQ(route.size(), 4u);
  const map::Node& first = map->node(route[0]);

  Master master;
  ASSERT_NO_FATAL_FAILURE(connect(master, *broker));
  const fs::path log = broker->dir() / "virtual_agv.log";
  auto agv = start_vehicle(node, *broker, first, log);
  ASSERT_NO_FATAL_FAILURE(wait_online(master, *agv, log));
  EXPECT_EQ(master.last_state->last_node_id, first.name);

  // The order: two edges released, the third in the horizon, a node action at the end.
  RouteSpec spec{.route = route,
                 .base_edges = 2,
                 .map_id = "g4s_y2",
                 .final_actions = {rondo::Action{"noop", {{"duration", "2"}}}}};
  auto order = build_order(*map, "nav-1", spec);
  ASSERT_TRUE(order.ok()) << order.error().message;
  master.send(*order);
  ASSERT_TRUE(master.queue.run_until([&] { return !master.all<WaitingForUpdate>().empty(); }, kDeadline))
      << "the vehicle never waited at the end of the base: " << describe(master.last_state);
  EXPECT_EQ(master.all<WaitingForUpdate>().at(0).node_id, map->node(route[2]).name);
  auto edges = master.all<EdgeFinished>();
  ASSERT_EQ(edges.size(), 2u);
  EXPECT_TRUE(master.all<RouteFinished>().empty());  // waiting is not done

  // The update at the decision point releases the rest.
  RouteSpec rest{
      .route = {route[2], route[3]}, .base_edges = 1, .map_id = "g4s_y2", .final_actions = spec.final_actions};
  auto update = build_update(*map, *order, rest);
  ASSERT_TRUE(update.ok()) << update.error().message;
  master.send(*update);
  auto action_finished = [&] {
    for (const ActionChanged& a : master.all<ActionChanged>()) {
      if (a.action_type == "noop" && a.status == ActionStatus::kFinished) return true;
    }
    return false;
  };
  ASSERT_TRUE(
      master.queue.run_until([&] { return !master.all<RouteFinished>().empty() && action_finished(); }, kDeadline));
  edges = master.all<EdgeFinished>();
  ASSERT_EQ(edges.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const EdgeAttempt& a = edges[i].attempt;
    EXPECT_EQ(a.from_node, map->node(route[i]).name);
    EXPECT_EQ(a.to_node, map->node(route[i + 1]).name);
    EXPECT_EQ(a.outcome, EdgeOutcome::kSucceeded);
    EXPECT_TRUE(a.timed);
    // The attempt starts when the order is sent, so it cannot be shorter than the drive (less a
    // tick of 20 ms); it ends when the state arrives, late by a tick and by however busy the
    // machine is, hence the generous upper bound. Either bound fails if the speed or the
    // time-lapse were not what the vehicle drove with (time-lapse 4 makes a 4x difference).
    const double expected = expected_seconds(*map, a.edge_id);
    const double measured = to_seconds(a.duration);
    EXPECT_GT(measured, 0.9 * expected - 0.05) << a.edge_id;
    EXPECT_LT(measured, 1.5 * expected + 0.75) << a.edge_id;
    std::cout << "edge " << a.edge_id << ": " << measured << " s measured, " << expected << " s expected\n";
  }

  // Cancel in the middle of an edge: onward from the end, the longest edge out.
  const map::NodeIndex at = route[3];
  map::EdgeIndex longest = map->out_edges(at)[0];
  for (map::EdgeIndex e : map->out_edges(at)) {
    if (map::edge_length(*map, e) > map::edge_length(*map, longest)) longest = e;
  }
  auto second = build_order(
      *map, "nav-2", {.route = {at, map->to_index(longest)}, .base_edges = 1, .map_id = "g4s_y2", .final_actions = {}});
  ASSERT_TRUE(second.ok());
  master.send(*second);
  ASSERT_TRUE(master.queue.run_until(
      [&] { return master.last_state->order_id == "nav-2" && master.last_state->driving; }, kDeadline));
  master.cancel("cancel-1");
  EXPECT_TRUE(master.progress.cancel_pending());  // sent is not finished
  bool vehicle_said_finished = false;
  ASSERT_TRUE(master.queue.run_until(
      [&] {
        for (const ActionState& a : master.last_state->action_states) {
          if (a.action_id == "cancel-1" && a.action_status == ActionStatus::kFinished) vehicle_said_finished = true;
        }
        // Never finished before the vehicle said so.
        if (!vehicle_said_finished) {
          EXPECT_TRUE(master.all<CancelFinished>().empty());
        }
        return !master.all<CancelFinished>().empty();
      },
      kDeadline));
  EXPECT_TRUE(vehicle_said_finished);
  EXPECT_TRUE(master.all<CancelFinished>().at(0).succeeded);
  EXPECT_FALSE(master.progress.cancel_pending());
  edges = master.all<EdgeFinished>();
  ASSERT_EQ(edges.size(), 4u);
  EXPECT_EQ(edges[3].attempt.outcome, EdgeOutcome::kCancelled);
  EXPECT_LT(to_seconds(edges[3].attempt.duration), expected_seconds(*map, map->edge(longest).id) + 0.5);
  EXPECT_TRUE(master.ignored.empty()) << master.ignored.front();

  agv->stop();
  ASSERT_TRUE(master.queue.run_until([&] { return master.connection == ConnectionState::kOffline; }, kDeadline));
  master.client->stop();
}

// A vehicle killed with SIGKILL leaves its last will (CONNECTIONBROKEN), and the connection
// watch calls it offline; restarted, it says ONLINE, counts its headerIds from 0 again, and its
// states are taken (a new session), not ignored as out of order.
TEST(Vda5050Peer, AKilledVehicleLeavesItsLastWillAndARestartedOneIsTaken) {
  std::string why;
  const std::string node = node_program();
  if (node.empty()) GTEST_SKIP() << "node is not installed (scripts/setup installs it)";
  auto broker = testing::Broker::start(why);
  if (!broker) GTEST_SKIP() << why;
  rondo::test::remove_at_exit(broker->dir());
  ASSERT_TRUE(fs::exists("tests/vda5050/peer/node_modules/vda-5050-lib"))
      << "the peer is not installed: run scripts/setup (npm ci in tests/vda5050/peer)";
  auto map = map::load_map("examples/g4s/map.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  const map::Node& at = map->node(0);

  Master master;
  ConnectionWatch watch(seconds(30), master.compat);
  ASSERT_NO_FATAL_FAILURE(connect(master, *broker));
  const fs::path log = broker->dir() / "virtual_agv.log";
  auto agv = start_vehicle(node, *broker, at, log);
  ASSERT_NO_FATAL_FAILURE(wait_online(master, *agv, log));
  watch.on_connection(*master.connection, now());
  watch.on_state(now());
  EXPECT_TRUE(watch.online(now()));
  const int states_before = master.states;

  agv->kill_hard();
  ASSERT_TRUE(
      master.queue.run_until([&] { return master.connection == ConnectionState::kConnectionBroken; }, kDeadline));
  watch.on_connection(*master.connection, now());
  EXPECT_NE(watch.why_offline(now()).find("CONNECTIONBROKEN"), std::string::npos);

  agv = start_vehicle(node, *broker, at, log);
  master.last_state.reset();
  ASSERT_NO_FATAL_FAILURE(wait_online(master, *agv, log));
  EXPECT_GT(master.states, states_before);
  // Asked for, its factsheet is a header only (a known deviation), taken with the compatibility
  // option. (The one it publishes when it starts is dropped: it is not connected yet.)
  master.instant(factsheet_request_action("factsheet-1"));
  ASSERT_TRUE(master.queue.run_until([&] { return master.factsheet.has_value(); }, kDeadline))
      << (master.ignored.empty() ? std::string("nothing ignored") : master.ignored.back());
  EXPECT_TRUE(master.factsheet->header_only);
  EXPECT_FALSE(decode_factsheet(R"({"headerId":0,"timestamp":"2026-12-01T10:00:00Z","version":"2.0.0",
      "manufacturer":"acme","serialNumber":"agv-7"})")
                   .ok());
  EXPECT_LE(master.last_state->header.header_id, 2);  // a new session counts from 0 again
  EXPECT_TRUE(master.ignored.empty()) << master.ignored.front();
  agv->stop();
  master.client->stop();
}

}  // namespace
}  // namespace rondo::vda5050
