// VDA 5050 (issue 18): latency from a state message showing an edge done to the order update that
// extends the base, through a real mosquitto on loopback. A scripted vehicle (an MQTT client of
// this program) answers every order at once with "accepted" and then "edge done" states; a
// Vda5050Robot on a SystemClock drives an executor-like listener that, like the executor, calls
// drive() again from the new node in its on_edge_finished(). The time measured is the vehicle's:
// from just before it publishes the edge-done state to the arrival of the update (two broker
// hops, rondo's decoding, progress tracking, the listener, the order building and encoding).
//
//   build/bench/bench_vda5050_update [ROUNDS]     # default 500; needs mosquitto
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <thread>
#include <vector>

#include "bench_clock.h"
#include "rondo/core/document.h"
#include "rondo/exec/clock.h"
#include "rondo/map/map_loader.h"
#include "rondo/vda5050/encode.h"
#include "rondo/vda5050/header.h"
#include "rondo/vda5050/mqtt_client.h"
#include "rondo/vda5050/vda5050_robot.h"
#include "vda5050/processes.h"

namespace rondo {
namespace {

using vda5050::MqttClient;

// Back and forth between two nodes, one edge committed, two more in the horizon: what the
// executor would hand the robot.
class Shuttle final : public exec::RobotListener {
 public:
  Shuttle(exec::Robot& robot, map::EdgeIndex there, map::EdgeIndex back) : robot_(robot), there_(there), back_(back) {}
  void go() {
    const bool at_start = robot_.location() == start_;
    const map::EdgeIndex a = at_start ? there_ : back_;
    const map::EdgeIndex b = at_start ? back_ : there_;
    robot_.drive({.edges = {a, b, a}, .committed = 1});
  }
  void set_start(map::NodeIndex n) { start_ = n; }
  void on_edge_finished(const exec::EdgeAttempt& a) override {
    if (a.succeeded() && !robot_.busy()) go();
  }
  void on_action_finished(const exec::ActionResult&) override {}
  void on_interruptible_changed(bool) override {}
  void on_observation(const exec::Observation&) override {}
  void on_fault(const exec::RobotFault&) override {}
  void on_ready() override {
    if (!started_) {
      started_ = true;
      go();
    }
  }

 private:
  exec::Robot& robot_;
  map::EdgeIndex there_, back_;
  map::NodeIndex start_ = 0;
  bool started_ = false;
};

// The scripted vehicle: accepts every order and reports its next node reached at once.
struct Vehicle {
  std::unique_ptr<MqttClient> client;
  vda5050::HeaderCounter headers{"acme", "bench-1"};
  std::mutex mutex;
  std::string node;
  std::int64_t sequence = 0;
  std::vector<double> latencies;
  std::optional<double> sent_at;
  int rounds = 0;
  std::atomic<bool> done{false};
  Json order = Json{{"nodes", Json::array()}, {"edges", Json::array()}};  // the last one taken

  // A stateRequest (the robot sends one on connecting): where it stands, with its order.
  void on_instant_actions() {
    std::lock_guard lock(mutex);
    publish_state(order, true);
  }

  static Time now() { return std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now()); }

  void publish_state(const Json& taken, bool advanced) {
    Json s = vda5050::encode_header(headers.next(vda5050::Topic::kState, now()));
    s["orderId"] = taken.value("orderId", "");
    s["orderUpdateId"] = taken.value("orderUpdateId", 0);
    s["lastNodeId"] = node;
    s["lastNodeSequenceId"] = sequence;
    Json nodes = Json::array(), edges = Json::array();
    for (const Json& n : taken["nodes"]) {
      if (n["sequenceId"].get<std::int64_t>() > sequence)
        nodes.push_back({{"nodeId", n["nodeId"]}, {"sequenceId", n["sequenceId"]}, {"released", n["released"]}});
    }
    for (const Json& e : taken["edges"]) {
      if (e["sequenceId"].get<std::int64_t>() > sequence)
        edges.push_back({{"edgeId", e["edgeId"]}, {"sequenceId", e["sequenceId"]}, {"released", e["released"]}});
    }
    s["nodeStates"] = nodes;
    s["edgeStates"] = edges;
    s["driving"] = !advanced;
    s["operatingMode"] = "AUTOMATIC";
    s["actionStates"] = Json::array();
    s["batteryState"] = {{"batteryCharge", 80.0}, {"charging", false}};
    s["errors"] = Json::array();
    s["safetyState"] = {{"eStop", "NONE"}, {"fieldViolation", false}};
    (void)client->publish({.topic = "uagv/v2/acme/bench-1/state", .payload = s.dump(), .qos = 1, .retained = false});
  }

