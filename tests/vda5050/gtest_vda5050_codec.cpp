// Encoders of what rondo sends and defensive decoders of what a vehicle sends.
#include <gtest/gtest.h>

#include "rondo/vda5050/decode.h"
#include "rondo/vda5050/encode.h"
#include "rondo/vda5050/header.h"
#include "rondo/vda5050/inbox.h"
#include "vda5050/vda5050_test_support.h"

namespace rondo::vda5050 {
namespace {

using testing::sample_state_json;

Time at(const char* text) {
  return *parse_time(text);
}

TEST(Vda5050Header, TimestampIsUtcWithMilliseconds) {
  EXPECT_EQ(format_timestamp(at("2026-12-01T20:58:07Z")), "2026-12-01T20:58:07.000Z");
  EXPECT_EQ(format_timestamp(at("1999-01-02T03:04:05.067Z")), "1999-01-02T03:04:05.067Z");
}

TEST(Vda5050Header, IdsAreCountedPerTopic) {
  HeaderCounter headers("acme", "agv-7");
  const Time t = at("2026-12-01T10:00:00Z");
  EXPECT_EQ(headers.next(Topic::kOrder, t).header_id, 0);
  EXPECT_EQ(headers.next(Topic::kOrder, t).header_id, 1);
  EXPECT_EQ(headers.next(Topic::kInstantActions, t).header_id, 0);
  Header h = headers.next(Topic::kOrder, t);
  EXPECT_EQ(h.header_id, 2);
  EXPECT_EQ(h.version, "2.0.0");
  EXPECT_EQ(h.manufacturer, "acme");
  EXPECT_EQ(h.serial_number, "agv-7");
}

TEST(Vda5050Topics, NamesAndParse) {
  Topics t{.interface_name = "uagv", .manufacturer = "acme", .serial_number = "agv-7"};
  EXPECT_EQ(t.of(Topic::kInstantActions), "uagv/v2/acme/agv-7/instantActions");
  EXPECT_EQ(t.parse("uagv/v2/acme/agv-7/state"), Topic::kState);
  EXPECT_EQ(t.parse("uagv/v2/acme/agv-8/state"), std::nullopt);
  EXPECT_TRUE(validate(t).ok());
  t.serial_number = "a/b";
  EXPECT_FALSE(validate(t).ok());
}

TEST(Vda5050Encode, OrderCarriesEveryField) {
  Order o{.order_id = "o1", .order_update_id = 3, .nodes = {}, .edges = {}};
  o.nodes.push_back(
      {.node_id = "A",
       .sequence_id = 0,
       .released = true,
       .position =
           NodePosition{
               .x = 1, .y = 2, .theta = 0.5, .allowed_deviation_xy = 0, .allowed_deviation_theta = 0, .map_id = "m"},
       .actions = {}});
  o.nodes.push_back({.node_id = "B",
                     .sequence_id = 2,
                     .released = false,
                     .position = std::nullopt,
                     .actions = {Action{.action_type = "say",
                                        .action_id = "o1/0",
                                        .blocking_type = BlockingType::kHard,
                                        .action_description = "",
                                        .action_parameters = {{"text", std::string("hi")}}}}});
  o.edges.push_back({.edge_id = "A_B",
                     .sequence_id = 1,
                     .released = false,
                     .start_node_id = "A",
                     .end_node_id = "B",
                     .max_speed = 0.5,
                     .length = 3.0,
                     .actions = {}});
  Header h{.header_id = 4,
           .timestamp = at("2026-12-01T10:00:00Z"),
           .version = "2.0.0",
           .manufacturer = "acme",
           .serial_number = "agv-7"};
  Json j = encode_order(h, o);
  EXPECT_EQ(j["headerId"], 4);
  EXPECT_EQ(j["timestamp"], "2026-12-01T10:00:00.000Z");
  EXPECT_EQ(j["orderUpdateId"], 3);
  EXPECT_EQ(j["nodes"][0]["nodePosition"]["mapId"], "m");
  EXPECT_EQ(j["nodes"][0]["nodePosition"]["theta"], 0.5);
  EXPECT_FALSE(j["nodes"][1].contains("nodePosition"));
  EXPECT_EQ(j["nodes"][1]["actions"][0]["blockingType"], "HARD");
  EXPECT_EQ(j["nodes"][1]["actions"][0]["actionParameters"][0]["value"], "hi");
  EXPECT_EQ(j["edges"][0]["maxSpeed"], 0.5);
  EXPECT_EQ(j["edges"][0]["released"], false);
}

TEST(Vda5050Encode, TheSchemaFileSpellingOfTheDeviationOnlyWithTheCompatibilityOption) {
  Order o{.order_id = "o1", .order_update_id = 0, .nodes = {}, .edges = {}};
  o.nodes.push_back({.node_id = "A",
                     .sequence_id = 0,
                     .released = true,
                     .position = NodePosition{.x = 1,
                                              .y = 2,
                                              .theta = std::nullopt,
                                              .allowed_deviation_xy = 1.5,
                                              .allowed_deviation_theta = 0,
                                              .map_id = "m"},
                     .actions = {}});
  Header h{.header_id = 0,
           .timestamp = at("2026-12-01T10:00:00Z"),
           .version = "2.0.0",
           .manufacturer = "acme",
           .serial_number = "agv-7"};
  const Json standard = encode_order(h, o)["nodes"][0]["nodePosition"];
  EXPECT_EQ(standard["allowedDeviationXY"], 1.5);
  EXPECT_FALSE(standard.contains("allowedDeviationXy"));
  EXPECT_FALSE(standard.contains("theta"));
  const Json compat = encode_order(h, o, Compatibility{.vda5050_lib_1_4 = true})["nodes"][0]["nodePosition"];
  EXPECT_EQ(compat["allowedDeviationXY"], 1.5);
  EXPECT_EQ(compat["allowedDeviationXy"], 1.5);
}

TEST(Vda5050Encode, InstantActionsOldKeyOnlyWithTheCompatibilityOption) {
  Header h{.header_id = 0,
           .timestamp = at("2026-12-01T10:00:00Z"),
           .version = "2.0.0",
           .manufacturer = "acme",
           .serial_number = "agv-7"};
  InstantActions ia{.actions = {cancel_order_action("c1")}};
  Json standard = encode_instant_actions(h, ia);
  EXPECT_EQ(standard["actions"][0]["actionType"], "cancelOrder");
  EXPECT_FALSE(standard.contains("instantActions"));
  Json compat = encode_instant_actions(h, ia, Compatibility{.vda5050_lib_1_4 = true});
  EXPECT_EQ(compat["instantActions"], compat["actions"]);
}

TEST(Vda5050Decode, FullState) {
  Json j = sample_state_json();
  j["orderId"] = "o1";
  j["nodeStates"] = Json::parse(R"([{"nodeId":"B","sequenceId":2,"released":true}])");
  j["edgeStates"] = Json::parse(R"([{"edgeId":"A_B","sequenceId":1,"released":true}])");
  j["actionStates"] = Json::parse(R"([{"actionId":"x","actionStatus":"FAILED","resultDescription":"no"}])");
  j["errors"] = Json::parse(R"([{"errorType":"orderError","errorLevel":"WARNING",
      "errorDescription":"bad","errorReferences":[{"referenceKey":"orderUpdateId","referenceValue":3}]}])");
  auto s = decode_state(j.dump());
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->header.header_id, 5);
  EXPECT_EQ(s->header.timestamp, at("2026-12-01T10:00:00.250Z"));
  EXPECT_EQ(s->order_id, "o1");
  ASSERT_EQ(s->node_states.size(), 1u);
  EXPECT_EQ(s->edge_states.at(0).sequence_id, 1);
  EXPECT_EQ(s->action_states.at(0).action_status, ActionStatus::kFailed);
  EXPECT_EQ(s->errors.at(0).error_references.at(0).reference_value, "3");
  EXPECT_DOUBLE_EQ(s->battery_state.battery_charge, 87.5);
  ASSERT_TRUE(s->agv_position.has_value());
  EXPECT_EQ(s->agv_position->map_id, "g4s");
  EXPECT_TRUE(s->information.empty());
}

