#include "rondo/vda5050/mqtt_client.h"

#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <map>
#include <mutex>
#include <thread>

#include <mqtt/async_client.h>

#include "tcp_nodelay.h"

namespace rondo::vda5050 {

Result<std::string> paho_server_uri(const std::string& broker) {
  std::string rest;
  for (const char* scheme : {"mqtt://", "tcp://"}) {
    if (broker.rfind(scheme, 0) == 0) rest = broker.substr(std::string(scheme).size());
  }
  const auto colon = rest.rfind(':');
  if (rest.empty() || colon == std::string::npos || colon == 0 || colon + 1 == rest.size() ||
      rest.find_first_not_of("0123456789", colon + 1) != std::string::npos) {
    return Error::invalid("broker: '" + broker + "' is not mqtt://host:port");
  }
  return "tcp://" + rest;
}

// What Paho's callbacks and the closures they post reach: shared with them, so it outlives the
// client for as long as one of them holds it. stop() closes it; from then on a callback of Paho's
// does nothing (it touches neither the client nor the owner), and a closure posted before and run
// later does not call the handler. A callback holds the mutex while it runs, so once close() has
// returned none is running on the client. (`post` may run a closure at once, on Paho's thread:
// the closures read `open` without the mutex.)
struct Gate {
  Gate(MqttHandlers h, Post p) : handlers(std::move(h)), post(std::move(p)) {}
  std::mutex mutex;
  std::atomic<bool> open{true};  // written under mutex
  const MqttHandlers handlers;
  const Post post;

  void close() {
    std::lock_guard lock(mutex);
    open = false;
  }
};

struct MqttClient::Impl {
  Impl(const std::string& uri, MqttOptions o, MqttHandlers h, Post p)
      : options(std::move(o)),
        gate(std::make_shared<Gate>(std::move(h), std::move(p))),
        client(uri, options.client_id, nullptr) {}

  MqttOptions options;
  std::shared_ptr<Gate> gate;
  mqtt::async_client client;
  mqtt::connect_options connect_options;
  std::string host;  // of the broker, for set_tcp_nodelay_to
  int port = 0;

  mutable std::mutex mutex;
  std::condition_variable wake;
  std::map<std::string, int> subscriptions;  // filter -> qos
  bool stopping = false;
  std::thread connector;

  void subscribe_all() {
    std::map<std::string, int> subs;
    {
      std::lock_guard lock(mutex);
      subs = subscriptions;
    }
    for (const auto& [filter, qos] : subs) {
      try {
        client.subscribe(filter, qos);  // asynchronous; never waited on in a Paho callback
      } catch (const mqtt::exception&) {
        // The connection dropped again; the next connect subscribes anew.
      }
    }
  }

  bool stop_asked() {
    std::lock_guard lock(mutex);
    return stopping;
  }

