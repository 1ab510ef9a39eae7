// The example floor examples/office: a valid map whose rooms are behind doors, the paper's places
// resolving through places.yaml, and routines.yaml being what its sentences mean.
#include <gtest/gtest.h>

#include <set>

#include "lang/lang_test_support.h"
#include "rondo/core/task_codec.h"
#include "rondo/map/map_validation.h"

namespace rondo::lang {
namespace {

const std::vector<std::string> kRooms = {"A-110", "A-111", "A-114", "A-117", "A-120", "A-123"};

TEST(OfficeExample, EveryRoomIsBehindItsDoor) {
  const map::TopoMap& m = test::office().map;
  for (const auto& room : kRooms) {
    // The room's nodes: its own and those whose names start with it (A-110-Desk).
    auto in_room = [&](const std::string& n) { return n == room || n.rfind(room + "-", 0) == 0; };
    int doors = 0;
    for (const auto& e : m.edges()) {
      if (in_room(e.from) == in_room(e.to)) continue;  // inside the room, or elsewhere
      EXPECT_EQ(e.action, "doorPassing") << e.id;
      EXPECT_EQ(e.door, room + "-door") << e.id;
      EXPECT_EQ(in_room(e.from) ? e.from : e.to, room) << e.id;  // only through the node inside the door
      ++doors;
    }
    EXPECT_EQ(doors, 2) << room;  // one door, both ways
  }
}

TEST(OfficeExample, ThePapersPlacesResolve) {
  const Places& p = test::office().places;
  const std::pair<const char*, const char*> kPaper[] = {
      {"the meeting table in room A-111", "A-111-Table"},
      {"the desk in room A-120", "A-120-Desk"},
      {"the librarian's desk in room A-110", "A-110-Desk"},
      {"the desk in room A-114", "A-114-Desk"},
      {"room A-110", "A-110"},
      {"A-111", "A-111"},
      {"A-120", "A-120"},
      {"office A-123", "A-123"},
      {"Michael's desk", "A-114-Desk"},
  };
  for (const auto& [phrase, node] : kPaper) {
    auto r = p.resolve(phrase);
    ASSERT_TRUE(r.ok()) << phrase << ": " << r.error().message;
    EXPECT_EQ(r->nodes, std::vector<std::string>{node}) << phrase;
    EXPECT_TRUE(test::office().map.find_node(node).has_value()) << node;
  }
  EXPECT_EQ(p.resolve("the emergency exits")->nodes, (std::vector<std::string>{"Exit-West", "Exit-East"}));
}

// routines.yaml says it was written with `rondo task add ... --at 2026-11-23T08:00`: check it.
TEST(OfficeExample, RoutinesAreWhatTheirSentencesMean) {
  auto file = load_task_file("examples/office/routines.yaml");
  ASSERT_TRUE(file.ok()) << file.error().message;
  CommandContext ctx = test::office_context();
  ctx.now = *parse_time("2026-11-23T08:00:00Z");
  std::vector<Routine> made;
  for (const char* sentence :
       {"check the emergency exits every 2 hours between 08:00 and 18:00 on weekdays",
        "patrol the hallway every weekday at 09:00", "check the kitchen every weekday between 13:30 and 14:00"}) {
    auto c = parse_command(sentence, ctx);
    ASSERT_TRUE(c.ok()) << sentence << ": " << c.error().message;
    made.insert(made.end(), c->routines.begin(), c->routines.end());
  }
  EXPECT_EQ(file->routines, made);
  EXPECT_TRUE(file->tasks.empty());
}

}  // namespace
}  // namespace rondo::lang
