// The traffic scaling bench's building (bench/traffic-scale/map.yaml, written by
// scripts/traffic_layout.py; issue 42): read through rondo's map loader, it is a valid map of at
// least 200 nodes with both kinds of narrow passage, a wide main corridor and dock room for the
// bench's 100 robots.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "rondo/map/map_loader.h"
#include "rondo/map/map_summary.h"
#include "rondo/map/map_validation.h"
#include "rondo/map/topo_map.h"
#include "source_dir.h"

namespace rondo {
namespace {

TEST(TrafficScaleMap, IsAValidBuildingWithNarrowCorridors) {
  const auto map = map::load_map(testing::source_dir() / "bench/traffic-scale/map.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_GE(map->node_count(), 200u);
  EXPECT_TRUE(map::find_map_problems(map->nodes(), map->edges()).empty());
  const auto warnings = map::map_warnings(*map);
  EXPECT_TRUE(warnings.empty()) << warnings.front();

  std::size_t single = 0;
  std::size_t one_way = 0;
  for (const map::Edge& e : map->edges()) {
    single += e.narrow == map::Narrow::kSingle ? 1 : 0;
    one_way += e.narrow == map::Narrow::kOneWay ? 1 : 0;
  }
  EXPECT_GE(single, 1u);
  EXPECT_GE(one_way, 1u);
  const map::MapSummary s = map::summarize(*map);
  EXPECT_EQ(s.narrow_single, single);
  EXPECT_EQ(s.narrow_one_way, one_way);
  EXPECT_EQ(s.strongly_connected_components, 1u);
}

TEST(TrafficScaleMap, HasAWideMainCorridorAndDockRoomForAHundredRobots) {
  const auto map = map::load_map(testing::source_dir() / "bench/traffic-scale/map.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  int dock_room = 0;
  std::size_t main_corridor = 0;
  for (const map::Node& n : map->nodes()) {
    if (n.name.starts_with("Dock-")) dock_room += n.capacity;
    if (n.name.starts_with("Main-")) {
      ++main_corridor;
      EXPECT_EQ(n.capacity, 2) << n.name;
    }
  }
  EXPECT_GE(main_corridor, 2u);
  EXPECT_GE(dock_room, 100);
}

}  // namespace
}  // namespace rondo