TEST(Vda5050Decode, InformationEntries) {
  Json j = sample_state_json();
  j["information"] = Json::parse(R"([{"infoType":"DOOR_STATE","infoLevel":"INFO","infoDescription":"door report",
      "infoReferences":[{"referenceKey":"doorId","referenceValue":"A-120-door"},{"referenceKey":"level","referenceValue":2}]},
      {"infoType":"BATTERY_SAVER","infoLevel":"DEBUG"}])");
  auto s = decode_state(j.dump());
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_EQ(s->information.size(), 2u);
  EXPECT_EQ(s->information[0].info_type, "DOOR_STATE");
  EXPECT_EQ(s->information[0].info_description, "door report");
  EXPECT_EQ(s->information[0].info_level, "INFO");
  ASSERT_EQ(s->information[0].info_references.size(), 2u);
  EXPECT_EQ(s->information[0].info_references[0].reference_value, "A-120-door");
  EXPECT_EQ(s->information[0].info_references[1].reference_value, "2");
  EXPECT_TRUE(s->information[1].info_references.empty());
  j["information"] = Json::parse(R"([{"infoLevel":"INFO"}])");
  auto bad = decode_state(j.dump());
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("information[0]: missing field 'infoType'"), std::string::npos) << bad.error().message;
}

TEST(Vda5050Decode, MalformedStatesAreErrorsThatNameTheField) {
  struct Case {
    const char* what;
    std::function<void(Json&)> edit;
    const char* expect;
  };
  std::vector<Case> cases = {
      {"missing", [](Json& j) { j.erase("lastNodeSequenceId"); }, "lastNodeSequenceId"},
      {"type", [](Json& j) { j["driving"] = "yes"; }, "driving"},
      {"nested", [](Json& j) { j["nodeStates"] = Json::parse(R"([{"nodeId":"B","sequenceId":"2","released":true}])"); },
       "nodeStates[0].sequenceId"},
      {"enum", [](Json& j) { j["operatingMode"] = "AUTOPILOT"; }, "operatingMode"},
      {"battery", [](Json& j) { j["batteryState"]["batteryCharge"] = 150; }, "batteryCharge"},
      {"negative", [](Json& j) { j["headerId"] = -1; }, "headerId"},
      {"version", [](Json& j) { j["version"] = "1.1.0"; }, "version"},
      {"time", [](Json& j) { j["timestamp"] = "yesterday"; }, "timestamp"},
  };
  for (const Case& c : cases) {
    Json j = sample_state_json();
    c.edit(j);
    auto s = decode_state(j.dump());
    ASSERT_FALSE(s.ok()) << c.what;
    EXPECT_NE(s.error().message.find(c.expect), std::string::npos) << c.what << ": " << s.error().message;
  }
  const std::string deep(200, '[');  // deeper than Document::kMaxDepth
  for (const std::string& text : std::vector<std::string>{"", "{", "[]", "null", "42", "{\"headerId\":", deep}) {
    EXPECT_FALSE(decode_state(text).ok()) << text;
  }
}

