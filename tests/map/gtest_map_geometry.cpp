// Edge length, the distance-based travel-time prior, action kinds and the bounding box.
#include "rondo/map/map_geometry.h"

#include <gtest/gtest.h>

#include "map_test_support.h"

namespace rondo::map {
namespace {

using testing::build_or_fail;
using testing::edge;
using testing::node_at;

TEST(ActionKind, ClassifiesByName) {
  const std::vector<std::pair<std::string, ActionKind>> cases = {
      {"move_base", ActionKind::kMove},    {"human_aware_navigation", ActionKind::kMove},
      {"doorPassing", ActionKind::kDoor},  {"door_wait_and_pass", ActionKind::kDoor},
      {"DOOR", ActionKind::kDoor},         {"docking", ActionKind::kDocking},
      {"undocking", ActionKind::kDocking}, {"Dock", ActionKind::kDocking},
      {"do", ActionKind::kMove},           {"", ActionKind::kMove},
  };
  for (const auto& [action, kind] : cases) EXPECT_EQ(action_kind(action), kind) << action;
  EXPECT_STREQ(to_string(ActionKind::kDoor), "door");
}

Edge fast(Edge e, double speed) {
  e.top_speed = speed;
  return e;
}

TopoMap sample() {
  // A at the origin, B 5 m away (3-4-5), C 2 m from A.
  return build_or_fail({node_at("A", 0, 0), node_at("B", 3, 4), node_at("C", -2, 0)},
                       {edge("A", "B"), fast(edge("B", "A"), 2.5), edge("A", "C", "doorPassing"),
                        fast(edge("C", "A", "undocking"), 0.1)});
}

TEST(EdgeLength, IsTheStraightLineBetweenPoses) {
  const TopoMap map = sample();
  EXPECT_DOUBLE_EQ(edge_length(map, 0), 5.0);
  EXPECT_DOUBLE_EQ(edge_length(map, 1), 5.0);
  EXPECT_DOUBLE_EQ(edge_length(map, 2), 2.0);
}

TEST(NominalTravelTime, TableOfEdgesAndOptions) {
  const TopoMap map = sample();
  struct Case {
    EdgeIndex edge;
    TravelTimeOptions options;
    double seconds;
  };
  const std::vector<Case> cases = {
      {0, {}, 10.0},  // 5 m at the default 0.5 m/s
      {0, {.default_speed = 0.25, .door_overhead_s = 15, .docking_overhead_s = 30}, 20.0},
      {1, {}, 2.0},         // the edge's own 2.5 m/s wins
      {2, {}, 4.0 + 15.0},  // door overhead
      {2, {.default_speed = 0.5, .door_overhead_s = 0, .docking_overhead_s = 30}, 4.0},
      {3, {}, 20.0 + 30.0},  // 2 m at 0.1 m/s, docking overhead
      {0, {.default_speed = 0, .door_overhead_s = 15, .docking_overhead_s = 30}, 10.0},  // bad option: 0.5
      {0, {.default_speed = -1, .door_overhead_s = 15, .docking_overhead_s = 30}, 10.0},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(nominal_travel_time(map, c.edge, c.options), from_seconds(c.seconds)) << "edge " << c.edge;
  }
}

TEST(NominalTravelTime, HugeDistancesAreCappedNotOverflowed) {
  const TopoMap map = build_or_fail({node_at("A", -1e308, 0), node_at("B", 1e308, 0)}, {fast(edge("A", "B"), 1e-300)});
  const Duration t = nominal_travel_time(map, 0);
  EXPECT_GT(t, Duration{0});
  EXPECT_EQ(t, from_seconds(1e12));
}

TEST(BoundingBox, CoversEveryNode) {
  const auto box = bounding_box(sample());
  ASSERT_TRUE(box.has_value());
  EXPECT_EQ(*box, (BoundingBox{-2, 0, 3, 4}));
  EXPECT_FALSE(bounding_box(TopoMap{}).has_value());
}

}  // namespace
}  // namespace rondo::map
