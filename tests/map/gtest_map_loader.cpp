// load_map: format detection, the three real STRANDS maps, round trips through rondo's format,
// and save_map.
#include "rondo/map/map_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "map_test_support.h"
#include "rondo/map/map_validation.h"
#include "rondo/map/map_yaml.h"

namespace rondo::map {
namespace {

using testing::fixture;
using testing::real_map;
using testing::TempDir;

struct RealMap {
  std::string file;
  MapFormat format;
  std::size_t nodes;
  std::size_t edges;
  std::size_t door_edges;
  std::string name;
};

class RealMaps : public ::testing::TestWithParam<RealMap> {};

TEST_P(RealMaps, LoadWithExpectedCountsAndNoWarnings) {
  const RealMap& c = GetParam();
  auto loaded = load_map_file(real_map(c.file));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->format, c.format);
  EXPECT_EQ(loaded->map.node_count(), c.nodes);
  EXPECT_EQ(loaded->map.edge_count(), c.edges);
  EXPECT_EQ(loaded->map.name(), c.name);
  std::size_t doors = 0;
  for (const Edge& e : loaded->map.edges()) doors += e.door ? 1u : 0u;
  EXPECT_EQ(doors, c.door_edges);
  EXPECT_TRUE(map_warnings(loaded->map).empty());
}

TEST_P(RealMaps, RoundTripThroughRondoFormatUnchanged) {
  const RealMap& c = GetParam();
  auto map = load_map(real_map(c.file));
  ASSERT_TRUE(map.ok()) << map.error().message;
  TempDir dir;
  const auto out = dir.path() / "converted.yaml";
  ASSERT_TRUE(save_map(*map, out).ok());
  auto again = load_map_file(out);
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(again->format, MapFormat::kRondo);
  EXPECT_EQ(again->map, *map);
  // And a second conversion writes the same text.
  EXPECT_EQ(write_map_yaml(again->map), write_map_yaml(*map));
}

INSTANTIATE_TEST_SUITE_P(
    Strands, RealMaps,
    ::testing::Values(RealMap{"tsc_1605.yaml", MapFormat::kStrandsYaml, 67, 232, 4, "tsc_1605"},
                      RealMap{"g4s_y2.tmap", MapFormat::kStrandsTmap, 40, 84, 18, "g4s_y2"},
                      RealMap{"aaf_winter.json", MapFormat::kStrandsJson, 48, 124, 0, "aaf_winter_bellbot"}),
    [](const auto& param_info) { return param_info.param.file.substr(0, param_info.param.file.find('.')); });

TEST(RealMaps, TscDetailsSurviveImport) {
  auto map = load_map(real_map("tsc_1605.yaml"));
  ASSERT_TRUE(map.ok());
  const Node& charger = map->node(*map->find_node("ChargingPoint"));
  EXPECT_NEAR(charger.pose.x, -47.1828079224, 1e-9);
  EXPECT_NEAR(charger.pose.y, -5.35404396057, 1e-9);
  // From the quaternion w -0.703398406506, z -0.710795760155 (about +90.6 degrees).
  EXPECT_NEAR(charger.pose.yaw,
              std::atan2(2 * -0.703398406506 * -0.710795760155,
                         0.703398406506 * 0.703398406506 - 0.710795760155 * 0.710795760155),
              1e-6);
  EXPECT_NEAR(charger.pose.yaw, 1.5813, 1e-3);
  EXPECT_EQ(charger.influence.size(), 8u);
  EXPECT_EQ(map->edge(*map->find_edge("ChargingPoint_Station")).action, "undocking");
  EXPECT_EQ(map->edge(*map->find_edge("ChargingPoint_Station")).top_speed, 0.55);
  EXPECT_EQ(map->edge(*map->find_edge("WayPoint31_WayPoint30")).door, "WayPoint30_WayPoint31");
}

TEST(RealMaps, AafMetaKeepsRooms) {
  auto map = load_map(real_map("aaf_winter.json"));
  ASSERT_TRUE(map.ok());
  const Node& waiting = map->node(*map->find_node("WayPoint29"));
  EXPECT_EQ(waiting.meta["description"], "Wheel Chair Waiting Area");
  EXPECT_EQ(waiting.meta["contains"].size(), 2u);
}

TEST(LoadMap, DetectsFormatsOfTheFixtures) {
  const std::vector<std::pair<std::string, MapFormat>> cases = {
      {"office.yaml", MapFormat::kRondo},
      {"small.yaml", MapFormat::kRondo},
      {"small.tmap", MapFormat::kStrandsTmap},
      {"small_strands.yaml", MapFormat::kStrandsYaml},
      {"small_strands.json", MapFormat::kStrandsJson},
  };
  for (const auto& [file, format] : cases) {
    auto loaded = load_map_file(fixture(file));
    ASSERT_TRUE(loaded.ok()) << file << ": " << loaded.error().message;
    EXPECT_EQ(loaded->format, format) << file;
    EXPECT_STRNE(to_string(format), "unknown");
  }
}

TEST(LoadMap, ImportedFormatsWarnThatTheyHaveNoCapacityOrNarrowEdges) {
  const std::vector<std::pair<std::string, std::string>> cases = {{"small.tmap", "STRANDS"},
                                                                  {"small_strands.yaml", "STRANDS"},
                                                                  {"small_strands.json", "STRANDS"},
                                                                  {"lcas_maps_test.tmap2", "tmap2"},
                                                                  {"lcas_certh_vogui_2sides_policies.tmap2", "tmap2"}};
  for (const auto& [file, format] : cases) {
    auto loaded = load_map_file(fixture(file));
    ASSERT_TRUE(loaded.ok()) << file << ": " << loaded.error().message;
    ASSERT_FALSE(loaded->import_warnings.empty()) << file;
    EXPECT_EQ(loaded->import_warnings.back(),
              format +
                  " maps have no node capacity and no narrow edges: every node holds one robot and robots pass each "
                  "other on every edge (a converted map may add capacity and narrow: docs/map-format.md)")
        << file;
    for (const Node& n : loaded->map.nodes()) EXPECT_EQ(n.capacity, 1) << file;
    for (const Edge& e : loaded->map.edges()) EXPECT_EQ(e.narrow, Narrow::kNone) << file;
  }
  auto own = load_map_file(fixture("traffic.yaml"));
  ASSERT_TRUE(own.ok()) << own.error().message;
  EXPECT_TRUE(own->import_warnings.empty());
}

TEST(LoadMap, RondoFormatAlsoReadsFromJsonAndYml) {
  TempDir dir;
  const auto json_file = dir.path() / "m.json";
  std::ofstream(json_file) << R"({"rondo_map": 1, "nodes": [{"name": "A", "pose": {"x": 1, "y": 2}}]})";
  auto loaded = load_map_file(json_file);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->format, MapFormat::kRondo);
  EXPECT_EQ(loaded->map.node(0).pose, (Pose{1, 2, 0}));