TEST(Vda5050Decode, ConnectionAndFactsheet) {
  auto c = decode_connection(R"({"headerId":1,"timestamp":"2026-12-01T10:00:00Z","version":"2.0.0",
      "manufacturer":"acme","serialNumber":"agv-7","connectionState":"CONNECTIONBROKEN"})");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->connection_state, ConnectionState::kConnectionBroken);
  EXPECT_FALSE(decode_connection(R"({"headerId":1,"timestamp":"2026-12-01T10:00:00Z","version":"2.0.0",
      "manufacturer":"acme","serialNumber":"agv-7","connectionState":"MAYBE"})")
                   .ok());

  const char* header_only = R"({"headerId":0,"timestamp":"2026-12-01T10:00:00Z","version":"2.0.0",
      "manufacturer":"acme","serialNumber":"agv-7"})";
  auto strict = decode_factsheet(header_only);
  ASSERT_FALSE(strict.ok());
  EXPECT_NE(strict.error().message.find("typeSpecification"), std::string::npos);
  auto lenient = decode_factsheet(header_only, Compatibility{.vda5050_lib_1_4 = true});
  ASSERT_TRUE(lenient.ok());
  EXPECT_TRUE(lenient->header_only);
  auto full = decode_factsheet(R"({"headerId":0,"timestamp":"2026-12-01T10:00:00Z","version":"2.0.0",
      "manufacturer":"acme","serialNumber":"agv-7","typeSpecification":{"seriesName":"S1"},
      "physicalParameters":{"speedMax":1.5}})");
  ASSERT_TRUE(full.ok()) << full.error().message;
  EXPECT_EQ(full->series_name, "S1");
  EXPECT_EQ(full->max_speed, 1.5);
  EXPECT_TRUE(full->agv_actions.empty());  // it lists none
}

