// The places file (docs/commands.md, "The places file"): what it defines resolves, and every bad
// file is an error naming the file, the line and the field.
#include <gtest/gtest.h>

#include "lang/lang_test_support.h"

namespace rondo::lang {
namespace {

const map::TopoMap& office_map() {
  return test::office().map;
}

Result<Places> places_from(const std::string& yaml) {
  auto doc = Document::parse(yaml, DocumentFormat::kYaml, "places.yaml");
  if (!doc) return doc.error();
  return Places::decode(*doc, office_map());
}

void expect_error(const std::string& yaml, const std::string& text) {
  auto p = places_from(yaml);
  ASSERT_FALSE(p.ok()) << yaml;
  EXPECT_NE(p.error().message.find(text), std::string::npos) << p.error().message;
}

TEST(Places, TheExampleResolvesRoomsThingsAliasesGroupsAndPeople) {
  const Places& p = test::office().places;
  ASSERT_TRUE(p.zone().has_value());
  EXPECT_EQ(p.zone()->name(), "Europe/London");
  auto nodes = [&](const std::string& phrase) {
    auto r = p.resolve(phrase);
    return r ? r->nodes : std::vector<std::string>{"error: " + r.error().message};
  };
  using V = std::vector<std::string>;
  EXPECT_EQ(nodes("room A-110"), V{"A-110"});
  EXPECT_EQ(nodes("Office a-110"), V{"A-110"});
  EXPECT_EQ(nodes("the library"), V{"A-110"});
  EXPECT_EQ(nodes("the librarian's desk in room A-110"), V{"A-110-Desk"});
  EXPECT_EQ(nodes("the desk in the library"), V{"A-110-Desk"});
  EXPECT_EQ(nodes("the librarian"), V{"A-110-Desk"});
  EXPECT_EQ(nodes("the meeting table"), V{"A-111-Table"});  // in one room only: no room needed
  EXPECT_EQ(nodes("Michael"), V{"A-114-Desk"});
  EXPECT_EQ(nodes("michael's desk"), V{"A-114-Desk"});
  EXPECT_EQ(nodes("Michael's office"), V{"A-114-Desk"});
  EXPECT_EQ(nodes("Anna's place"), V{"A-120-Desk"});
  EXPECT_EQ(nodes("the dock"), V{"ChargingPoint"});
  EXPECT_EQ(nodes("Hall-A-120"), V{"Hall-A-120"});
  EXPECT_EQ(nodes("the emergency exits"), (V{"Exit-West", "Exit-East"}));
  EXPECT_EQ(p.resolve("the corridor")->nodes.size(), 8u);
  EXPECT_TRUE(p.is_room("the kitchen"));
  EXPECT_FALSE(p.is_room("the dock"));
  auto unknown = p.resolve("room A-121");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().code, ErrorCode::kNotFound);
  EXPECT_EQ(unknown.error().message, "no place called 'room A-121'; nearest known places: A-120, A-123, A-111");
}

TEST(Places, EveryNodeItNamesMustBeOnTheMap) {
  expect_error("rooms:\n  - {name: A-110, node: A-11}\n",
               "places.yaml:2: rooms[0].node: map 'office' has no node 'A-11' (nearest: A-110, A-111, A-114)");
  expect_error("groups:\n  - name: exits\n    nodes: [Exit-West, Exit-North]\n", "places.yaml:3: groups[0].nodes[1]");
  expect_error("places:\n  - {name: dock, node: Charger}\n", "places[0].node: map 'office' has no node 'Charger'");
}

TEST(Places, NamesThatNormaliseAlikeMustMeanTheSameNodes) {
  expect_error("places:\n  - {name: dock, node: ChargingPoint}\n  - {name: The Dock, node: Exit-West}\n",
               "places.yaml:3: places[1].name: 'The Dock' already names ChargingPoint (dock)");
  expect_error("places:\n  - {name: a-120, node: A-123}\n", "'a-120' already names A-120 (A-120)");
  // The same meaning twice is not a conflict.
  EXPECT_TRUE(
      places_from("places:\n  - {name: dock, node: ChargingPoint}\n  - {name: the dock, node: ChargingPoint}\n").ok());
  expect_error(
      "rooms:\n  - name: A-120\n    node: A-120\n    places:\n      - {name: desk, node: A-120-Desk}\n"
      "      - {name: Desk, node: A-123-Desk}\n",
      "rooms[0].places[1].name: 'Desk' already names A-120-Desk in room A-120");
}

TEST(Places, MalformedFilesAreRejectedWithTheField) {
  expect_error("rondo_places: 2\n", "places.yaml:1: rondo_places: places format 2 is not supported");
  expect_error("time_zone: Mars/Olympus\n", "places.yaml:1: time_zone:");
  expect_error("rooms:\n  - {name: A-110, node: A-110, desks: []}\n", "unknown field 'desks'");
  expect_error("groups:\n  - {name: twice, nodes: [Exit-West, Exit-West]}\n", "node 'Exit-West' is listed twice");
  expect_error("groups:\n  - {name: none, nodes: []}\n", "a group needs at least one node");
  expect_error("places:\n  - {name: '', node: A-110}\n", "places[0].name: a name needs at least one word");
  expect_error("people:\n  - {name: Ghost, place: the attic}\n", "people[0].place: no place called 'the attic'");
  expect_error("groups:\n  - {name: exits, nodes: [Exit-West, Exit-East]}\npeople:\n  - {name: Bob, place: exits}\n",
               "'exits' is 2 places; a person has one");
  expect_error("rooms:\n  - {name: A-110, node: A-110}\n  - {name: a-110, node: A-110}\n",
               "room 'a-110' is defined twice");
}

}  // namespace
}  // namespace rondo::lang
