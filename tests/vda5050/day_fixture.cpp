#include "vda5050/day_fixture.h"

#include <SQLiteCpp/SQLiteCpp.h>
#include <fmt/format.h>

#include <signal.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "deployment.h"
#include "rondo/map/map_loader.h"
#include "rondo/vda5050/decode.h"
#include "run_session.h"
#include "test_files.h"

namespace rondo::vda5050::testing {
namespace {

constexpr const char* kTopicRoot = "uagv/v2/acme/agv-7/";

// The keys only the compatibility option writes: without them the message must be the
// standard shape.
Json without_compat_keys(Json j) {
  j.erase("instantActions");
  if (j.contains("nodes")) {
    for (Json& n : j["nodes"]) {
      if (n.contains("nodePosition")) n["nodePosition"].erase("allowedDeviationXy");
    }
  }
  return j;
}

// Like wait_until, at a slower pace: each look opens the run's store.
bool poll_until(const std::function<bool()>& condition, std::chrono::milliseconds deadline) {
  const auto end = std::chrono::steady_clock::now() + deadline;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > end) return condition();
    std::this_thread::sleep_for(50ms);  // a poll interval, not a wait for time
  }
  return true;
}

std::string utc(std::chrono::system_clock::time_point t) {
  return format_time(std::chrono::time_point_cast<Duration>(t));
}

}  // namespace

void Spy::on_message(const std::string& topic, const std::string& payload) {
  std::lock_guard lock(mutex_);
  const std::string level = topic.substr(topic.rfind('/') + 1);
  if (level == "order" || level == "instantActions") {
    Json j;
    try {
      j = Json::parse(payload);
    } catch (const std::exception& e) {
      problems_.push_back(level + ": not JSON: " + e.what());
      return;
    }
    const bool order = level == "order";
    (order ? orders_ : instants_)++;
    const std::string raw = (order ? order_raw_ : instant_raw_).problems(j);
    const std::string standard = (order ? order_standard_ : instant_standard_).problems(without_compat_keys(j));
    if (!raw.empty()) problems_.push_back(level + " (as sent): " + raw + "\n" + payload);
    if (!standard.empty()) problems_.push_back(level + " (standard shape): " + standard + "\n" + payload);
  } else if (level == "state") {
    auto s = decode_state(payload);
    if (!s) return;  // the tests' own malformed messages
    for (const ActionState& a : s->action_states) {
      if (a.action_status != ActionStatus::kFinished) continue;
      if (a.action_type == "cancelOrder") cancel_finished_ = true;
      const std::pair<std::string, std::string> key{a.action_type, a.action_id};
      if (std::find(finished_.begin(), finished_.end(), key) == finished_.end()) finished_.push_back(key);
    }
    last_state_ = std::move(*s);
  }
}

std::vector<std::string> Spy::problems() const {
  std::lock_guard lock(mutex_);
  return problems_;
}
int Spy::orders() const {
  std::lock_guard lock(mutex_);
  return orders_;
}
int Spy::instant_actions() const {
  std::lock_guard lock(mutex_);
  return instants_;
}
std::optional<State> Spy::last_state() const {
  std::lock_guard lock(mutex_);
  return last_state_;
}
int Spy::finished_actions(const std::string& action_type) const {
  std::lock_guard lock(mutex_);
  return static_cast<int>(std::count_if(finished_.begin(), finished_.end(),
                                        [&](const auto& f) { return f.first == action_type; }));
}
bool Spy::cancel_finished() const {
  std::lock_guard lock(mutex_);
  return cancel_finished_;
}