  const auto yml_file = dir.path() / "m.yml";
  std::ofstream(yml_file) << "nodes: [{name: A, pose: {x: 1, y: 2}}]\n";
  ASSERT_TRUE(load_map(yml_file).ok());
}

TEST(LoadMap, ErrorsNameTheFile) {
  struct Case {
    std::filesystem::path file;
    ErrorCode code;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"no/such/map.yaml", ErrorCode::kNotFound, "no/such/map.yaml: no such file"},
      {"map.txt", ErrorCode::kInvalidInput,
       "map.txt: unknown map file type '.txt': expected .yaml, .yml or .tmap2 (rondo, LCAS tmap2 or STRANDS YAML), "
       ".tmap or .json (STRANDS)"},
      {"map", ErrorCode::kInvalidInput,
       "map: unknown map file type '': expected .yaml, .yml or .tmap2 (rondo, LCAS tmap2 or STRANDS YAML), .tmap or "
       ".json (STRANDS)"},
  };
  for (const Case& c : cases) {
    auto map = load_map(c.file);
    ASSERT_FALSE(map.ok()) << c.file;
    EXPECT_EQ(map.error().code, c.code) << c.file;
    EXPECT_EQ(map.error().message, c.expected);
  }
  auto bad = load_map(fixture("unknown_node.yaml"));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message, fixture("unknown_node.yaml").string() + ":9: edges[1].to: no node named 'Lab'");
}

TEST(LoadMap, AFolderIsNotAMap) {
  TempDir dir;
  const auto folder = dir.path() / "maps.yaml";
  std::filesystem::create_directories(folder);
  auto map = load_map(folder);
  ASSERT_FALSE(map.ok());
  EXPECT_EQ(map.error().code, ErrorCode::kInvalidInput);
}

TEST(SaveMap, ReplacesAnExistingFileAndLeavesNoPartialFile) {
  TempDir dir;
  const auto out = dir.path() / "out.yaml";
  std::ofstream(out) << "old contents";
  auto map = load_map(fixture("small.yaml"));
  ASSERT_TRUE(map.ok());
  ASSERT_TRUE(save_map(*map, out).ok());
  EXPECT_EQ(*load_map(out), *map);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out.yaml.partial"));
}

TEST(SaveMap, UnwritablePlaceIsAnIoError) {
  auto map = load_map(fixture("small.yaml"));
  ASSERT_TRUE(map.ok());
  const auto status = save_map(*map, "/nonexistent-folder/out.yaml");
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error().code, ErrorCode::kIo);
  EXPECT_NE(status.error().message.find("/nonexistent-folder/out.yaml"), std::string::npos);
}

}  // namespace
}  // namespace rondo::map
