#include "live_service.h"

#include <fmt/format.h>

#include <future>

#include "source_dir.h"

namespace rondo::test {
namespace {

app::DeploymentParts example_parts(const std::string& deployment) {
  auto d = app::load_deployment(rondo::testing::source_dir() / deployment);
  if (!d) throw std::runtime_error(d.error().message);
  auto parts = app::load_parts(*d);
  if (!parts) throw std::runtime_error(parts.error().message);
  parts->people.reset();  // the tests add their own tasks
  return std::move(*parts);
}

store::Store open_store(const std::filesystem::path& data) {
  std::filesystem::create_directories(data);
  auto s = store::Store::open(data / "rondo.sqlite", {.sync_commits = false});
  if (!s) throw std::runtime_error(s.error().message);
  return std::move(*s);
}

// The machine's monotonic clock, read as wall time from `start` on.
exec::SystemClock::Sources starting_at(const std::string& start) {
  auto at = parse_time(start);
  if (!at) throw std::runtime_error(at.error().message);
  const auto steady_start = exec::SystemClock::Steady::now();
  return {.wall = [at = *at, steady_start] {
            return at + std::chrono::duration_cast<Duration>(exec::SystemClock::Steady::now() - steady_start);
          },
          .steady = [] { return exec::SystemClock::Steady::now(); }};
}

// The simulated robot, saying which actions it runs (as a VDA 5050 vehicle's factsheet does).
class RobotWithActions final : public exec::Robot {
 public:
  RobotWithActions(exec::Robot& robot, std::vector<std::string> actions)
      : robot_(robot), support_{"the test robot", std::move(actions)} {}
  void set_listener(exec::RobotListener* listener) override { robot_.set_listener(listener); }
  Status activate() override { return robot_.activate(); }
  void deactivate() override { robot_.deactivate(); }
  map::NodeIndex location() const override { return robot_.location(); }
  std::optional<map::Pose> position() const override { return robot_.position(); }
  bool busy() const override { return robot_.busy(); }
  void drive(const exec::Route& route) override { robot_.drive(route); }
  void run_action(const Action& action, Duration expected) override { robot_.run_action(action, expected); }
  void cancel() override { robot_.cancel(); }
  double battery() const override { return robot_.battery(); }
  bool charging() const override { return robot_.charging(); }
  std::optional<exec::RobotFault> fault() const override { return robot_.fault(); }
  std::optional<exec::ActionSupport> supported_actions() const override { return support_; }

 private:
  exec::Robot& robot_;
  exec::ActionSupport support_;
};

}  // namespace

LiveService::LiveService(const std::filesystem::path& data, LiveOptions o)
    : parts_(example_parts(o.deployment)), store_(open_store(data)), clock_(o.speed, starting_at(o.start)), token_(o.token) {
  sim_ = std::make_unique<sim::SimRobot>(clock_, parts_.map, *parts_.world,
                                         sim::SimRobotOptions{.start = parts_.dock, .dock = parts_.dock, .seed = 3});
  robot_ = sim_.get();
  if (o.robot_actions) {
    with_actions_ = std::make_unique<RobotWithActions>(*sim_, *o.robot_actions);
    robot_ = with_actions_.get();
  }
  exec::ExecutorOptions eo;
  eo.dock = parts_.dock;
  eo.forget_finished = true;  // as rondo serve: finished tasks are read from the store
  fleet_ = std::make_unique<fleet::Fleet>(clock_, parts_.map, store_, TimeZone::utc(), eo);
  executor_ = &fleet_->add_robot(*robot_, eo);
  for (std::size_t i = 0; i < o.more_robots.size(); ++i) {
    more_.push_back(std::make_unique<sim::SimRobot>(
        clock_, parts_.map, *parts_.world,
        sim::SimRobotOptions{.start = parts_.dock, .dock = parts_.dock, .seed = 4 + i, .name = o.more_robots[i]}));
    exec::ExecutorOptions own = eo;
    own.robot_name = o.more_robots[i];
    fleet_->add_robot(*more_.back(), own);
  }
  fleet_->start();
  server_ =
      std::make_unique<service::Server>(service::ServiceContext{.clock = clock_,
                                                                .fleet = *fleet_,
                                                                .executor = *executor_,
                                                                .robot = *robot_,
                                                                .store = store_,
                                                                .map = parts_.map,
                                                                .zone = TimeZone::utc(),
                                                                .deployment = "g4s",
                                                                .places = parts_.places ? &*parts_.places : nullptr},
                                        service::ServerOptions{.host = "127.0.0.1",
                                                               .port = 0,
                                                               .token = o.token,
                                                               .body_limit = o.body_limit,
                                                               .read_timeout = o.read_timeout,
                                                               .answer_timeout = o.answer_timeout,
                                                               .stream_poll = std::chrono::milliseconds(20),
                                                               .stream_keepalive = seconds(1),
                                                               .threads = o.threads});
  auto port = server_->bind();
  if (!port) throw std::runtime_error(port.error().message);
  port_ = *port;
  clock_thread_ = std::thread([this] { clock_.run_until(clock_.now() + hours(24 * 365)); });
  http_thread_ = std::thread([this] { server_->run(); });
}

LiveService::~LiveService() {
  server_->stop();
  http_thread_.join();
  clock_.post([this] { clock_.stop(); });
  clock_thread_.join();
}

httplib::Client LiveService::client() const {
  httplib::Client c("127.0.0.1", port_);
  c.set_read_timeout(std::chrono::seconds(60));
  c.set_connection_timeout(std::chrono::seconds(10));
  return c;
}

httplib::Headers LiveService::auth() const {
  if (!token_) return {};
  return {{"Authorization", "Bearer " + *token_}};
}

void LiveService::on_clock(const std::function<void()>& f) {
  std::promise<void> done;
  clock_.post([&] {
    f();
    done.set_value();
  });
  done.get_future().wait();
}

std::string LiveService::task_body(const std::string& id, Duration from_now, Duration width, Duration duration) const {
  const Time release = clock_.now() + from_now;
  return fmt::format(R"({{"tasks": [{{"id": "{}", "activity": "look at the door", "window": {{"release": "{}",
      "deadline": "{}"}}, "duration": {}, "start_node": "WayPoint2"}}]}})",
                     id, format_time(release), format_time(release + width), to_seconds(duration));
}

Json body_of(const httplib::Result& r) {
  if (!r) {
    ADD_FAILURE() << "no response: " << httplib::to_string(r.error());
    return nullptr;
  }
  Json j = Json::parse(r->body, nullptr, false);
  if (j.is_discarded()) {
    ADD_FAILURE() << "not JSON: " << r->body;
    return nullptr;
  }
  return j;
}

bool eventually(const std::function<bool()>& done, Duration deadline) {
  const auto end = std::chrono::steady_clock::now() + deadline;
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));  // polling: the deadline is the bound
  }
  return done();
}

}  // namespace rondo::test
