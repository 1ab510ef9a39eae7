// The deployment's mapping of a vehicle's information[] entries to observations: parsed with
// file:line:field errors, checked against the map, and read from states (information.h).
#include <gtest/gtest.h>

#include "rondo/map/map_loader.h"
#include "rondo/vda5050/config.h"
#include "rondo/vda5050/information.h"
#include "rondo/vda5050/messages.h"

namespace rondo::vda5050 {
namespace {

Result<std::vector<InformationRule>> rules(const std::string& yaml) {
  auto doc = Document::parse(yaml, DocumentFormat::kYaml, "deployment.yaml");
  if (!doc) return doc.error();
  auto list = doc->root().required("information");
  if (!list) return list.error();
  return parse_information_rules(*list);
}

constexpr const char* kRules = R"(information:
  - info_type: DOOR_STATE
    kind: door_open
    where_key: doorId
    value_key: state
    values: {OPEN: 1, CLOSED: 0}
  - info_type: CORRIDOR_BLOCKED
    kind: edge_blocked
    where: WayPoint1_WayPoint2
    values: {blocked: 1, clear: 0}
  - info_type: PERSON
    kind: person_present
    where_key: node
    values: {seen: 1}
)";

const map::TopoMap& g4s() {
  static const map::TopoMap map = map::load_map("examples/g4s/map.yaml").value();
  return map;
}

Information door(const std::string& id, const std::string& state) {
  return {.info_type = "DOOR_STATE",
          .info_references = {{.reference_key = "doorId", .reference_value = id},
                              {.reference_key = "state", .reference_value = state}},
          .info_level = "INFO"};
}

Time at(int s) { return Time{} + seconds(s); }

TEST(Vda5050Information, ParsesTheRules) {
  auto r = rules(kRules);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_EQ(r->size(), 3u);
  EXPECT_EQ((*r)[0].kind, "door_open");
  EXPECT_EQ((*r)[0].where_key, "doorId");
  EXPECT_EQ((*r)[0].values.at("CLOSED"), 0);
  EXPECT_EQ((*r)[1].where, "WayPoint1_WayPoint2");
  EXPECT_EQ((*r)[1].value_key, "");
  EXPECT_NE((*r)[1].origin.find("deployment.yaml:9: information[1].where"), std::string::npos) << (*r)[1].origin;
  EXPECT_TRUE(check_information_places(*r, g4s()).ok());
}

TEST(Vda5050Information, BadRulesNameTheFileLineAndField) {
  struct Case {
    const char* yaml;
    const char* expect;
  };
  const Case cases[] = {
      {"information:\n  - info_type: D\n    kind: door\n    where: x\n    values: {a: 1}\n",
       "deployment.yaml:3: information[0].kind: 'door' is not an observation kind"},
      {"information:\n  - info_type: D\n    kind: door_open\n    values: {a: 1}\n", "information[0]: give the place"},
      {"information:\n  - info_type: D\n    kind: door_open\n    where: x\n    where_key: k\n    values: {a: 1}\n",
       "exactly one"},
      {"information:\n  - info_type: D\n    kind: door_open\n    where: x\n    values: {a: 2}\n",
       "deployment.yaml:5: information[0].values.a: must be 1 or 0"},
      {"information:\n  - info_type: D\n    kind: door_open\n    where: x\n    values: {}\n", "information[0].values"},
      {"information:\n  - info_type: \"\"\n    kind: door_open\n    where: x\n    values: {a: 1}\n",
       "information[0].info_type: must not be empty"},
      {"information:\n  - info_type: D\n    kind: door_open\n    where: x\n    values: {a: 1}\n    colour: red\n",
       "colour"},
      {"information:\n  - {info_type: D, kind: door_open, where: x, values: {a: 1}}\n"
       "  - {info_type: D, kind: edge_blocked, where: y, values: {a: 1}}\n",
       "information[1].info_type: 'D' is mapped already by information[0]"},
      {"information: {info_type: D}\n", "information"},
  };
  for (const Case& c : cases) {
    auto r = rules(c.yaml);
    ASSERT_FALSE(r.ok()) << c.yaml;
    EXPECT_NE(r.error().message.find(c.expect), std::string::npos) << r.error().message;
  }
  auto off_map = rules("information:\n  - info_type: D\n    kind: door_open\n    where: the-moon\n    values: {a: 1}\n");
  ASSERT_TRUE(off_map.ok());
  auto checked = check_information_places(*off_map, g4s());
  ASSERT_FALSE(checked.ok());
  EXPECT_NE(checked.error().message.find("deployment.yaml:4: information[0].where: 'the-moon' is not a door of map"),
            std::string::npos)
      << checked.error().message;
}

TEST(Vda5050Information, TheRobotSectionCarriesTheRules) {
  auto doc = Document::parse(
      "robot:\n  kind: vda5050\n  broker: \"mqtt://127.0.0.1:1883\"\n  interface_name: uagv\n  manufacturer: acme\n"
      "  serial_number: agv-7\n  map_id: g4s_y2\n  information:\n"
      "    - {info_type: DOOR_STATE, kind: door_open, where_key: doorId, values: {OPEN: 1, CLOSED: 0}}\n",
      DocumentFormat::kYaml, "deployment.yaml");
  ASSERT_TRUE(doc.ok());
  auto c = parse_vda5050_config(doc->root().required("robot").value());
  ASSERT_TRUE(c.ok()) << c.error().message;
  ASSERT_EQ(c->information.size(), 1u);
  EXPECT_EQ(c->information[0].info_type, "DOOR_STATE");
}

TEST(Vda5050Information, ReportsNewAndChangedEntriesAndRepeatsThemWhileTheyHold) {
  InformationReader reader(rules(kRules).value(), g4s(), minutes(5));
  auto r = reader.read({door("WayPoint1_WayPoint2", "CLOSED")}, at(0));
  ASSERT_EQ(r.seen.size(), 1u);
  EXPECT_EQ(r.seen[0].what, "door_open");
  EXPECT_EQ(r.seen[0].where, "WayPoint1_WayPoint2");
  EXPECT_EQ(r.seen[0].value, 0);
  EXPECT_EQ(r.seen[0].when, at(0));
  EXPECT_EQ(r.seen[0].source, "") << "the robot's own observation";
  EXPECT_TRUE(r.ignored.empty());
  EXPECT_TRUE(reader.read({door("WayPoint1_WayPoint2", "CLOSED")}, at(10)).seen.empty()) << "unchanged";
  EXPECT_TRUE(reader.read({}, at(20)).seen.empty()) << "gone says nothing";
  EXPECT_EQ(reader.read({door("WayPoint1_WayPoint2", "CLOSED")}, at(300)).seen.size(), 1u) << "repeated";
  auto open = reader.read({door("WayPoint1_WayPoint2", "OPEN")}, at(301));
  ASSERT_EQ(open.seen.size(), 1u);
  EXPECT_EQ(open.seen[0].value, 1);
  // A fixed place, read from infoDescription; another vendor entry is not an observation.
  auto blocked = reader.read({{.info_type = "CORRIDOR_BLOCKED", .info_description = "blocked"},
                              {.info_type = "CHARGING_HINT", .info_description = "soon"}},
                             at(302));
  ASSERT_EQ(blocked.seen.size(), 1u);
  EXPECT_EQ(blocked.seen[0].what, "edge_blocked");
  EXPECT_EQ(blocked.seen[0].where, "WayPoint1_WayPoint2");
  EXPECT_EQ(blocked.seen[0].value, 1);
}

TEST(Vda5050Information, EntriesThatCannotBeReadAreIgnoredOnceWithTheReason) {
  InformationReader reader(rules(kRules).value(), g4s());
  auto r = reader.read({door("the-moon", "OPEN"), door("WayPoint1_WayPoint2", "AJAR"),
                        {.info_type = "DOOR_STATE", .info_references = {{"state", "OPEN"}}},
                        {.info_type = "PERSON", .info_references = {{"node", "WayPoint1"}}, .info_description = "away"}},
                       at(0));
  EXPECT_TRUE(r.seen.empty());
  ASSERT_EQ(r.ignored.size(), 4u);
  EXPECT_EQ(r.ignored[0], "state: information[0] (infoType DOOR_STATE): 'the-moon' is not a door of map 'g4s_y2'");
  EXPECT_EQ(r.ignored[1], "state: information[1] (infoType DOOR_STATE): 'AJAR' is not one of CLOSED, OPEN");
  EXPECT_EQ(r.ignored[2], "state: information[2] (infoType DOOR_STATE): no infoReference 'doorId' naming the place");
  EXPECT_EQ(r.ignored[3], "state: information[3] (infoType PERSON): 'away' is not one of seen");
  EXPECT_TRUE(reader.read({door("the-moon", "OPEN")}, at(1)).ignored.empty()) << "told once";
}

}  // namespace
}  // namespace rondo::vda5050