  void on_order(const std::string& payload) {
    std::lock_guard lock(mutex);
    if (done) return;
    const double arrived = bench::steady_seconds();
    order = Json::parse(payload);
    if (sent_at && order.value("orderUpdateId", 0) > 0) {
      latencies.push_back(arrived - *sent_at);
      if (static_cast<int>(latencies.size()) >= rounds) {
        done = true;
        return;
      }
    }
    publish_state(order, false);  // accepted, driving the released edge
    // The released edge, done: the vehicle is at the next base node.
    for (const Json& n : order["nodes"]) {
      if (n["sequenceId"].get<std::int64_t>() == sequence + 2 && n["released"].get<bool>()) {
        node = n["nodeId"].get<std::string>();
        sequence += 2;
        break;
      }
    }
    sent_at = bench::steady_seconds();
    publish_state(order, true);
  }
};

// The floor under any master control: the same two broker hops with an echo that does nothing.
std::vector<double> echo_baseline(const std::string& url, int rounds) {
  std::mutex m;
  std::condition_variable cv;
  std::optional<double> sent, got;
  auto noop_post = [](std::function<void()> f) { f(); };
  std::unique_ptr<MqttClient> echo, pinger;
  auto e = MqttClient::create({.broker = url, .client_id = "bench-echo", .will = std::nullopt},
                              {.message = [&](const std::string&, const std::string& p) {
                                 (void)echo->publish({.topic = "bench/pong", .payload = p, .qos = 1, .retained = false});
                               },
                               .connected = nullptr,
                               .connection_lost = nullptr},
                              noop_post);
  auto p = MqttClient::create({.broker = url, .client_id = "bench-pinger", .will = std::nullopt},
                              {.message = [&](const std::string&, const std::string&) {
                                 std::lock_guard lock(m);
                                 got = bench::steady_seconds();
                                 cv.notify_all();
                               },
                               .connected = nullptr,
                               .connection_lost = nullptr},
                              noop_post);
  echo = std::move(*e);
  pinger = std::move(*p);
  echo->subscribe("bench/ping", 1);
  pinger->subscribe("bench/pong", 1);
  echo->start();
  pinger->start();
  vda5050::testing::wait_until([&] { return echo->connected() && pinger->connected(); }, std::chrono::seconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // let both subscriptions settle (a bench only)
  std::vector<double> out;
  for (int i = 0; i < rounds; ++i) {
    std::unique_lock lock(m);
    got.reset();
    const double t0 = bench::steady_seconds();
    (void)pinger->publish({.topic = "bench/ping", .payload = std::string(600, 'x'), .qos = 1, .retained = false});
    if (!cv.wait_for(lock, std::chrono::seconds(5), [&] { return got.has_value(); })) break;
    out.push_back(*got - t0);
  }
  echo->stop();
  pinger->stop();
  return out;
}

void print_quantiles(const std::string& what, std::vector<double> l) {
  if (l.empty()) return;
  std::sort(l.begin(), l.end());
  const auto at = [&](double q) {
    return l[std::min(l.size() - 1, static_cast<std::size_t>(q * static_cast<double>(l.size())))];
  };
  fmt::print("  {:<44} median {:6.2f} ms   p90 {:6.2f} ms   p99 {:6.2f} ms   max {:6.2f} ms\n", what, 1e3 * at(0.5),
             1e3 * at(0.9), 1e3 * at(0.99), 1e3 * l.back());
}

int run(int rounds) {
  std::string why;
  auto broker = vda5050::testing::Broker::start(why);
  if (!broker) {
    fmt::print(stderr, "bench_vda5050_update: {}\n", why);
    return 1;
  }
  auto map = map::load_map("examples/g4s/map.yaml");
  if (!map) {
    fmt::print(stderr, "{}\n", map.error().message);
    return 1;
  }
  const map::NodeIndex a = *map->find_node("WayPoint6");
  const map::EdgeIndex there = map->out_edges(a)[0];
  const map::NodeIndex b = map->to_index(there);
  std::optional<map::EdgeIndex> back;
  for (map::EdgeIndex e : map->out_edges(b))
    if (map->to_index(e) == a) back = e;
  if (!back) return 1;

  Vehicle vehicle;
  vehicle.rounds = rounds;
  vehicle.node = map->node(a).name;
  auto client = MqttClient::create(
      {.broker = broker->url(), .client_id = "bench-vehicle", .will = std::nullopt},
      {.message = [&](const std::string& t, const std::string& p) {
         if (t.ends_with("/order")) vehicle.on_order(p);
         if (t.ends_with("/instantActions")) vehicle.on_instant_actions();
       },
       .connected = nullptr,
       .connection_lost = nullptr},
      [](std::function<void()> f) { f(); });
  vehicle.client = std::move(*client);
  vehicle.client->subscribe("uagv/v2/acme/bench-1/order", 1);
  vehicle.client->subscribe("uagv/v2/acme/bench-1/instantActions", 1);
  vehicle.client->start();
  vda5050::testing::wait_until([&] { return vehicle.client->connected(); }, std::chrono::seconds(20));

  exec::SystemClock clock;
  vda5050::Vda5050Config config{.broker = broker->url(),
                                .topics = {.interface_name = "uagv", .manufacturer = "acme", .serial_number = "bench-1"},
                                .map_id = "g4s_y2",
                                .offline_after = seconds(60),
                                .compat = {}};
  auto robot = vda5050::Vda5050Robot::create(clock, *map, config, {.start = a});
  if (!robot) {
    fmt::print(stderr, "{}\n", robot.error().message);
    return 1;
  }
  Shuttle shuttle(**robot, there, *back);
  shuttle.set_start(a);
  (*robot)->set_listener(&shuttle);
  (void)(*robot)->activate();
  std::thread stopper([&] {
    vda5050::testing::wait_until([&] { return vehicle.done.load(); }, std::chrono::seconds(300));
    clock.stop();
  });
  clock.run_until(clock.now() + hours(1));
  stopper.join();
  (*robot)->deactivate();
  vehicle.client->stop();

  if (vehicle.latencies.empty()) {
    fmt::print(stderr, "bench_vda5050_update: no update arrived\n");
    return 1;
  }
  const std::vector<double> echo = echo_baseline(broker->url(), rounds);
  fmt::print("through mosquitto on loopback, {} rounds (load {}); goal: p99 < 10 ms\n", vehicle.latencies.size(),
             bench::load_average());
  print_quantiles("state 'edge done' -> order update (rondo)", vehicle.latencies);
  print_quantiles("the same two hops, echoed (no master control)", echo);
  return 0;
}

}  // namespace
}  // namespace rondo

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 500;
  return rondo::run(rounds > 0 ? rounds : 500);
}
