// The MQTT client against a real mosquitto: publish and subscribe, events handed over through
// post(), and re-subscription after the broker restarts.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace rondo::vda5050
