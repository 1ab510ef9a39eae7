// `rondo map info|check|convert`, run in-process through rondo::app::run.
#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include "app/cli_runner.h"
#include "map_test_support.h"
#include "rondo/core/atomic_file.h"
#include "rondo/core/document.h"
#include "rondo/map/map_loader.h"

namespace rondo::map {
namespace {

using testing::fixture;
using testing::real_map;

using CliRun = rondo::test::CliResult;
using rondo::test::run_cli;

TEST(MapCli, InfoJsonOfTheRealMaps) {
  struct Case {
    std::string file;
    int nodes;
    int edges;
    std::string format;
  };
  const std::vector<Case> cases = {{"tsc_1605.yaml", 67, 232, "strands-yaml"},
                                   {"g4s_y2.tmap", 40, 84, "strands-tmap"},
                                   {"aaf_winter.json", 48, 124, "strands-json"}};
  for (const Case& c : cases) {
    const CliRun r = run_cli({"map", "info", real_map(c.file).string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << c.file << ": " << r.err;
    const Json j = Json::parse(r.out);
    EXPECT_EQ(j["nodes"], c.nodes) << c.file;
    EXPECT_EQ(j["edges"], c.edges) << c.file;
    EXPECT_EQ(j["format"], c.format) << c.file;
    EXPECT_EQ(j["warnings"], Json::array());
    EXPECT_TRUE(j.contains("actions"));
    EXPECT_TRUE(j.contains("doors"));
    EXPECT_TRUE(j.contains("bounding_box_m"));
    EXPECT_TRUE(j.contains("total_edge_length_m"));
  }
}

TEST(MapCli, InfoTableShowsTheEssentials) {
  const CliRun r = run_cli({"map", "info", fixture("office.yaml").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* expected : {"office (rondo,", "nodes      5", "edges      8", "doorPassing", "kitchen_door",
                               "warnings   none", "connected  yes"}) {
    EXPECT_NE(r.out.find(expected), std::string::npos) << expected << "\n" << r.out;
  }
}

TEST(MapCli, CheckValidMapExitsZero) {
  const CliRun r = run_cli({"map", "check", real_map("tsc_1605.yaml").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("valid strands-yaml map, 67 nodes, 232 edges, 1 warning"), std::string::npos) << r.out;
  // The one warning: what a STRANDS map cannot say.
  EXPECT_EQ(r.err,
            "rondo: warning: STRANDS maps have no node capacity and no narrow edges: every node holds one robot and "
            "robots pass each other on every edge (a converted map may add capacity and narrow: "
            "docs/map-format.md)\n");
}

TEST(MapCli, InfoCountsCapacitiesAndNarrowEdges) {
  const CliRun r = run_cli({"map", "info", fixture("traffic.yaml").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("traffic    2 nodes hold more than one robot (up to 4); 4 narrow edges (2 single, 2 one-way)"),
            std::string::npos)
      << r.out;
  const CliRun office = run_cli({"map", "info", fixture("office.yaml").string()});
  EXPECT_NE(office.out.find("traffic    every node holds one robot; no narrow edges"), std::string::npos) << office.out;
  const CliRun j = run_cli({"map", "info", fixture("traffic.yaml").string(), "--json"});
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const Json info = Json::parse(j.out);
  EXPECT_EQ(info["nodes_with_capacity"], 2);
  EXPECT_EQ(info["narrow_edges"]["single"], 2);
  EXPECT_EQ(info["narrow_edges"]["one_way"], 2);
  EXPECT_EQ(info["import_warnings"], Json::array());  // rondo's format says both
}

TEST(MapCli, BadCapacityOrNarrowExitsTwoNamingLineAndField) {
  testing::TempDir dir;
  auto text = read_text_file(fixture("traffic.yaml"));
  ASSERT_TRUE(text.ok());
  for (const auto& [from, to, expected] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"capacity: 4}", "capacity: -1}",
            ":8: nodes[2].capacity: expected a whole number of robots the place holds at once, from 1 to 1000, not -1"},
           {"narrow: one_way}\n  - {from: Ward", "narrow: twoway}\n  - {from: Ward",
            ":15: edges[4].narrow: expected single (one robot at a time) or one_way (one direction at a time)"}}) {
    std::string bad = *text;
    bad.replace(bad.find(from), from.size(), to);
    const auto file = dir.path() / "bad.yaml";
    ASSERT_TRUE(write_file_atomically(file, bad).ok());
    const CliRun r = run_cli({"map", "check", file.string()});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(file.string() + expected), std::string::npos) << r.err;
  }
}

TEST(MapCli, CheckWithWarningsStillExitsZero) {
  const CliRun r = run_cli({"map", "check", fixture("dead_end.yaml").string()});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("3 warnings"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("rondo: warning: node 'Lift' is a dead end"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("rondo: warning: node 'Island' is cut off"), std::string::npos) << r.err;
}

TEST(MapCli, BadInputExitsTwoNamingFileLineAndProblem) {
  struct Case {
    std::vector<std::string> args;
    std::string expected;  // part of stderr
  };
  const std::string unknown = fixture("unknown_node.yaml").string();
  const std::vector<Case> cases = {
      {{"map", "check", unknown}, unknown + ":9: edges[1].to: no node named 'Lab'"},
      {{"map", "info", unknown, "--json"}, unknown + ":9: edges[1].to: no node named 'Lab'"},
      {{"map", "convert", unknown, "-o", "/tmp/never-written.yaml"}, "no node named 'Lab'"},
      {{"map", "check", "missing.yaml"}, "rondo: error: missing.yaml: no such file"},
      {{"map", "check", "map.docx"}, "unknown map file type '.docx'"},
      {{"map", "convert", fixture("small.yaml").string()}, "--output is required"},
      {{"map", "info"}, "file is required"},
      {{"map"}, "A subcommand is required"},
  };
  for (const Case& c : cases) {
    const CliRun r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.expected;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << "expected '" << c.expected << "' in:\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists("/tmp/never-written.yaml"));
}

TEST(MapCli, ConvertWritesAMapThatReadsBackTheSame) {
  const auto out =
      std::filesystem::temp_directory_path() / ("rondo_cli_convert_" + std::to_string(::getpid()) + ".yaml");
  for (const char* file : {"g4s_y2.tmap", "tsc_1605.yaml", "aaf_winter.json"}) {
    const CliRun r = run_cli({"map", "convert", real_map(file).string(), "-o", out.string()});
    ASSERT_EQ(r.exit_code, 0) << file << ": " << r.err;
    EXPECT_NE(r.out.find("wrote " + out.string()), std::string::npos) << r.out;
    auto original = load_map(real_map(file));
    auto converted = load_map_file(out);
    ASSERT_TRUE(converted.ok()) << converted.error().message;
    EXPECT_EQ(converted->format, MapFormat::kRondo);
    EXPECT_EQ(converted->map, *original) << file;
    // Converting the converted file again changes nothing.
    const CliRun again = run_cli({"map", "convert", out.string(), "-o", out.string()});
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(*load_map(out), *original) << file;
  }
  std::filesystem::remove(out);
}

TEST(MapCli, ConvertToStandardOutput) {
  const CliRun r = run_cli({"map", "convert", fixture("small.tmap").string(), "-o", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("# rondo topological map", 0), 0u);
  EXPECT_NE(r.out.find("name: ChargingPoint"), std::string::npos);
}

TEST(MapCli, HelpListsTheMapCommands) {
  const CliRun r = run_cli({"map", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* cmd : {"info", "check", "convert"}) EXPECT_NE(r.out.find(cmd), std::string::npos) << r.out;
}

}  // namespace
}  // namespace rondo::map
