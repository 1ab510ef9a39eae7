// Vda5050Robot: the lifecycle, the messages in and out, and the faults. What the robot's commands
// become (orders, updates, actions, cancel) and how progress events end them is in
// robot_commands.cpp.
#include "robot_impl.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "rondo/vda5050/decode.h"
#include "rondo/vda5050/encode.h"

namespace rondo::vda5050 {

Result<std::unique_ptr<Vda5050Robot>> Vda5050Robot::create(exec::Clock& clock, const map::TopoMap& map,
                                                           Vda5050Config config, Vda5050RobotOptions options) {
  if (options.start >= map.node_count()) return Error::invalid("the robot's start node is not on the map");
  RONDO_RETURN_IF_ERROR(validate(config.topics));
  RONDO_ASSIGN_OR_RETURN(const std::string uri, paho_server_uri(config.broker));
  (void)uri;
  RONDO_RETURN_IF_ERROR(check_information_places(config.information, map));
  auto impl = std::make_unique<Impl>(clock, map, std::move(config), std::move(options));
  return std::unique_ptr<Vda5050Robot>(new Vda5050Robot(std::move(impl)));
}

Vda5050Robot::Vda5050Robot(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Vda5050Robot::~Vda5050Robot() { impl_->stop(); }

void Vda5050Robot::set_listener(exec::RobotListener* listener) { impl_->listener = listener; }
Status Vda5050Robot::activate() { return impl_->activate(); }
void Vda5050Robot::deactivate() { impl_->stop(); }
map::NodeIndex Vda5050Robot::location() const { return impl_->location; }
std::optional<map::Pose> Vda5050Robot::position() const { return impl_->position(); }
bool Vda5050Robot::busy() const {
  return !std::holds_alternative<std::monostate>(impl_->job) || impl_->ending > 0;
}
void Vda5050Robot::drive(const exec::Route& route) { impl_->drive(route); }
void Vda5050Robot::run_action(const rondo::Action& action, Duration expected) { impl_->run_action(action, expected); }
void Vda5050Robot::cancel() { impl_->cancel(); }
double Vda5050Robot::battery() const { return impl_->battery; }
bool Vda5050Robot::charging() const { return impl_->charging; }
std::optional<exec::RobotFault> Vda5050Robot::fault() const { return impl_->reported_fault; }
std::optional<exec::ActionSupport> Vda5050Robot::supported_actions() const {
  if (!impl_->factsheet || impl_->factsheet->agv_actions.empty()) return std::nullopt;
  return exec::ActionSupport{.robot = fmt::format("vehicle {}/{} (its factsheet)", impl_->config.topics.manufacturer,
                                                  impl_->config.topics.serial_number),
                             .actions = impl_->factsheet->agv_actions};
}
double Vda5050Robot::distance_m() const { return impl_->distance_m; }
const std::vector<std::string>& Vda5050Robot::ignored() const { return impl_->ignored; }

Vda5050Robot::Impl::Impl(exec::Clock& c, const map::TopoMap& m, Vda5050Config cfg, Vda5050RobotOptions opts)
    : clock(c),
      map(m),
      config(std::move(cfg)),
      options(std::move(opts)),
      headers(config.topics.manufacturer, config.topics.serial_number),
      inbox(config.topics.manufacturer, config.topics.serial_number),
      watch(config.offline_after, config.compat),
      information(config.information, m),
      location(options.start),
      order_prefix(fmt::format("rondo-{}", std::chrono::duration_cast<std::chrono::milliseconds>(
                                               std::chrono::system_clock::now().time_since_epoch())
                                               .count())) {
  if (options.client_id.empty()) {
    options.client_id = fmt::format("rondo-{}-{}-{}", config.topics.interface_name, config.topics.manufacturer,
                                    config.topics.serial_number);
  }
}

Status Vda5050Robot::Impl::activate() {
  if (client) return Status{};
  // Events come from Paho's threads; each is handed to the clock's thread, and dropped there if
  // the robot is gone by then.
  std::weak_ptr<int> alive = life;
  exec::Clock* c = &clock;
  Post post = [c, alive](std::function<void()> f) {
    c->post([alive, f = std::move(f)] {
      if (!alive.expired()) f();
    });
  };
  MqttHandlers handlers{
      .message = [this](const std::string& topic, const std::string& payload) { on_message(topic, payload); },
      .connected = [this] { on_connected(); },
      .connection_lost = [this](const std::string& cause) { on_connection_lost(cause); }};
  RONDO_ASSIGN_OR_RETURN(client, MqttClient::create({.broker = config.broker, .client_id = options.client_id, .will = std::nullopt},
                                                    std::move(handlers), std::move(post)));
  for (Topic t : {Topic::kState, Topic::kConnection, Topic::kFactsheet}) client->subscribe(config.topics.of(t), 1);
  client->start();
  // Not there until the vehicle is heard from: a fault, reported from the clock (never from
  // inside the call).
  update_faults();
  schedule_check();
  return Status{};
}

void Vda5050Robot::Impl::stop() {
  if (check_timer != 0) clock.cancel(check_timer);
  if (retry_timer != 0) clock.cancel(retry_timer);
  check_timer = retry_timer = 0;
  if (client) client->stop();
  client.reset();
}

void Vda5050Robot::Impl::schedule_check() {
  check_timer = clock.schedule_after(options.check_every, [this] {
    check_timer = 0;
    update_faults();
    schedule_check();
  });
}

Time Vda5050Robot::Impl::wall_now() {
  return std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now());
}

Status Vda5050Robot::Impl::publish(Topic topic, const Json& message) {
  if (!client) return Error::invalid("the robot is not activated");
  RONDO_RETURN_IF_ERROR(
      client->publish({.topic = config.topics.of(topic), .payload = message.dump(), .qos = 1, .retained = false}));
  if (options.on_published) options.on_published(topic, message);
  return Status{};
}

void Vda5050Robot::Impl::deliver(std::function<void(exec::RobotListener&)> call, bool ends_job) {
  std::weak_ptr<int> alive = life;
  if (ends_job) ++ending;  // busy() until this callback is delivered
  clock.post([this, alive, ends_job, call = std::move(call)] {
    if (alive.expired()) return;
    if (ends_job) --ending;
    if (listener != nullptr) call(*listener);
  });
}

void Vda5050Robot::Impl::ignore(const std::string& why) {
  ignored.push_back(why);
  deliver([o = exec::Observation{.what = "vda5050_ignored",
                                 .where = config.topics.serial_number,
                                 .when = clock.now(),
                                 .value = 1,
                                 .text = why}](exec::RobotListener& l) { l.on_observation(o); });
}

void Vda5050Robot::Impl::on_connected() {
  // After every (re)connect: Paho has renewed the subscriptions; ask where the vehicle is now, and
  // what it is (its factsheet: the actions it runs). Two messages, so that a vehicle that does not
  // know factsheetRequest still answers the stateRequest.
  const Header h = headers.next(Topic::kInstantActions, wall_now());
  Json j = encode_instant_actions(h, InstantActions{.actions = {state_request_action(
                                                        fmt::format("{}-state-{}", order_prefix, ++instant_count))}},
                                  config.compat);
  (void)publish(Topic::kInstantActions, j);
  const Header f = headers.next(Topic::kInstantActions, wall_now());
  (void)publish(Topic::kInstantActions,
                encode_instant_actions(f,
                                       InstantActions{.actions = {factsheet_request_action(
                                                          fmt::format("{}-factsheet-{}", order_prefix, ++instant_count))}},
                                       config.compat));
}

void Vda5050Robot::Impl::on_connection_lost(const std::string& cause) {
  watch.on_broker_lost(clock.now());
  broker_cause = cause;
  update_faults();
}

void Vda5050Robot::Impl::on_message(const std::string& topic, const std::string& payload) {
  const std::optional<Topic> which = config.topics.parse(topic);
  if (!which) return ignore(fmt::format("{}: not a topic of this vehicle", topic));
  if (*which == Topic::kConnection) {
    auto c = decode_connection(payload);
    if (!c) return ignore(fmt::format("{}: {}", topic, c.error().message));
    if (auto ok = inbox.admit(*c); !ok) return ignore(fmt::format("{}: {}", topic, ok.error().message));
    watch.on_connection(c->connection_state, clock.now());
    update_faults();
    return;
  }
  if (*which == Topic::kState) {
    auto s = decode_state(payload);
    if (!s) return ignore(fmt::format("{}: {}", topic, s.error().message));
    if (auto ok = inbox.admit(Topic::kState, s->header); !ok) {
      return ignore(fmt::format("{}: {}", topic, ok.error().message));
    }
    on_state(std::move(*s));
    return;
  }
  if (*which == Topic::kFactsheet) {
    auto f = decode_factsheet(payload, config.compat);
    if (!f) return ignore(fmt::format("{}: {}", topic, f.error().message));
    if (inbox.admit(Topic::kFactsheet, f->header)) factsheet = std::move(*f);
  }
}

void Vda5050Robot::Impl::on_state(State s) {
  const Time now = clock.now();
  watch.on_state(now);
  if (!s.last_node_id.empty()) {
    if (auto n = map.find_node(s.last_node_id)) {
      location = *n;
    } else if (unknown_nodes.insert(s.last_node_id).second) {
      ignore(fmt::format("state: lastNodeId '{}' is not on map '{}'; the robot stays at {}", s.last_node_id,
                         map.name(), map.node(location).name));
    }
  }
  if (s.agv_position && s.agv_position->position_initialized) agv_position = s.agv_position;
  last_state = s;
  std::vector<ProgressEvent> events = progress.observe(s, now);
  // Faults first: an edge the fault interrupts ends as a robot fault, after on_fault().
  for (const ProgressEvent& e : events) {
    if (const auto* f = std::get_if<FaultRaised>(&e)) vehicle_fault = f->reason;
    if (std::holds_alternative<FaultCleared>(e)) vehicle_fault.reset();
  }
  update_faults();
  for (const ProgressEvent& e : events) handle(e);
  // What the vehicle tells of the building (the deployment's information rules).
  InformationReader::Reading seen = information.read(s.information, now);
  for (std::string& why : seen.ignored) ignore(why);
  for (exec::Observation& o : seen.seen)
    deliver([o = std::move(o)](exec::RobotListener& l) { l.on_observation(o); });
}

std::optional<map::Pose> Vda5050Robot::Impl::position() const {
  if (agv_position) return map::Pose{.x = agv_position->x, .y = agv_position->y, .yaw = agv_position->theta};
  return map.node(location).pose;
}

// The fault is the first of: rondo's broker connection or the vehicle offline, the vehicle's own
// fault (FATAL, operating mode), a rejected drive. on_fault() when one begins (or its message
// changes), on_ready() when none is left; whatever runs ends as a robot fault.
void Vda5050Robot::Impl::update_faults() {
  const Time now = clock.now();
  std::optional<exec::RobotFault> f;
  const bool heard = last_state.has_value();
  std::string offline = watch.why_offline(now);
  if (offline.empty() && !heard) offline = "no state from the vehicle yet";
  if (!offline.empty()) {
    if (!broker_cause.empty() && offline.starts_with("rondo lost the broker")) offline += ": " + broker_cause;
    f = exec::RobotFault{.kind = exec::RobotFault::Kind::kConnectionLost,
                         .message = fmt::format("vehicle {}: {}", config.topics.serial_number, offline)};
  } else if (vehicle_fault) {
    f = exec::RobotFault{.kind = exec::RobotFault::Kind::kError, .message = *vehicle_fault};
  } else if (rejected_fault) {
    f = exec::RobotFault{.kind = exec::RobotFault::Kind::kError, .message = *rejected_fault};
  }
  if (offline.empty()) broker_cause.clear();
  if (f) {
    const bool changed = !reported_fault || reported_fault->message != f->message;
    if (!changed) return;
    const bool first = !reported_fault;
    reported_fault = f;
    deliver([f = *f](exec::RobotListener& l) { l.on_fault(f); });
    if (first) end_job(f->message);
  } else if (reported_fault) {
    reported_fault.reset();
    deliver([](exec::RobotListener& l) { l.on_ready(); });
  }
}

}  // namespace rondo::vda5050