std::unique_ptr<VdaDay> VdaDay::start(std::string& why) {
  std::unique_ptr<VdaDay> day(new VdaDay());
  day->node_ = find_program({"/usr/bin/node", "/usr/local/bin/node"});
  if (day->node_.empty()) {
    why = "node is not installed (scripts/setup installs it)";
    return nullptr;
  }
  if (!std::filesystem::exists("tests/vda5050/peer/node_modules/vda-5050-lib")) {
    why = "the peer is not installed: run scripts/setup (npm ci in tests/vda5050/peer)";
    return nullptr;
  }
  day->broker_ = Broker::start(why);
  if (!day->broker_) return nullptr;
  rondo::test::remove_at_exit(day->broker_->dir());  // with the run's files, kept when a test fails
  auto map = map::load_map("examples/g4s/map.yaml");
  if (!map) {
    why = map.error().message;
    return nullptr;
  }
  day->map_ = std::make_unique<map::TopoMap>(std::move(*map));
  day->dir_ = day->broker_->dir();
  day->spy_ = std::make_unique<Spy>();
  Spy* spy = day->spy_.get();
  auto client = MqttClient::create(
      {.broker = day->broker_->url(), .client_id = "rondo-test-spy", .will = std::nullopt},
      {.message = [spy](const std::string& t, const std::string& p) { spy->on_message(t, p); },
       .connected = nullptr,
       .connection_lost = nullptr},
      [](std::function<void()> f) { f(); });
  if (!client) {
    why = client.error().message;
    return nullptr;
  }
  day->spy_client_ = std::move(*client);
  day->spy_client_->subscribe(std::string(kTopicRoot) + "#", 1);
  day->spy_client_->start();
  if (!wait_until([&] { return day->spy_client_->connected(); }, 30s)) {
    why = "the spy did not connect to the broker";
    return nullptr;
  }
  return day;
}

VdaDay::~VdaDay() {
  if (run_thread_.joinable()) run_thread_.join();
  if (vehicle_) vehicle_->stop();
  if (spy_client_) spy_client_->stop();
}

void VdaDay::start_vehicle(const std::string& node, double x, double y, double theta) {
  auto arg = [](const char* name, double v) { return fmt::format("--{}={}", name, v); };
  vehicle_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{node_, "tests/vda5050/peer/virtual_agv.js", "--broker", broker_->url(), "--interface",
                               "uagv", "--manufacturer", "acme", "--serial", "agv-7", "--map", "g4s_y2", "--node",
                               node, arg("x", x), arg("y", y), arg("theta", theta), arg("speed", kVehicleSpeed),
                               arg("time-lapse", speed_), "--state-interval=1000", "--information-file",
                               (dir_ / "information.json").string()},
      dir_ / "virtual_agv.log");
}

void VdaDay::kill_vehicle() {
  if (vehicle_) vehicle_->kill_hard();
}

bool VdaDay::tell_information(const Json& entries, std::chrono::milliseconds deadline) {
  const std::filesystem::path log = dir_ / "virtual_agv.log";
  const auto log_has = [&log](const std::string& line) {
    std::ifstream in(log);
    for (std::string l; std::getline(in, l);)
      if (l == line) return true;
    return false;
  };
  // Before it is ready the vehicle has no handler yet, and SIGUSR2 would end it.
  if (!vehicle_ || vehicle_->pid() <= 0 || !poll_until([&] { return log_has("ready"); }, deadline)) return false;
  const std::filesystem::path file = dir_ / "information.json";
  {
    std::ofstream out(dir_ / "information.json.new");
    out << entries.dump();
  }
  std::filesystem::rename(dir_ / "information.json.new", file);  // the vehicle never reads half of it
  ::kill(vehicle_->pid(), SIGUSR2);
  return poll_until([&] { return log_has("information: " + entries.dump()); }, deadline);
}

void VdaDay::freeze_vehicle(bool frozen) {
  if (vehicle_ && vehicle_->pid() > 0) ::kill(vehicle_->pid(), frozen ? SIGSTOP : SIGCONT);
}

