// `rondo map info|check|convert` on LCAS tmap2 files, run in-process through rondo::app::run.
#include <gtest/gtest.h>

#include <fstream>

#include "app/cli_runner.h"
#include "map_test_support.h"
#include "rondo/map/map_loader.h"

namespace rondo::map {
namespace {

using testing::fixture;
using testing::TempDir;

using CliRun = rondo::test::CliResult;
using rondo::test::run_cli;

void copy_to(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::filesystem::copy_file(from, to, std::filesystem::copy_options::overwrite_existing);
}

struct Tmap2File {
  std::string file;
  int nodes;
  int edges;
  std::size_t import_warnings;
};

// Each has one warning more than its restrictions: tmap2 has no node capacity or narrow edges.
const std::vector<Tmap2File> kFiles = {{"lcas_tests_conf_test.tmap2", 2, 2, 1},
                                       {"lcas_maps_test.tmap2", 6, 12, 1},
                                       {"lcas_maps_test_2021.tmap2", 4, 8, 1},
                                       {"lcas_certh_vogui_2sides_policies.tmap2", 24, 52, 3}};

TEST(Tmap2Cli, InfoJsonOfTheRealFiles) {
  for (const Tmap2File& c : kFiles) {
    const CliRun r = run_cli({"map", "info", fixture(c.file).string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << c.file << ": " << r.err;
    const Json j = Json::parse(r.out);
    EXPECT_EQ(j["format"], "tmap2") << c.file;
    EXPECT_EQ(j["nodes"], c.nodes) << c.file;
    EXPECT_EQ(j["edges"], c.edges) << c.file;
    EXPECT_EQ(j["import_warnings"].size(), c.import_warnings) << c.file;
  }
}

TEST(Tmap2Cli, InfoOfAYamlNamedTmap2File) {
  // Before tmap2 was read, this failed with "unknown field 'meta'" (read as rondo's format).
  TempDir dir;
  const auto file = dir.path() / "site.yaml";
  copy_to(fixture("lcas_maps_test.tmap2"), file);
  const CliRun r = run_cli({"map", "info", file.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("test (tmap2, " + file.string() + ")"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("nodes      6"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
}

TEST(Tmap2Cli, CheckPrintsTheRestrictionsItDoesNotApply) {
  const CliRun r = run_cli({"map", "check", fixture("lcas_certh_vogui_2sides_policies.tmap2").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("valid tmap2 map, 24 nodes, 52 edges"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("rondo: warning: restrictions_planning 'allowedside_a' on 10 nodes"), std::string::npos)
      << r.err;
}

TEST(Tmap2Cli, InfoTableListsTheRestrictionsAmongTheWarnings) {
  const CliRun r = run_cli({"map", "info", fixture("lcas_certh_vogui_2sides_policies.tmap2").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("warnings   restrictions_planning 'allowedside_a' on 10 nodes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n           restrictions_planning '~allowedside_a' on 10 nodes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("row_change/move_base  4"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
}

TEST(Tmap2Cli, ConvertWritesAMapThatReadsBackTheSame) {
  TempDir dir;
  const auto out = dir.path() / "converted.yaml";
  for (const Tmap2File& c : kFiles) {
    const CliRun r = run_cli({"map", "convert", fixture(c.file).string(), "-o", out.string()});
    ASSERT_EQ(r.exit_code, 0) << c.file << ": " << r.err;
    EXPECT_NE(r.out.find("(from tmap2 "), std::string::npos) << r.out;
    auto original = load_map_file(fixture(c.file));
    auto converted = load_map_file(out);
    ASSERT_TRUE(original.ok()) << original.error().message;
    ASSERT_TRUE(converted.ok()) << converted.error().message;
    EXPECT_EQ(converted->format, MapFormat::kRondo);
    // Same nodes (names, poses, tolerances, influence, meta) and edges (ids, ends, actions,
    // speeds, doors), in the same order.
    EXPECT_EQ(converted->map, original->map) << c.file;
    EXPECT_EQ(converted->map.edge_count(), static_cast<std::size_t>(c.edges)) << c.file;
  }
  // The speeds of the 2021 form come through the conversion.
  run_cli({"map", "convert", fixture("lcas_maps_test_2021.tmap2").string(), "-o", out.string()});
  auto converted = load_map(out);
  ASSERT_TRUE(converted.ok()) << converted.error().message;
  for (const Edge& e : converted->edges()) EXPECT_EQ(e.top_speed, 0.55) << e.id;
}

TEST(Tmap2Cli, BadFileExitsTwoNamingFileLineAndFieldAndWritesNothing) {
  TempDir dir;
  const auto bad = dir.path() / "bad.tmap2";
  std::string text = *read_text_file(fixture("lcas_tests_conf_test.tmap2"));
  const std::string target = "      node: WayPoint1\n";
  ASSERT_NE(text.find(target), std::string::npos);
  text.replace(text.find(target), target.size(), "      node: WayPoint9\n");
  std::ofstream(bad, std::ios::binary) << text;
  const auto out = dir.path() / "out.yaml";
  std::ofstream(out, std::ios::binary) << "previous\n";
  const std::string expected =
      bad.string() + ":79: nodes[1].node.edges[0].node: edge 'WayPoint2_WayPoint1': no node named 'WayPoint9'";
  for (const char* cmd : {"info", "check", "convert"}) {
    std::vector<std::string> args = {"map", cmd, bad.string()};
    if (std::string(cmd) == "convert") args.insert(args.end(), {"-o", out.string()});
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << cmd;
    EXPECT_NE(r.err.find(expected), std::string::npos) << cmd << ": " << r.err;
  }
  EXPECT_EQ(*read_text_file(out), "previous\n");
}

}  // namespace
}  // namespace rondo::map
