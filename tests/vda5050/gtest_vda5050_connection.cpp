// The connection watch and the deployment's robot section.
#include <gtest/gtest.h>

#include "rondo/vda5050/config.h"
#include "rondo/vda5050/connection_watch.h"

namespace rondo::vda5050 {
namespace {

Time at(int s) {
  return *parse_time("2026-12-01T10:00:00Z") + seconds(s);
}

TEST(Vda5050ConnectionWatch, OnlineOfflineSilenceAndTheBroker) {
  ConnectionWatch w(seconds(30), {});
  EXPECT_FALSE(w.online(at(0)));
  w.on_connection(ConnectionState::kOnline, at(0));
  EXPECT_TRUE(w.online(at(1)));
  w.on_state(at(10));
  EXPECT_TRUE(w.online(at(39)));
  EXPECT_FALSE(w.online(at(41)));  // silent too long, no last will needed
  EXPECT_NE(w.why_offline(at(41)).find("no state for 31s"), std::string::npos);
  w.on_state(at(42));
  EXPECT_TRUE(w.online(at(42)));
  w.on_connection(ConnectionState::kConnectionBroken, at(50));
  EXPECT_NE(w.why_offline(at(50)).find("CONNECTIONBROKEN"), std::string::npos);
  w.on_state(at(51));  // without the compatibility option only ONLINE brings it back
  EXPECT_FALSE(w.online(at(51)));
  w.on_connection(ConnectionState::kOnline, at(52));
  EXPECT_TRUE(w.online(at(52)));
  w.on_broker_lost(at(53));
  EXPECT_FALSE(w.online(at(53)));
  w.on_state(at(54));
  EXPECT_TRUE(w.online(at(54)));
}

TEST(Vda5050ConnectionWatch, WithTheCompatibilityOptionAStateAfterABreakIsBack) {
  ConnectionWatch w(seconds(30), Compatibility{.vda5050_lib_1_4 = true});
  w.on_connection(ConnectionState::kOnline, at(0));
  w.on_connection(ConnectionState::kConnectionBroken, at(5));
  EXPECT_FALSE(w.online(at(5)));
  w.on_state(at(5));  // not after the announcement
  EXPECT_FALSE(w.online(at(5)));
  w.on_state(at(7));
  EXPECT_TRUE(w.online(at(7)));
}

Result<Vda5050Config> parse(const std::string& yaml) {
  auto doc = Document::parse(yaml, DocumentFormat::kYaml, "deployment.yaml");
  if (!doc) return doc.error();
  auto robot = doc->root().required("robot");
  if (!robot) return robot.error();
  return parse_vda5050_config(*robot);
}

TEST(Vda5050Config, ParsesAndNamesBadFields) {
  auto c = parse(R"(robot:
  kind: vda5050
  broker: "mqtt://127.0.0.1:1883"
  interface_name: uagv
  manufacturer: acme
  serial_number: agv-7
  map_id: g4s_y2
  offline_after: 1m
)");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->topics.of(Topic::kState), "uagv/v2/acme/agv-7/state");
  EXPECT_EQ(c->offline_after, minutes(1));
  EXPECT_FALSE(c->compat.vda5050_lib_1_4);
  auto bad = parse(
      "robot:\n  kind: vda5050\n  broker: \"http://x\"\n  interface_name: u\n  manufacturer: a\n"
      "  serial_number: s\n  map_id: m\n");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("deployment.yaml:3"), std::string::npos) << bad.error().message;
  auto slash = parse(
      "robot:\n  kind: vda5050\n  broker: \"mqtt://h:1\"\n  interface_name: u\n  manufacturer: a\n"
      "  serial_number: s/t\n  map_id: m\n  compatibility: vda5050-lib-1.4\n");
  ASSERT_FALSE(slash.ok());
  EXPECT_NE(slash.error().message.find("serial_number"), std::string::npos);
  auto unknown = parse("robot:\n  kind: vda5050\n  brokr: x\n");
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.error().message.find("brokr"), std::string::npos);
}

}  // namespace
}  // namespace rondo::vda5050
