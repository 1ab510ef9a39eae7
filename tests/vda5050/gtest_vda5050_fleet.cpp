// Ten VDA 5050 vehicles on one broker (issue 38, point 6): `rondo serve` (the binary, --speed 10)
// with a deployment of ten vda5050 robots, one Vda5050Robot each, against ten virtual vehicles of
// vda-5050-lib (tests/vda5050/peer) on one mosquitto on a free loopback port, on the G4S map. Two
// tasks per vehicle are submitted at once, each at a place of its own, and the fleet allocates
// them. A spy on the broker records every order each vehicle receives and every action it
// reports finished. Checked: every task succeeds, on one robot; each vehicle's orders lead only to
// its own tasks' places (or its dock); each vehicle finished exactly as many actions as it had
// tasks; no task's events name two robots; and the store, the API's per-robot counts and the
// vehicles agree. Not in the sanitizer builds (tests/vda5050/CMakeLists.txt).
#include <gtest/gtest.h>
#include <httplib.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <mutex>
#include <regex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/time.h"
#include "rondo/map/map_loader.h"
#include "rondo/store/events.h"
#include "rondo/store/store.h"
#include "rondo/store/task_table.h"
#include "rondo/vda5050/decode.h"
#include "rondo/vda5050/mqtt_client.h"
#include "service/serve_process.h"
#include "test_files.h"
#include "vda5050/processes.h"