  // The first connection: Paho's automatic reconnect only covers a connection once made. An
  // attempt in progress is looked at every 100 ms, so that stop() does not wait for it to end.
  void connect_until_connected() {
    auto backoff = options.min_retry;
    while (!stop_asked()) {
      try {
        const mqtt::token_ptr attempt = client.connect(connect_options);
        // Paho ends an attempt after its connect timeout (5 s); 10 s bounds the wait anyway.
        for (int i = 0; i < 100; ++i) {
          if (attempt->wait_for(std::chrono::milliseconds(100))) return;
          if (stop_asked()) return;
        }
      } catch (const mqtt::exception&) {
        // refused or unreachable: wait and try again
      }
      std::unique_lock lock(mutex);
      if (wake.wait_for(lock, backoff, [&] { return stopping; })) return;
      backoff = std::min(backoff * 2, options.max_retry);
    }
  }
};

Result<std::unique_ptr<MqttClient>> MqttClient::create(MqttOptions options, MqttHandlers handlers, Post post) {
  RONDO_ASSIGN_OR_RETURN(std::string uri, paho_server_uri(options.broker));
  if (options.client_id.empty()) return Error::invalid("client_id: must not be empty");
  if (!post) return Error::invalid("post: a function to hand events over is required");
  std::unique_ptr<Impl> impl;
  try {
    impl = std::make_unique<Impl>(uri, std::move(options), std::move(handlers), std::move(post));
  } catch (const mqtt::exception& e) {
    return Error::invalid(std::string("broker: ") + e.what());
  }
  // "tcp://host:port", checked above.
  const auto colon = uri.rfind(':');
  impl->host = uri.substr(6, colon - 6);
  impl->port = std::atoi(uri.c_str() + colon + 1);
  auto builder = mqtt::connect_options_builder()
                     .clean_session(true)
                     .keep_alive_interval(std::chrono::duration_cast<std::chrono::seconds>(impl->options.keep_alive))
                     .connect_timeout(std::chrono::seconds(5))
                     .automatic_reconnect(std::chrono::duration_cast<std::chrono::seconds>(impl->options.min_retry),
                                          std::chrono::duration_cast<std::chrono::seconds>(impl->options.max_retry));
  if (impl->options.will) {
    const MqttMessage& w = *impl->options.will;
    builder.will(mqtt::message(w.topic, w.payload, w.qos, w.retained));
  }
  impl->connect_options = builder.finalize();

  // Paho's callbacks hold the gate, not the client: one that comes after stop() finds it closed
  // and returns (Paho may call back while the client is being destroyed). They touch the client
  // (`self`) only while it is open, and stop() closes it before the client goes.
  Impl* self = impl.get();
  const std::shared_ptr<Gate> gate = impl->gate;
  // Every connect, the first and each automatic reconnect: the session is clean, so subscribe
  // again before telling the owner.
  self->client.set_connected_handler([self, gate](const std::string&) {
    std::lock_guard lock(gate->mutex);
    if (!gate->open) return;
    (void)set_tcp_nodelay_to(self->host, self->port);
    self->subscribe_all();
    if (gate->handlers.connected)
      gate->post([gate] {
        if (gate->open) gate->handlers.connected();
      });
  });
  self->client.set_connection_lost_handler([gate](const std::string& cause) {
    std::lock_guard lock(gate->mutex);
    if (!gate->open || !gate->handlers.connection_lost) return;
    gate->post([gate, cause] {
      if (gate->open) gate->handlers.connection_lost(cause);
    });
  });
  self->client.set_message_callback([gate](const mqtt::const_message_ptr& m) {
    std::lock_guard lock(gate->mutex);
    if (!m || !gate->open || !gate->handlers.message) return;
    gate->post([gate, topic = m->get_topic(), payload = m->to_string()] {
      if (gate->open) gate->handlers.message(topic, payload);
    });
  });
  return std::unique_ptr<MqttClient>(new MqttClient(std::move(impl)));
}

MqttClient::MqttClient(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

MqttClient::~MqttClient() {
  stop();
}

void MqttClient::subscribe(const std::string& topic_filter, int qos) {
  {
    std::lock_guard lock(impl_->mutex);
    impl_->subscriptions[topic_filter] = qos;
  }
  if (impl_->client.is_connected()) {
    try {
      impl_->client.subscribe(topic_filter, qos);
    } catch (const mqtt::exception&) {
      // made again on the next connect
    }
  }
}

void MqttClient::start() {
  std::lock_guard lock(impl_->mutex);
  if (impl_->connector.joinable() || impl_->stopping) return;
  impl_->connector = std::thread([self = impl_.get()] { self->connect_until_connected(); });
}

Status MqttClient::publish(const MqttMessage& message) {
  if (!impl_->client.is_connected()) {
    return Error::io("mqtt: not connected to " + impl_->options.broker + "; " + message.topic + " not sent");
  }
  try {
    impl_->client.publish(mqtt::make_message(message.topic, message.payload, message.qos, message.retained));
  } catch (const mqtt::exception& e) {
    return Error::io("mqtt: publishing on " + message.topic + " failed: " + e.what());
  }
  return {};
}

void MqttClient::stop(Duration timeout) noexcept {
  {
    std::lock_guard lock(impl_->mutex);
    if (impl_->stopping) return;
    impl_->stopping = true;
  }
  // First: nothing more reaches the owner, whatever Paho does from now on.
  impl_->gate->close();
  impl_->wake.notify_all();
  if (impl_->connector.joinable()) impl_->connector.join();
  // Paho's disconnect also ends its automatic reconnect, connected or not (then it throws, saying
  // so). Nothing here may throw: stop() runs in destructors and on the way out of the service.
  // (Paho C++'s disable_callbacks() is not used: it throws while a reconnect is in progress.)
  try {
    const mqtt::token_ptr done = impl_->client.disconnect(static_cast<int>(timeout.count()));
    (void)done->wait_for(timeout);
  } catch (...) {
    // not connected, or already gone
  }
}

bool MqttClient::connected() const {
  return impl_->client.is_connected();
}

}  // namespace rondo::vda5050
