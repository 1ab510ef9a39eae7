#include <gtest/gtest.h>

#include "app/cli_runner.h"

namespace rondo {
namespace {

using test::run_cli;

TEST(Cli, HelpListsTheCommandsAndExitsZero) {
  auto r = run_cli({"--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* cmd : {"map", "task", "log"}) EXPECT_NE(r.out.find(cmd), std::string::npos) << cmd;
}

TEST(Cli, VersionPrintsTheVersion) {
  auto r = run_cli({"--version"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out.rfind("rondo ", 0), 0u);
}

TEST(Cli, UsageErrorsAreBadInput) {
  for (const auto& args : std::vector<std::vector<std::string>>{{}, {"frobnicate"}, {"task", "check"}, {"--nope"}}) {
    auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("rondo: error:"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace rondo
