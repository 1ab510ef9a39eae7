// Shared by the rondo::map tests: where the fixtures live and a quick way to build small maps.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "rondo/map/topo_map.h"
#include "source_dir.h"

namespace rondo::map::testing {

// tests/data/maps of this project.
inline std::filesystem::path fixture(const std::string& name) {
  return rondo::testing::source_dir() / "tests" / "data" / "maps" / name;
}
// The real STRANDS maps, read in place beside the project.
inline std::filesystem::path real_map(const std::string& name) {
  return rondo::testing::source_dir() / ".." / "shared" / "data" / "maps" / name;
}

// A fresh folder under the system temp folder, removed at the end of the test.
class TempDir {
 public:
  TempDir() : path_(std::filesystem::temp_directory_path() / ("rondo_map_test_" + unique())) {
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  static std::string unique() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name() + "_" + std::to_string(::getpid());
    std::replace(name.begin(), name.end(), '/', '_');  // parameterised tests: Prefix/Suite, Test/Param
    return name;
  }
  std::filesystem::path path_;
};

inline Node node_at(std::string name, double x, double y, double yaw = 0) {
  Node n;
  n.name = std::move(name);
  n.pose = {x, y, yaw};
  return n;
}

inline Edge edge(std::string from, std::string to, std::string action = "move_base") {
  Edge e;
  e.id = from + "_" + to;
  e.from = std::move(from);
  e.to = std::move(to);
  e.action = std::move(action);
  return e;
}

// A map that must build; fails the test (and returns an empty map) otherwise.
inline TopoMap build_or_fail(std::vector<Node> nodes, std::vector<Edge> edges, std::string name = "test") {
  auto map = TopoMap::build(std::move(name), std::move(nodes), std::move(edges));
  EXPECT_TRUE(map.ok()) << (map.ok() ? "" : map.error().message);
  return map.ok() ? *map : TopoMap{};
}

}  // namespace rondo::map::testing
