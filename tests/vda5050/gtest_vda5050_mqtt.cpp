// The MQTT client against a real mosquitto: publish and subscribe, events handed over through
// post(), re-subscription after the broker restarts, and stop() whatever the connection is doing.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "rondo/vda5050/mqtt_client.h"
#include "test_files.h"
#include "vda5050/event_queue.h"
#include "vda5050/processes.h"

namespace rondo::vda5050 {
namespace {

using namespace std::chrono_literals;
using testing::Broker;
using testing::EventQueue;

TEST(Vda5050Mqtt, BrokerAddresses) {
  EXPECT_EQ(*paho_server_uri("mqtt://127.0.0.1:1883"), "tcp://127.0.0.1:1883");
  EXPECT_EQ(*paho_server_uri("tcp://localhost:5"), "tcp://localhost:5");
  EXPECT_FALSE(paho_server_uri("http://x:1").ok());
  EXPECT_FALSE(paho_server_uri("mqtt://x").ok());
  EXPECT_FALSE(paho_server_uri("mqtt://x:port").ok());
}

TEST(Vda5050Mqtt, PublishSubscribeAndResubscribeAfterABrokerRestart) {
  std::string why;
  auto broker = Broker::start(why);
  if (!broker) GTEST_SKIP() << why;
  rondo::test::remove_at_exit(broker->dir());

  EventQueue events;
  std::vector<std::string> received;
  int connects = 0;
  int losses = 0;
  MqttHandlers handlers{.message = [&](const std::string& topic,
                                       const std::string& payload) { received.push_back(topic + " " + payload); },
                        .connected = [&] { ++connects; },
                        .connection_lost = [&](const std::string&) { ++losses; }};
  auto sub = MqttClient::create({.broker = broker->url(),
                                 .client_id = "rondo-test-sub",
                                 .will = std::nullopt,
                                 .keep_alive = seconds(5),
                                 .min_retry = seconds(1),
                                 .max_retry = seconds(2)},
                                handlers, events.poster());
  ASSERT_TRUE(sub.ok()) << sub.error().message;
  (*sub)->subscribe("t/v2/m/s/state", 1);
  (*sub)->start();

  int pub_connects = 0;
  MqttHandlers pub_handlers{.message = nullptr, .connected = [&] { ++pub_connects; }, .connection_lost = nullptr};
  auto pub = MqttClient::create({.broker = broker->url(),
                                 .client_id = "rondo-test-pub",
                                 .will = std::nullopt,
                                 .keep_alive = seconds(5),
                                 .min_retry = seconds(1),
                                 .max_retry = seconds(2)},
                                pub_handlers, events.poster());
  ASSERT_TRUE(pub.ok());
  EXPECT_FALSE((*pub)->publish({.topic = "t/v2/m/s/state", .payload = "early", .qos = 1, .retained = false}).ok());
  (*pub)->start();
  ASSERT_TRUE(events.run_until([&] { return connects == 1 && pub_connects == 1; }, 30s));

  ASSERT_TRUE((*pub)->publish({.topic = "t/v2/m/s/state", .payload = "one", .qos = 1, .retained = false}).ok());
  ASSERT_TRUE(events.run_until([&] { return received.size() == 1; }, 30s));
  EXPECT_EQ(received[0], "t/v2/m/s/state one");

  // The broker goes away and comes back on the same port: both clients reconnect by themselves,
  // and the subscriber's subscription is renewed (its session was clean).
  ASSERT_TRUE(broker->restart());
  ASSERT_TRUE(events.run_until([&] { return connects == 2 && pub_connects == 2; }, 60s))
      << "connects " << connects << ", losses " << losses;
  EXPECT_GE(losses, 1);
  // The renewed subscription is asynchronous: publish until one arrives.
  ASSERT_TRUE(events.run_until(
      [&] {
        if (received.size() >= 2) return true;
        (void)(*pub)->publish({.topic = "t/v2/m/s/state", .payload = "two", .qos = 1, .retained = false});
        return false;
      },
      30s));
  EXPECT_EQ(received[1], "t/v2/m/s/state two");
  (*sub)->stop();
  (*pub)->stop();
}

// A TCP listener on 127.0.0.1:port that takes connections and never answers: to Paho, a broker
// that accepted the connection and has not sent its CONNACK yet.
class SilentListener {
 public:
  explicit SilentListener(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    const int on = 1;
    ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = htons(static_cast<std::uint16_t>(port));
    ok_ = ::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0 && ::listen(fd_, 8) == 0;
  }
  ~SilentListener() { ::close(fd_); }
  bool ok() const { return ok_; }
  // A connection waits in the backlog.
  bool connection_waiting() const {
    pollfd p{fd_, POLLIN, 0};
    return ::poll(&p, 1, 0) > 0;
  }