// The actions a vehicle runs, from its factsheet's protocolFeatures.agvActions (VDA 5050 2.0.0,
// 6.10.4): in order, each once; a malformed list is an error naming the field.
TEST(Vda5050Decode, TheFactsheetListsTheActionsTheVehicleRuns) {
  auto f = decode_factsheet(R"({"headerId":0,"timestamp":"2026-12-01T10:00:00Z","version":"2.0.0",
      "manufacturer":"acme","serialNumber":"agv-7","typeSpecification":{"seriesName":"S1"},
      "protocolFeatures":{"optionalParameters":[],"agvActions":[
        {"actionType":"pick","actionScopes":["NODE"]},{"actionType":"drop","actionScopes":["NODE"]},
        {"actionType":"pick","actionScopes":["INSTANT"]},{"actionType":"noop","actionScopes":["NODE"]}]}})");
  ASSERT_TRUE(f.ok()) << f.error().message;
  EXPECT_EQ(f->agv_actions, (std::vector<std::string>{"pick", "drop", "noop"}));
  auto bad = decode_factsheet(R"({"headerId":0,"timestamp":"2026-12-01T10:00:00Z","version":"2.0.0",
      "manufacturer":"acme","serialNumber":"agv-7","typeSpecification":{"seriesName":"S1"},
      "protocolFeatures":{"agvActions":[{"actionScopes":["NODE"]}]}})");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("protocolFeatures.agvActions[0]: missing field 'actionType'"), std::string::npos)
      << bad.error().message;
}

TEST(Vda5050Inbox, WrongVehicleAndBackwardsHeaderIdsAreIgnoredWithAReason) {
  Inbox inbox("acme", "agv-7");
  Header h{.header_id = 3, .timestamp = {}, .version = "2.0.0", .manufacturer = "acme", .serial_number = "agv-7"};
  EXPECT_TRUE(inbox.admit(Topic::kState, h).ok());
  auto again = inbox.admit(Topic::kState, h);
  ASSERT_FALSE(again.ok());
  EXPECT_NE(again.error().message.find("out of order"), std::string::npos);
  h.header_id = 2;
  EXPECT_FALSE(inbox.admit(Topic::kState, h).ok());
  EXPECT_TRUE(inbox.admit(Topic::kConnection, h).ok());  // counted per topic
  h.header_id = 4;
  EXPECT_TRUE(inbox.admit(Topic::kState, h).ok());
  Header other = h;
  other.header_id = 9;
  other.serial_number = "agv-8";
  auto wrong = inbox.admit(Topic::kState, other);
  ASSERT_FALSE(wrong.ok());
  EXPECT_NE(wrong.error().message.find("agv-8"), std::string::npos);
  inbox.new_session();  // a restarted vehicle counts from 0 again
  h.header_id = 0;
  EXPECT_TRUE(inbox.admit(Topic::kState, h).ok());
}

TEST(Vda5050Inbox, ConnectionSessionsAndTheOlderLastWill) {
  Inbox inbox("acme", "agv-7");
  auto conn = [](std::int64_t id, ConnectionState s) {
    return Connection{.header = {.header_id = id,
                                 .timestamp = {},
                                 .version = "2.0.0",
                                 .manufacturer = "acme",
                                 .serial_number = "agv-7"},
                      .connection_state = s};
  };
  Header state{.header_id = 40, .timestamp = {}, .version = "2.0.0", .manufacturer = "acme", .serial_number = "agv-7"};
  EXPECT_TRUE(inbox.admit(conn(1, ConnectionState::kOnline)).ok());
  EXPECT_TRUE(inbox.admit(Topic::kState, state).ok());
  // The will was composed at connect, before ONLINE: headerId 0, and still taken.
  EXPECT_TRUE(inbox.admit(conn(0, ConnectionState::kConnectionBroken)).ok());
  EXPECT_FALSE(inbox.admit(conn(0, ConnectionState::kOffline)).ok());
  // The restarted vehicle: ONLINE starts a new session, its states count from 0 again.
  EXPECT_TRUE(inbox.admit(conn(1, ConnectionState::kOnline)).ok());
  state.header_id = 0;
  EXPECT_TRUE(inbox.admit(Topic::kState, state).ok());
  Connection other = conn(9, ConnectionState::kOnline);
  other.header.serial_number = "agv-8";
  EXPECT_FALSE(inbox.admit(other).ok());
}

}  // namespace
}  // namespace rondo::vda5050
