// A thin MQTT client over Eclipse Paho C++ (libpaho-mqttpp-dev): asynchronous, reconnecting by
// itself, re-subscribing after every reconnect, with a last will. Paho calls back on its own
// threads; this client hands every event over as a closure to `post`, which the owner makes
// thread-safe (the robot adapter passes its clock's post(); a test passes a queue).
//
//   MqttClient client(MqttOptions{.broker = "mqtt://127.0.0.1:1883", .client_id = "rondo-agv-7"},
//                     handlers, [&](std::function<void()> f) { clock.post(std::move(f)); });
//   client.subscribe("uagv/v2/acme/agv-7/state", 1);   // kept, and renewed on every connect
//   client.start();
//   client.publish({.topic = ..., .payload = order_json, .qos = 1, .retained = false});
//
// Nothing here blocks the caller: start() returns at once and the first connection, like every
// reconnection, happens in the background (retrying with back-off until stop()).
//
// Stopping, in any order of events (the broker gone before, during or after it; a connect or
// reconnect in progress; a message arriving meanwhile): stop() never throws; once it has
// returned, `post` is not called again, and a closure posted before and run later does nothing
// (it neither calls a handler nor touches the client, which may be gone by then).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "rondo/core/result.h"
#include "rondo/core/time.h"

namespace rondo::vda5050 {

struct MqttMessage {
  std::string topic;
  std::string payload;
  int qos = 1;
  bool retained = false;
};

struct MqttOptions {
  std::string broker;     // "mqtt://host:port" (or tcp://); only plain TCP
  std::string client_id;  // unique at the broker
  std::optional<MqttMessage> will;
  Duration keep_alive = seconds(10);
  Duration min_retry = seconds(1);  // reconnect back-off, doubling up to max_retry
  Duration max_retry = seconds(8);
};

struct MqttHandlers {
  std::function<void(const std::string& topic, const std::string& payload)> message;
  std::function<void()> connected;  // after each (re)connect and re-subscribe
  std::function<void(const std::string& cause)> connection_lost;
};

// Hands a closure to the owner's thread; must be callable from any thread. It may also run the
// closure at once (a test's spy does), provided the handlers then never call stop().
using Post = std::function<void(std::function<void()>)>;

class MqttClient {
 public:
  // An error for a broker address that is not mqtt:// or tcp://host:port.
  static Result<std::unique_ptr<MqttClient>> create(MqttOptions options, MqttHandlers handlers, Post post);
  ~MqttClient();  // stops
  MqttClient(const MqttClient&) = delete;
  MqttClient& operator=(const MqttClient&) = delete;

  // Remembers the subscription; it is made now if connected and again after every connect.
  void subscribe(const std::string& topic_filter, int qos);
  // Starts connecting in the background.
  void start();
  // Publishes when connected; an error (not an exception) when not connected or refused.
  Status publish(const MqttMessage& message);
  // Disconnects cleanly (no last will) and stops reconnecting; waits at most `timeout` for the
  // broker (a first connect in progress is given up at once). Idempotent; the destructor calls it.
  void stop(Duration timeout = seconds(2)) noexcept;
  bool connected() const;

 private:
  struct Impl;
  explicit MqttClient(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// "mqtt://127.0.0.1:1883" -> "tcp://127.0.0.1:1883"; an error for any other form.
Result<std::string> paho_server_uri(const std::string& broker);

}  // namespace rondo::vda5050