 private:
  int fd_ = -1;
  bool ok_ = false;
};

// The broker goes while the client is connected, and its automatic reconnect finds a listener that
// never answers (as a broker that is shutting down, or not started yet): the reconnect waits for a
// CONNACK. stop() then must not throw. It did (issue 37): Paho C++'s disable_callbacks() fails
// while a connect is in progress, and the exception left the robot's deactivate() and ended
// `rondo serve` with "internal error: terminated without an exception".
TEST(Vda5050Mqtt, StopWhileAReconnectWaitsForItsAnswerDoesNotThrow) {
  std::string why;
  auto broker = Broker::start(why);
  if (!broker) GTEST_SKIP() << why;
  rondo::test::remove_at_exit(broker->dir());
  EventQueue events;
  int connects = 0;
  int losses = 0;
  auto client = MqttClient::create(
      {.broker = broker->url(),
       .client_id = "rondo-test-stop",
       .will = std::nullopt,
       .keep_alive = seconds(5),
       .min_retry = seconds(1),
       .max_retry = seconds(1)},
      {.message = nullptr, .connected = [&] { ++connects; }, .connection_lost = [&](const std::string&) { ++losses; }},
      events.poster());
  ASSERT_TRUE(client.ok()) << client.error().message;
  (*client)->start();
  ASSERT_TRUE(events.run_until([&] { return connects == 1; }, 30s));

  broker->stop();
  SilentListener silent(broker->port());
  ASSERT_TRUE(silent.ok());
  ASSERT_TRUE(testing::wait_until([&] { return silent.connection_waiting(); }, 30s));
  EXPECT_NO_THROW((*client)->stop());
  // The loss was posted before the stop and is run after it: it calls no handler.
  EXPECT_GE(events.pending(), 1u);
  events.run_until([] { return false; }, 0ms);
  EXPECT_EQ(losses, 0);
  EXPECT_EQ(connects, 1);
}

// A message handed over just before stop() and run after it reaches no handler (the robot's
// deactivate() destroys the client; the closure once called into it when run later).
TEST(Vda5050Mqtt, AMessagePostedBeforeStopAndRunAfterItCallsNoHandler) {
  std::string why;
  auto broker = Broker::start(why);
  if (!broker) GTEST_SKIP() << why;
  rondo::test::remove_at_exit(broker->dir());
  EventQueue events;
  int connects = 0;
  std::vector<std::string> received;
  auto sub = MqttClient::create({.broker = broker->url(), .client_id = "rondo-test-stop-sub", .will = std::nullopt},
                                {.message = [&](const std::string&, const std::string& p) { received.push_back(p); },
                                 .connected = [&] { ++connects; },
                                 .connection_lost = nullptr},
                                events.poster());
  ASSERT_TRUE(sub.ok());
  (*sub)->subscribe("t/v2/m/s/state", 1);
  (*sub)->start();
  auto pub = MqttClient::create({.broker = broker->url(), .client_id = "rondo-test-stop-pub", .will = std::nullopt},
                                {.message = nullptr, .connected = [&] { ++connects; }, .connection_lost = nullptr},
                                events.poster());
  ASSERT_TRUE(pub.ok());
  (*pub)->start();
  ASSERT_TRUE(events.run_until([&] { return connects == 2; }, 30s));
  // The subscription is asynchronous: publish until one arrives, then one more that stays queued.
  ASSERT_TRUE(events.run_until(
      [&] {
        if (!received.empty()) return true;
        (void)(*pub)->publish({.topic = "t/v2/m/s/state", .payload = "one", .qos = 1, .retained = false});
        return false;
      },
      30s));
  const std::size_t before = received.size();
  ASSERT_TRUE((*pub)->publish({.topic = "t/v2/m/s/state", .payload = "late", .qos = 1, .retained = false}).ok());
  ASSERT_TRUE(testing::wait_until([&] { return events.pending() >= 1; }, 30s));
  (*sub)->stop();
  sub->reset();  // as the robot's deactivate() does
  events.run_until([] { return false; }, 0ms);
  EXPECT_EQ(received.size(), before);
  (*pub)->stop();
}

}  // namespace
}  // namespace rondo::vda5050
