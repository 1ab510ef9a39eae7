// Naming the store: a deployment's `store:`, `rondo serve --store`, `rondo task add --store` and
// `--db` with a PostgreSQL URL. What is checked here needs no server: bad names are refused with
// exit 2 before anything runs, a password never comes from the command line (and is not echoed),
// and a server that is not there is a clear error, not a hang. (The store itself on PostgreSQL:
// tests/store.)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.h"
#include "deployment.h"
#include "test_files.h"

namespace rondo {
namespace {

using test::run_cli;
using test::slurp;
using ::testing::HasSubstr;
using ::testing::Not;

// The G4S example's deployment with `extra` appended, in a fresh folder beside copies of its files.
std::filesystem::path example_with(const std::string& name, const std::string& extra) {
  const auto dir = test::fresh_dir("rondo-store-option", name);
  for (const char* f : {"deployment.yaml", "map.yaml", "routines.yaml", "world.yaml", "requests.yaml"})
    std::filesystem::copy_file(std::filesystem::path("examples/g4s") / f, dir / f);
  std::ofstream(dir / "deployment.yaml", std::ios::app) << "\n" << extra << "\n";
  return dir / "deployment.yaml";
}

TEST(DeploymentStore, NoStoreMeansTheDataFolder) {
  const auto d = app::load_deployment("examples/g4s/deployment.yaml");
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_FALSE(d->store.has_value());
}

TEST(DeploymentStore, PathsAreRelativeToTheDeploymentFile) {
  const auto file = example_with("sqlite", "store: {kind: sqlite, file: fleet.sqlite}");
  const auto d = app::load_deployment(file);
  ASSERT_TRUE(d.ok()) << d.error().message;
  ASSERT_TRUE(d->store.has_value());
  EXPECT_EQ(d->store->kind, store::StoreLocation::Kind::kSqlite);
  EXPECT_EQ(d->store->file, file.parent_path() / "fleet.sqlite");

  const auto pg = app::load_deployment(example_with(
      "pg", "store: {kind: postgresql, url: \"postgresql://rondo@db.example/fleet\", password_file: secret/pw}"));
  ASSERT_TRUE(pg.ok()) << pg.error().message;
  EXPECT_EQ(pg->store->kind, store::StoreLocation::Kind::kPostgres);
  EXPECT_EQ(pg->store->url, "postgresql://rondo@db.example/fleet");
  EXPECT_EQ(pg->store->password_file, file.parent_path().parent_path() / "pg" / "secret" / "pw");
}

TEST(DeploymentStore, BadStoresAreRefusedNamingTheLine) {
  struct Case {
    const char* name;
    const char* yaml;
    const char* says;
  };
  const Case cases[] = {
      {"kind", "store: {kind: mysql, url: x}", "'mysql' is not a store kind"},
      {"key", "store: {kind: sqlite, file: a.sqlite, url: b}", "url"},
      {"malformed", "store: {kind: postgresql, url: \"postgresql://db/fleet?no_such_option=1\"}", "no_such_option"},
      {"password", "store: {kind: postgresql, url: \"postgresql://rondo:hunter2@db/fleet\"}", "password"},
  };
  for (const Case& c : cases) {
    const auto file = example_with(c.name, c.yaml);
    const auto d = app::load_deployment(file);
    ASSERT_FALSE(d.ok()) << c.name;
    EXPECT_EQ(d.error().code, ErrorCode::kInvalidInput) << c.name;
    EXPECT_THAT(d.error().message, HasSubstr(c.says)) << c.name;
    EXPECT_THAT(d.error().message, HasSubstr("deployment.yaml:")) << c.name << ": names the file and line";
    EXPECT_THAT(d.error().message, Not(HasSubstr("hunter2"))) << c.name;
  }
}

TEST(StoreOption, APasswordOnTheCommandLineIsRefusedAndNotEchoed) {
  const std::string url = "postgresql://rondo:hunter2@127.0.0.1:1/fleet";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"serve", "--store", url, "--listen", "127.0.0.1:0"},
        std::vector<std::string>{"task", "add", "check A-123", "--map", "examples/office/map.yaml", "--time-zone", "UTC",
                                 "--store", url},
        std::vector<std::string>{"log", "stats", "--db", url}}) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args[0] << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr("password")) << args[0];
    EXPECT_THAT(r.err + r.out, Not(HasSubstr("hunter2"))) << args[0];
  }
}

// Port 1 on loopback: nothing listens there, so the connection is refused at once.
TEST(StoreOption, AServerThatIsNotThereIsExitCode2NamingTheUrl) {
  const std::string url = "postgresql://rondo@127.0.0.1:1/fleet?connect_timeout=3";
  const auto began = std::chrono::steady_clock::now();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"task", "add", "check A-123", "--map", "examples/office/map.yaml", "--time-zone", "UTC",
                                 "--store", url},
        std::vector<std::string>{"log", "stats", "--db", url},
        std::vector<std::string>{"serve", "--store", url, "--listen", "127.0.0.1:0"}}) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args[0] << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(url)) << args[0];
    EXPECT_THAT(r.err, HasSubstr("cannot connect")) << args[0];
  }
  EXPECT_LT(std::chrono::steady_clock::now() - began, std::chrono::seconds(20));
}

TEST(StoreOption, TaskAddTakesDataOrStoreNotBoth) {
  const auto r = run_cli({"task", "add", "check A-123", "--map", "examples/office/map.yaml", "--data", "x", "--store",
                          "postgresql://db/fleet"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("excludes")) << r.err;
}

}  // namespace
}  // namespace rondo