void VdaDay::run(const DayOptions& o) {
  speed_ = o.speed;
  const map::Node& dock = map_->node(*map_->find_node("ChargingPoint"));
  start_vehicle(dock.name, dock.pose.x, dock.pose.y, std::remainder(dock.pose.yaw, 2 * M_PI));
  const auto now = std::chrono::system_clock::now();
  std::ofstream tasks(dir_ / "tasks.yaml");
  tasks << "timezone: UTC\ntasks:\n";
  for (const DayTask& t : o.tasks) {
    tasks << fmt::format(
        "  - {{id: {}, activity: visit {}, window: {{release: \"{}\", deadline: \"{}\"}}, duration: 1m, "
        "priority: 2, start_node: {}, actions: [{}]}}\n",
        t.id, t.node, utc(now + t.release_in), utc(now + 1h), t.node, t.action_yaml);
  }
  tasks.close();
  const std::filesystem::path source = std::filesystem::absolute("examples/g4s");
  std::ofstream dep(dir_ / "deployment.yaml");
  dep << "rondo_deployment: 1\nname: vda-day\n"
      << "map: " << (source / "map.yaml").string() << "\n"
      << "time_zone: UTC\ndock: ChargingPoint\nstart: 2026-12-01\ndays: 3\nroutines: tasks.yaml\n"
      << "executor: " << o.executor_yaml << "\n"
      << "robot: {kind: vda5050, broker: \"" << broker_->url() << "\", interface_name: uagv, manufacturer: acme, "
      << "serial_number: agv-7, map_id: g4s_y2, offline_after: " << o.offline_after
      << ", compatibility: vda5050-lib-1.4" << o.robot_yaml << "}\n";
  dep.close();
  auto deployment = app::load_deployment(dir_ / "deployment.yaml");
  if (!deployment) {
    run_error_ = deployment.error().message;
    run_done_ = true;
    return;
  }
  auto run_for = parse_duration(o.run_for);
  app::RunRequest request{.deployment = std::move(*deployment),
                          .out = dir_ / "run",
                          .realtime = true,
                          .speed = o.speed,
                          .run_for = run_for ? std::optional<Duration>(*run_for) : std::nullopt,
                          .progress = false};
  run_thread_ = std::thread([this, request = std::move(request)] {
    std::ostringstream progress;
    auto result = app::run_deployment(request, progress);
    std::lock_guard lock(run_mutex_);
    if (!result) run_error_ = result.error().message;
    run_done_ = true;
  });
}

bool VdaDay::wait_run_done(std::chrono::milliseconds deadline) {
  const bool done = poll_until(
      [&] {
        std::lock_guard lock(run_mutex_);
        return run_done_;
      },
      deadline);
  if (done && run_thread_.joinable()) run_thread_.join();
  return done;
}

std::string VdaDay::run_error() const {
  std::lock_guard lock(run_mutex_);
  return run_error_;
}

std::vector<EventRow> VdaDay::events() const {
  std::vector<EventRow> out;
  const auto db = dir_ / "run" / "rondo.sqlite";
  if (!std::filesystem::exists(db)) return out;
  try {
    SQLite::Database d(db.string(), SQLite::OPEN_READONLY);
    d.setBusyTimeout(2000);
    SQLite::Statement q(d, "SELECT time_ms, subject, coalesce(task_id, ''), event, code, reason FROM events ORDER BY seq");
    while (q.executeStep()) {
      out.push_back({q.getColumn(0).getInt64(), q.getColumn(1).getString(), q.getColumn(2).getString(),
                     q.getColumn(3).getString(), q.getColumn(4).getString(), q.getColumn(5).getString()});
    }
  } catch (const std::exception&) {
    // Not there yet (the run is creating it): nothing so far.
  }
  return out;
}

std::vector<TraversalRow> VdaDay::traversals() const {
  std::vector<TraversalRow> out;
  const auto db = dir_ / "run" / "rondo.sqlite";
  if (!std::filesystem::exists(db)) return out;
  try {
    SQLite::Database d(db.string(), SQLite::OPEN_READONLY);
    d.setBusyTimeout(2000);
    SQLite::Statement q(d, "SELECT * FROM traversals ORDER BY rowid");
    while (q.executeStep()) {
      out.push_back({q.getColumn(1).getString(), q.getColumn(4).getInt64(), q.getColumn(5).getInt64(),
                     q.getColumn(6).getInt() != 0});
    }
  } catch (const std::exception&) {
  }
  return out;
}

std::string VdaDay::event_text() const {
  std::string out;
  for (const EventRow& e : events()) {
    out += fmt::format("  {} {} {} {} {}: {}\n", e.time_ms, e.subject, e.task_id, e.event, e.code, e.reason);
  }
  return out;
}

std::vector<EventRow> VdaDay::events_named(const std::string& event) const {
  std::vector<EventRow> out;
  for (EventRow& e : events()) {
    if (e.event == event) out.push_back(std::move(e));
  }
  return out;
}

bool VdaDay::wait_for_event(const std::string& event, std::chrono::milliseconds deadline,
                            const std::string& reason_has) {
  return poll_until(
      [&] {
        for (const EventRow& e : events()) {
          if ((e.event == event || e.code == event) && e.reason.find(reason_has) != std::string::npos) return true;
        }
        return false;
      },
      deadline);
}

}  // namespace rondo::vda5050::testing
