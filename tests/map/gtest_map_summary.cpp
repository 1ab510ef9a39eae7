// summarize() and its JSON form, which `rondo map info --json` prints.
#include "rondo/map/map_summary.h"

#include <gtest/gtest.h>

#include "map_test_support.h"
#include "rondo/map/map_loader.h"

namespace rondo::map {
namespace {

TEST(MapSummary, OfficeFixture) {
  auto map = load_map(testing::fixture("office.yaml"));
  ASSERT_TRUE(map.ok()) << map.error().message;
  const MapSummary s = summarize(*map);
  EXPECT_EQ(s.name, "office");
  EXPECT_EQ(s.nodes, 5u);
  EXPECT_EQ(s.edges, 8u);
  EXPECT_EQ(
      s.actions,
      (std::map<std::string, std::size_t>{
          {"docking", 1}, {"doorPassing", 2}, {"human_aware_navigation", 2}, {"move_base", 2}, {"undocking", 1}}));
  ASSERT_EQ(s.doors.size(), 1u);
  EXPECT_EQ(s.doors[0].id, "kitchen_door");
  EXPECT_EQ(s.doors[0].edges, (std::vector<std::string>{"Corridor_Kitchen", "Kitchen_Corridor"}));
  ASSERT_TRUE(s.bounding_box.has_value());
  EXPECT_EQ(*s.bounding_box, (BoundingBox{0, -3, 5, 4}));
  // 1+1 (dock) + 4+4 (station-corridor) + 4+4 (kitchen) + 3+3 (office)
  EXPECT_DOUBLE_EQ(s.total_edge_length, 24.0);
  EXPECT_EQ(s.longest_edge, "Station_Corridor");
  EXPECT_DOUBLE_EQ(s.longest_edge_length, 4.0);
  EXPECT_EQ(s.edges_with_top_speed, 6u);
  EXPECT_EQ(s.nodes_with_influence, 1u);
  EXPECT_EQ(s.strongly_connected_components, 1u);
  // dock 1/0.1+30 twice, 4/0.5 twice, 4/0.3+15 twice, 3/0.55 twice
  EXPECT_NEAR(s.nominal_travel_time_total, 2 * 40.0 + 2 * 8.0 + 2 * (4 / 0.3 + 15) + 2 * (3 / 0.55), 0.01);
  EXPECT_TRUE(s.warnings.empty());
}

TEST(MapSummary, JsonHasTheCountsAndUnits) {
  auto map = load_map(testing::fixture("dead_end.yaml"));
  ASSERT_TRUE(map.ok()) << map.error().message;
  const Json j = to_json(summarize(*map));
  EXPECT_EQ(j["nodes"], 4);
  EXPECT_EQ(j["edges"], 3);
  EXPECT_EQ(j["actions"]["move_base"], 3);
  EXPECT_EQ(j["doors"], Json::array());
  EXPECT_EQ(j["bounding_box_m"]["max_x"], 9.0);
  EXPECT_EQ(j["total_edge_length_m"], 3.0);
  EXPECT_EQ(j["strongly_connected"], false);
  EXPECT_EQ(j["strongly_connected_components"], 3);
  EXPECT_EQ(j["warnings"].size(), 3u);
  EXPECT_EQ(j["longest_edge"]["id"], "A_B");
}

TEST(MapSummary, CountsCapacitiesAndNarrowEdges) {
  auto map = load_map(testing::fixture("traffic.yaml"));
  ASSERT_TRUE(map.ok()) << map.error().message;
  const MapSummary s = summarize(*map);
  EXPECT_EQ(s.nodes_with_capacity, 2u);
  EXPECT_EQ(s.largest_capacity, 4);
  EXPECT_EQ(s.narrow_single, 2u);
  EXPECT_EQ(s.narrow_one_way, 2u);
  const Json j = to_json(s);
  EXPECT_EQ(j["nodes_with_capacity"], 2);
  EXPECT_EQ(j["largest_capacity"], 4);
  EXPECT_EQ(j["narrow_edges"], (Json{{"single", 2}, {"one_way", 2}}));
  EXPECT_TRUE(s.warnings.empty());
}

TEST(MapSummary, MapWithoutEdges) {
  const TopoMap map = testing::build_or_fail({testing::node_at("A", 1, 1)}, {});
  const Json j = to_json(summarize(map));
  EXPECT_EQ(j["edges"], 0);
  EXPECT_TRUE(j["longest_edge"].is_null());
  EXPECT_EQ(j["strongly_connected"], true);
}

}  // namespace
}  // namespace rondo::map