namespace rondo::vda5050::testing {
namespace {

using namespace std::chrono_literals;

constexpr int kVehicles = 10;
constexpr int kTasksPerVehicle = 2;
constexpr double kSpeed = 10;     // rondo's clock and the vehicles' time-lapse
constexpr auto kDeadline = 300s;  // generous: ten node processes, a broker and rondo on a busy 2-core machine

// Where each vehicle stands (its dock too), and the places of the tasks: all distinct, so that a
// place in an order says whose task it is.
const std::vector<std::string> kStands = {"WayPoint1",  "WayPoint4",  "WayPoint10", "WayPoint13", "WayPoint16",
                                          "WayPoint20", "WayPoint23", "WayPoint26", "WayPoint30", "WayPoint40"};
const std::vector<std::string> kPlaces = {"WayPoint2",  "WayPoint3",  "WayPoint5",  "WayPoint6",  "WayPoint9",
                                          "WayPoint11", "WayPoint12", "WayPoint14", "WayPoint15", "WayPoint17",
                                          "WayPoint18", "WayPoint19", "WayPoint21", "WayPoint22", "WayPoint24",
                                          "WayPoint25", "WayPoint27", "WayPoint28", "WayPoint29", "WayPoint31"};

std::string vehicle_name(int i) {
  return fmt::format("v{}", i);
}

// What each vehicle received and reported, from its topics. Thread-safe.
class FleetSpy {
 public:
  void on_message(const std::string& topic, const std::string& payload) {
    // uagv/v2/acme/<serial>/<level>
    const std::size_t level_at = topic.rfind('/');
    const std::size_t serial_at = topic.rfind('/', level_at - 1);
    const std::string serial = topic.substr(serial_at + 1, level_at - serial_at - 1);
    const std::string level = topic.substr(level_at + 1);
    std::lock_guard lock(mutex_);
    if (level == "order") {
      const Json j = Json::parse(payload, nullptr, /*allow_exceptions=*/false);
      if (j.is_discarded() || !j.contains("nodes") || j["nodes"].empty()) {
        problems_.push_back(serial + ": an order that is not JSON with nodes: " + payload);
        return;
      }
      // The route's end: the last node of the order (or of the update), horizon included.
      destinations_[serial].insert(j["nodes"].back()["nodeId"].get<std::string>());
      ++orders_[serial];
    } else if (level == "state") {
      auto s = decode_state(payload);
      if (!s) return;
      for (const ActionState& a : s->action_states)
        if (a.action_status == ActionStatus::kFinished && a.action_type == "noop")
          finished_[serial].insert(a.action_id);
    }
  }
  std::map<std::string, std::set<std::string>> destinations() const {
    std::lock_guard lock(mutex_);
    return destinations_;
  }
  std::map<std::string, std::set<std::string>> finished_noops() const {
    std::lock_guard lock(mutex_);
    return finished_;
  }
  std::map<std::string, int> orders() const {
    std::lock_guard lock(mutex_);
    return orders_;
  }
  std::vector<std::string> problems() const {
    std::lock_guard lock(mutex_);
    return problems_;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::set<std::string>> destinations_, finished_;
  std::map<std::string, int> orders_;
  std::vector<std::string> problems_;
};

// Reads what the service wrote to stderr so far, without waiting: its pipe must never fill.
void drain(rondo::test::Child& c) {
  for (;;) {
    pollfd p{c.err, POLLIN, 0};
    if (::poll(&p, 1, 0) <= 0) return;
    char buf[4096];
    const ssize_t n = ::read(c.err, buf, sizeof buf);
    if (n <= 0) return;
    c.seen.append(buf, static_cast<std::size_t>(n));
  }
}

Json get_json(httplib::Client& cli, const std::string& path) {
  auto r = cli.Get(path);
  if (!r || r->status != 200) return nullptr;
  const Json j = Json::parse(r->body, nullptr, /*allow_exceptions=*/false);
  return j.is_discarded() ? Json(nullptr) : j;
}

// Like wait_until, at a pace that leaves the machine to the fleet: each look asks the service.
bool poll_until(const std::function<bool()>& condition, std::chrono::milliseconds deadline) {
  const auto end = std::chrono::steady_clock::now() + deadline;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > end) return condition();
    std::this_thread::sleep_for(250ms);  // a poll interval, not a wait for time
  }
  return true;
}

bool log_says_ready(const std::filesystem::path& log) {
  std::ifstream in(log);
  for (std::string line; std::getline(in, line);)
    if (line == "ready") return true;
  return false;
}

TEST(Vda5050Fleet, TenVehiclesOnOneBrokerEachRunOnlyTheirOwnTasks) {
  if (rondo::test::kSanitized) GTEST_SKIP() << "a broker and vehicle scenario: the normal build runs it";
  const std::string node = find_program({"/usr/bin/node", "/usr/local/bin/node"});
  if (node.empty()) GTEST_SKIP() << "node is not installed (scripts/setup installs it)";
  if (!std::filesystem::exists("tests/vda5050/peer/node_modules/vda-5050-lib"))
    GTEST_SKIP() << "the peer is not installed: run scripts/setup (npm ci in tests/vda5050/peer)";
  std::string why;
  auto broker = Broker::start(why);
  if (!broker) GTEST_SKIP() << why;
  rondo::test::remove_at_exit(broker->dir());  // kept when the test fails
  const std::filesystem::path dir = broker->dir();
  auto map = map::load_map("examples/g4s/map.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;

  FleetSpy spy;
  auto spy_client =
      MqttClient::create({.broker = broker->url(), .client_id = "rondo-test-fleet-spy", .will = std::nullopt},
                         {.message = [&spy](const std::string& t, const std::string& p) { spy.on_message(t, p); },
                          .connected = nullptr,
                          .connection_lost = nullptr},
                         [](std::function<void()> f) { f(); });
  ASSERT_TRUE(spy_client.ok()) << spy_client.error().message;
  (*spy_client)->subscribe("uagv/v2/acme/+/order", 1);
  (*spy_client)->subscribe("uagv/v2/acme/+/state", 1);
  (*spy_client)->start();
  ASSERT_TRUE(wait_until([&] { return (*spy_client)->connected(); }, 60s));

  // The vehicles, each at its stand, and each ready before rondo starts.
  std::vector<std::unique_ptr<ChildProcess>> vehicles;
  for (int i = 0; i < kVehicles; ++i) {
    const map::Node& at = map->node(*map->find_node(kStands[static_cast<std::size_t>(i)]));
    std::vector<std::string> argv = {node, "tests/vda5050/peer/virtual_agv.js", "--broker", broker->url()};
    for (const std::string& a : {std::string("--interface"), std::string("uagv"), std::string("--manufacturer"),
                                 std::string("acme"), std::string("--serial"), vehicle_name(i), std::string("--map"),
                                 std::string("g4s_y2"), std::string("--node"), at.name})
      argv.push_back(a);
    const std::pair<const char*, double> numbers[] = {
        {"x", at.pose.x},        {"y", at.pose.y},       {"theta", std::remainder(at.pose.yaw, 2 * M_PI)},
        {"speed", 1.0},          {"time-lapse", kSpeed}, {"tick-rate", 10},
        {"state-interval", 2000}};
    for (const auto& [name, v] : numbers) argv.push_back(fmt::format("--{}={}", name, v));
    vehicles.push_back(std::make_unique<ChildProcess>(argv, dir / fmt::format("{}.log", vehicle_name(i))));
  }
  for (int i = 0; i < kVehicles; ++i)
    ASSERT_TRUE(poll_until([&] { return log_says_ready(dir / fmt::format("{}.log", vehicle_name(i))); }, kDeadline))
        << vehicle_name(i) << " did not say it was ready";

  // The deployment: the ten vehicles as the fleet's robots, each docked where it stands. They do
  // not reserve their way (docs/traffic.md): the test checks that each vehicle is sent only to its
  // own tasks' places and its dock, and a vehicle making way for another goes elsewhere.
  {
    const std::filesystem::path source = std::filesystem::absolute("examples/g4s");
    std::ofstream dep(dir / "deployment.yaml");
    dep << "rondo_deployment: 1\nname: vda-fleet\n"
        << "map: " << (source / "map.yaml").string() << "\n"
        << "time_zone: UTC\ndock: ChargingPoint\nstart: 2026-12-01\ndays: 3\n"
        << "traffic: {reservations: false}\nrobots:\n";
    for (int i = 0; i < kVehicles; ++i)
      dep << fmt::format(
          "  - {{name: {0}, kind: vda5050, broker: \"{1}\", interface_name: uagv, manufacturer: acme, "
          "serial_number: {0}, map_id: g4s_y2, offline_after: 60s, compatibility: vda5050-lib-1.4, dock: {2}}}\n",
          vehicle_name(i), broker->url(), kStands[static_cast<std::size_t>(i)]);
  }
  rondo::test::Child serve =
      rondo::test::spawn({RONDO_BINARY, "serve", (dir / "deployment.yaml").string(), "--listen", "127.0.0.1:0",
                          "--data", (dir / "data").string(), "--speed", fmt::format("{}", kSpeed)});
  const std::string port = serve.wait_for(std::regex(R"(on http://127\.0\.0\.1:(\d+)/)"), 120s);
  ASSERT_FALSE(port.empty()) << serve.seen;
  httplib::Client cli("127.0.0.1", std::stoi(port));
  cli.set_read_timeout(60s);

  // Every robot has heard its vehicle (an unheard vehicle is a fault, passed over by the allocator).
  ASSERT_TRUE(poll_until(
      [&] {
        drain(serve);
        const Json robots = get_json(cli, "/api/v1/robots");
        if (!robots.is_object() || robots["robots"].size() != static_cast<std::size_t>(kVehicles)) return false;
        for (const Json& r : robots["robots"])
          if (!r["faults"].empty()) return false;
        return true;
      },
      kDeadline))
      << get_json(cli, "/api/v1/robots").dump() << "\n"
      << serve.seen;

  // Twenty tasks in one submission, their windows open for an hour of rondo's clock.
  const Time now = std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now());
  Json tasks = Json::array();
  for (std::size_t k = 0; k < kPlaces.size(); ++k)
    tasks.push_back(
        Json{{"id", fmt::format("t{:02}", k)},
             {"activity", "visit " + kPlaces[k]},
             {"window", Json{{"release", format_time(now - minutes(1))}, {"deadline", format_time(now + hours(1))}}},
             {"duration", 60},
             {"priority", 2},
             {"start_node", kPlaces[k]},
             {"actions", Json::array({Json{{"name", "noop"}, {"args", Json{{"duration", 3}}}}})}});
  static_assert(kVehicles * kTasksPerVehicle == 20);
  auto posted = cli.Post("/api/v1/tasks", Json{{"tasks", tasks}}.dump(), "application/json");
  ASSERT_TRUE(posted) << serve.seen;
  ASSERT_EQ(posted->status, 201) << posted->body;

  const auto started = std::chrono::steady_clock::now();
  Json listed;
  const bool all_over = poll_until(
      [&] {
        drain(serve);
        listed = get_json(cli, "/api/v1/tasks?limit=1000");
        if (!listed.is_object() || listed["tasks"].size() != kPlaces.size()) return false;
        for (const Json& t : listed["tasks"])
          if (t["state"] == "queued" || t["state"] == "waiting" || t["state"] == "navigating" || t["state"] == "acting")
            return false;
        return true;
      },
      kDeadline);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  ASSERT_TRUE(all_over) << listed.dump(1);
  const Json robots = get_json(cli, "/api/v1/robots");

  ::kill(serve.pid, SIGTERM);
  const int status = serve.wait_exit(120s);
  drain(serve);
  ::close(serve.err);
  EXPECT_EQ(status, 0) << serve.seen;

  // The store: each task succeeded, on one robot, and every event of it names that robot.
  auto db = store::Store::open(dir / "data" / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(db.ok()) << db.error().message;
  std::map<std::string, std::set<std::string>> places_of;  // robot -> its tasks' places
  std::map<std::string, long> succeeded_on;                // robot -> its tasks that succeeded
  for (std::size_t k = 0; k < kPlaces.size(); ++k) {
    const std::string id = fmt::format("t{:02}", k);
    auto row = store::get_task(*db, id);
    ASSERT_TRUE(row.ok()) << row.error().message;
    EXPECT_EQ(row->state, "succeeded") << id << " on " << row->robot;
    ASSERT_FALSE(row->robot.empty()) << id;
    places_of[row->robot].insert(kPlaces[k]);
    if (row->state == "succeeded") ++succeeded_on[row->robot];
    auto events = store::read_events_of(*db, id);
    ASSERT_TRUE(events.ok()) << events.error().message;
    std::set<std::string> named;
    for (const store::Event& e : *events)
      if (e.event == "navigating" || e.event == "acting" || e.event == "succeeded" || e.event == "failed")
        named.insert(e.robot);
    EXPECT_EQ(named, std::set<std::string>{row->robot}) << id << ": its run's events name other robots";
  }

  // The vehicles: each was sent only to its own tasks' places and its dock, reached each of them,
  // and finished one action per task of its own.
  const auto destinations = spy.destinations();
  const auto finished = spy.finished_noops();
  int working = 0;
  for (int i = 0; i < kVehicles; ++i) {
    const std::string v = vehicle_name(i);
    SCOPED_TRACE(v);
    std::set<std::string> allowed = places_of[v];
    allowed.insert(kStands[static_cast<std::size_t>(i)]);
    const auto sent = destinations.count(v) ? destinations.at(v) : std::set<std::string>{};
    for (const std::string& d : sent) EXPECT_TRUE(allowed.count(d)) << "an order to " << d << ", not its task's place";
    for (const std::string& p : places_of[v]) EXPECT_TRUE(sent.count(p)) << "no order to its task's place " << p;
    const long noops = finished.count(v) ? static_cast<long>(finished.at(v).size()) : 0;
    EXPECT_EQ(noops, static_cast<long>(places_of[v].size()));
    EXPECT_EQ(noops, succeeded_on[v]);
    if (!places_of[v].empty()) ++working;
  }
  // The allocation spreads the work: no vehicle could do all twenty in their hour at once.
  EXPECT_GE(working, kVehicles / 2) << "only " << working << " vehicles got work";

  // The API's per-robot counts, read before the stop, agree with the store.
  ASSERT_TRUE(robots.is_object()) << serve.seen;
  ASSERT_EQ(robots["robots"].size(), static_cast<std::size_t>(kVehicles));
  for (const Json& r : robots["robots"]) {
    const std::string name = r["name"];
    EXPECT_EQ(r["tasks"].value("succeeded", 0L), succeeded_on[name]) << name << ": " << r.dump();
    EXPECT_EQ(r["open_tasks"], 0) << name;
  }
  for (const std::string& p : spy.problems()) ADD_FAILURE() << p;
  std::string spread;
  for (const auto& [robot, places] : places_of) spread += fmt::format(" {}:{}", robot, places.size());
  std::cout << fmt::format("[ fleet    ] 20 tasks over {} vehicles in {:.1f} s of wall time:{}\n", working, took,
                           spread);
  (*spy_client)->stop();
}

}  // namespace
}  // namespace rondo::vda5050::testing
