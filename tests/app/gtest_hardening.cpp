// Hostile input on the command line: every loader bounds its work before doing it, and the CLI
// never aborts (issue 14). Each case here failed before its fix.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <new>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "cli_runner.h"
#include "test_files.h"
#include "core/alias_bomb.h"
#include "store/child_process.h"

namespace rondo {
namespace {

using ::testing::HasSubstr;
using test::slurp;

std::filesystem::path fresh_dir(const std::string& name) { return test::fresh_dir("rondo-hardening", name); }

void write(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
}

// A copy of the bundled G4S deployment with one of its files replaced by `text`.
std::filesystem::path g4s_with(const std::filesystem::path& dir, const std::string& file, const std::string& text) {
  for (const auto& entry : std::filesystem::directory_iterator("examples/g4s")) {
    std::filesystem::copy_file(entry.path(), dir / entry.path().filename(),
                               std::filesystem::copy_options::overwrite_existing);
  }
  write(dir / file, text);
  return dir / "deployment.yaml";
}

TEST(Hardening, EveryLoaderRefusesAnAliasBombByCountingIt) {
  const std::string bomb = test::alias_bomb();
  ASSERT_LT(bomb.size(), 1024u);
  struct Case {
    std::string name;
    std::function<std::vector<std::string>(const std::filesystem::path& dir)> args;
  };
  const Case cases[] = {
      {"map",
       [&](const auto& d) {
         write(d / "bomb.yaml", bomb);
         return std::vector<std::string>{"map", "info", (d / "bomb.yaml").string()};
       }},
      {"map convert",
       [&](const auto& d) {
         write(d / "bomb.yaml", bomb);
         return std::vector<std::string>{"map", "convert", (d / "bomb.yaml").string(), "-o", (d / "out.yaml").string()};
       }},
      {"task file",
       [&](const auto& d) {
         write(d / "bomb.yaml", bomb);
         return std::vector<std::string>{"task", "check", (d / "bomb.yaml").string()};
       }},
      {"task expand",
       [&](const auto& d) {
         write(d / "bomb.yaml", bomb);
         return std::vector<std::string>{"task", "expand", (d / "bomb.yaml").string(), "--from", "2026-03-02"};
       }},
      {"problem file",
       [&](const auto& d) {
         write(d / "bomb.yaml", bomb);
         return std::vector<std::string>{"schedule", (d / "bomb.yaml").string()};
       }},
      {"deployment",
       [&](const auto& d) {
         return std::vector<std::string>{
             "run", g4s_with(d, "deployment.yaml", bomb).string(), "--days", "1", "--out", (d / "run").string()};
       }},
      {"deployment map",
       [&](const auto& d) {
         return std::vector<std::string>{
             "run", g4s_with(d, "map.yaml", bomb).string(), "--days", "1", "--out", (d / "run").string()};
       }},
      {"routines",
       [&](const auto& d) {
         return std::vector<std::string>{
             "run", g4s_with(d, "routines.yaml", bomb).string(), "--days", "1", "--out", (d / "run").string()};
       }},
      {"world",
       [&](const auto& d) {
         return std::vector<std::string>{
             "run", g4s_with(d, "world.yaml", bomb).string(), "--days", "1", "--out", (d / "run").string()};
       }},
      {"requests",
       [&](const auto& d) {
         return std::vector<std::string>{
             "run", g4s_with(d, "requests.yaml", bomb).string(), "--days", "1", "--out", (d / "run").string()};
       }},
  };
  for (const auto& c : cases) {
    const auto dir = fresh_dir("bomb");
    const auto r = test::run_cli(c.args(dir));
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(test::kAliasBombLimit)) << c.name;
    EXPECT_THAT(r.err, HasSubstr(".yaml:")) << c.name;  // the file, and the line
  }
  std::filesystem::remove_all(fresh_dir("bomb").parent_path());
}

TEST(Hardening, TheGuardTurnsEveryExceptionIntoExitOne) {
  struct Case {
    std::string name;
    std::function<int()> body;
    std::string expect;
  };
  const Case cases[] = {
      {"bad_alloc", []() -> int { throw std::bad_alloc(); }, "rondo: error: out of memory"},
      {"std::exception", []() -> int { throw std::runtime_error("boom"); }, "rondo: internal error: boom"},
      {"anything else", []() -> int { throw 42; }, "rondo: internal error: unknown exception"},
      {"no exception", [] { return 2; }, ""},
  };
  for (const auto& c : cases) {
    std::ostringstream err;
    const int code = app::run_guarded(c.body, err);
    EXPECT_EQ(code, c.expect.empty() ? 2 : 1) << c.name;
    EXPECT_THAT(err.str(), HasSubstr(c.expect)) << c.name;
  }
}

TEST(Hardening, AnExceptionOnAnotherThreadExitsOneInsteadOfAborting) {
  const auto end = store::testing::run_in_child([] {
    app::install_terminate_handler();
    std::thread([] { throw std::bad_alloc(); }).join();
  });
  EXPECT_TRUE(end.exited_with(1)) << end.status;
  EXPECT_FALSE(end.killed_by(SIGABRT));
}

// A TSPTW file with `n` nodes, `matrix` as its weight section and `windows` as its windows.
std::string tsptw(const std::string& dimension, const std::string& matrix, const std::string& windows) {
  return "NAME : t\nTYPE : TSPTW\nDIMENSION : " + dimension +
         "\nEDGE_WEIGHT_TYPE : EXPLICIT\nEDGE_WEIGHT_FORMAT : FULL_MATRIX\nEDGE_WEIGHT_SECTION\n" + matrix +
         "\nTIME_WINDOW_SECTION\n" + windows + "\nDEPOT_SECTION\n1\n-1\nEOF\n";
}

TEST(Hardening, NumbersAreCheckedNotClampedOrOverflowed) {
  struct Case {
    std::string name;
    std::string file;  // written to a .tsptw or .yaml file by its first line
    std::vector<std::string> extra;
    std::string expect;
  };
  const std::string ok2 = tsptw("2", "0 5\n5 0", "1 0 100\n2 0 100");
  const std::string problem =
      "locations: [dock, A]\ntravel: [[0, 60], [60, 0]]\nrobot: {location: dock, time: 0}\n"
      "tasks:\n  - {id: a, release: 0, deadline: DEADLINE, start: A, priority: PRIORITY}\n";
  const auto with = [&](std::string text, const std::string& key, const std::string& value) {
    text.replace(text.find(key), key.size(), value);
    return text;
  };
  const Case cases[] = {
      {"DIMENSION past the bytes present",
       tsptw("90000", "0 1\n1 0", "1 0 10"),
       {},
       "DIMENSION 90000 needs 8100000000 entries"},
      {"TSPTW window near 1e16",
       tsptw("2", "0 5\n5 0", "1 0 10000000000000000\n2 0 100"),
       {},
       "10000000000000000 is out of range"},
      {"TSPTW weight near 1e16",
       tsptw("2", "0 9999999999999999\n5 0", "1 0 100\n2 0 100"),
       {},
       "is out of range (at most 1000000000 seconds)"},
      {"--time-limit nan", ok2, {"--time-limit", "nan"}, "--time-limit: must be a number of seconds"},
      {"--time-limit inf", ok2, {"--time-limit", "inf"}, "--time-limit"},
      {"--time-limit a year", ok2, {"--time-limit", "31536000"}, "--time-limit: must be a number of seconds"},
      {"--seed -1", ok2, {"--seed", "-1"}, "--seed: '-1' is not a whole number from 0 to 9223372036854775807"},
      {"problem time 1e300",
       "#yaml\n" + with(with(problem, "DEADLINE", "1e300"), "PRIORITY", "0"),
       {},
       "tasks[0].deadline: 1e+300 seconds is out of range"},
      {"problem priority out of range",
       "#yaml\n" + with(with(problem, "DEADLINE", "600"), "PRIORITY", "5000000000"),
       {},
       "tasks[0].priority: must be from -1000000 to 1000000"},
  };
  const auto dir = fresh_dir("numbers");
  for (const auto& c : cases) {
    const bool yaml = c.file.starts_with("#yaml");
    const auto file = dir / (yaml ? "p.yaml" : "t.tsptw");
    write(file, c.file);
    std::vector<std::string> args = yaml ? std::vector<std::string>{"schedule", file.string()}
                                         : std::vector<std::string>{"schedule", "--tsptw", file.string()};
    args.insert(args.end(), c.extra.begin(), c.extra.end());
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err << r.out;
    EXPECT_THAT(r.err, HasSubstr(c.expect)) << c.name;
  }
  // The same small instance within the limits solves.
  write(dir / "ok.tsptw", ok2);
  EXPECT_EQ(test::run_cli({"schedule", "--tsptw", (dir / "ok.tsptw").string(), "--time-limit", "1"}).exit_code, 0);
  std::filesystem::remove_all(dir.parent_path());
}

TEST(Hardening, MapConvertWritesOnlyWhatTheNameSaysAndKeepsTheOldFileOnFailure) {
  const auto dir = fresh_dir("convert");
  const std::string old = "an existing file that a failed convert must leave alone\n";
  struct Case {
    std::string name;
    std::string input;   // a map file (written as in.yaml) or a path
    std::string output;  // file name in dir
  };
  write(dir / "bomb.yaml", test::alias_bomb());
  write(dir / "broken.yaml", "nodes: [\n");
  const Case cases[] = {
      {"a .json name", "tests/data/maps/small.yaml", "out.json"},
      {"a .tmap name", "tests/data/maps/small.yaml", "out.tmap"},
      {"no extension", "tests/data/maps/small.yaml", "out"},
      {"an alias bomb", (dir / "bomb.yaml").string(), "out.yaml"},
      {"a broken map", (dir / "broken.yaml").string(), "out.yaml"},
  };
  for (const auto& c : cases) {
    write(dir / c.output, old);
    const auto r = test::run_cli({"map", "convert", c.input, "-o", (dir / c.output).string()});
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
    EXPECT_EQ(slurp(dir / c.output), old) << c.name;
  }
  // A good convert replaces the old file whole, and leaves no temporary file beside it.
  write(dir / "out.yaml", old);
  const auto r = test::run_cli({"map", "convert", "tests/data/maps/small.yaml", "-o", (dir / "out.yaml").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(slurp(dir / "out.yaml"), HasSubstr("nodes:"));
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  std::filesystem::remove_all(dir.parent_path());
}

TEST(Hardening, AFailedLearnLeavesTheModelsFileAsItWas) {
  const auto dir = fresh_dir("learn");
  const std::string old = "{\"old\": \"models\"}\n";
  write(dir / "models.json", old);
  write(dir / "empty.db", "");
  struct Case {
    std::string name;
    std::vector<std::string> args;
  };
  const Case cases[] = {
      {"missing database", {"learn", "--db", (dir / "none.db").string(), "-o", (dir / "models.json").string()}},
      {"empty database", {"learn", "--db", (dir / "empty.db").string(), "-o", (dir / "models.json").string()}},
      {"bad zone",
       {"learn", "--db", (dir / "empty.db").string(), "--zone", "Mars/Olympus", "-o", (dir / "models.json").string()}},
  };
  for (const auto& c : cases) {
    const auto r = test::run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
    EXPECT_EQ(slurp(dir / "models.json"), old) << c.name;
  }
  EXPECT_EQ(slurp(dir / "empty.db"), "");  // and the read-only open did not make it a store
  std::filesystem::remove_all(dir.parent_path());
}

// Every numeric option of every command: a number out of its range, past its type's (CLI11 clamped
// --seed 99999999999999999999 to 9223372036854775807 and the run went ahead), negative, zero where
// that means nothing, NaN or not written in decimal is refused with exit 2 before anything runs,
// and the message names the option.
TEST(Hardening, EveryNumericOptionRefusesWhatItCannotMean) {
  const auto dir = fresh_dir("options");
  const std::string out = (dir / "run").string();
  const std::string g4s = "examples/g4s/deployment.yaml";
  const std::string tasks = "tests/data/tasks/office_day.yaml";
  const std::string witham = "../shared/data/witham_wharf";
  write(dir / "ok.tsptw", tsptw("2", "0 5\n5 0", "1 0 100\n2 0 100"));
  const std::string tsptw_file = (dir / "ok.tsptw").string();
  // The other options of each command are small and valid: were the bad one let through, the job
  // would be short.
  // The command, then the bad option and its value, then the command's other options except that one.
  const auto with = [](std::vector<std::string> command, const std::vector<std::string>& bad,
                       const std::vector<std::pair<std::string, std::string>>& others) {
    command.insert(command.end(), bad.begin(), bad.end());
    for (const auto& [option, value] : others)
      if (option != bad[0]) command.insert(command.end(), {option, value});
    return command;
  };
  const auto run = [&](const std::vector<std::string>& bad) {
    return with({"run", g4s}, bad, {{"--days", "1"}, {"--out", out}});
  };
  const auto robustness = [&](const std::vector<std::string>& bad) {
    return with({"eval", "robustness", g4s}, bad,
                {{"--days", "1"}, {"--seeds", "1"}, {"--alphas", "0.2"}, {"--variants", "expected"}, {"--jobs", "1"}});
  };
  const auto edges = [&](const std::vector<std::string>& bad) {
    return with({"eval", "edges"}, bad, {{"--witham", witham}, {"--split", "2014-08-01T00:00:00Z"}});
  };
  const auto plan = [&](const std::vector<std::string>& bad) {
    return with({"plan"}, bad, {{"--map", "tests/data/maps/small.yaml"}, {"--from", "A"}, {"--to", "B"}});
  };
  struct Case {
    std::vector<std::string> args;
    std::string expect;  // in the message
  };
  const Case cases[] = {
      {run({"--seed", "99999999999999999999"}), "--seed: '99999999999999999999' is not a whole number from 0 to"},
      {run({"--seed", "9223372036854775808"}), "--seed: '9223372036854775808'"},
      {run({"--seed", "-1"}), "--seed: '-1'"},
      {run({"--seed", "1.5"}), "--seed: '1.5'"},
      {run({"--seed", "0x10"}), "--seed: '0x10'"},
      {run({"--seed", ""}), "--seed"},
      {run({"--days", "99999999999999999999"}), "--days: '99999999999999999999' is not a whole number from 1 to 3660"},
      {run({"--days", "4294967297"}), "--days: '4294967297'"},
      {run({"--days", "-3"}), "--days: '-3'"},
      {run({"--days", "0"}), "--days: '0'"},
      {run({"--days", "3661"}), "--days: '3661'"},
      {run({"--speed", "0"}), "--speed"},
      {run({"--speed", "-2"}), "--speed"},
      {run({"--speed", "nan"}), "--speed"},
      {run({"--speed", "1e400"}), "--speed"},
      {run({"--for", "-5m"}), "--for"},
      {run({"--for", "0s"}), "--for"},
      {{"schedule", "--tsptw", tsptw_file, "--seed", "99999999999999999999"}, "--seed: '99999999999999999999'"},
      {{"schedule", "--tsptw", tsptw_file, "--seed", "-1"}, "--seed: '-1'"},
      {{"schedule", "--tsptw", tsptw_file, "--time-limit", "-1"}, "--time-limit"},
      {{"schedule", "--tsptw", tsptw_file, "--time-limit", "0"}, "--time-limit"},
      {{"serve", g4s, "--streams", "99999999999999999999"}, "--streams: '99999999999999999999'"},
      {{"serve", g4s, "--streams", "0"}, "--streams: '0'"},
      {{"serve", g4s, "--streams", "-1"}, "--streams: '-1'"},
      {{"serve", g4s, "--speed", "0"}, "--speed"},
      {{"serve", g4s, "--speed", "-1"}, "--speed"},
      {{"serve", g4s, "--speed", "nan"}, "--speed"},
      {{"serve", g4s, "--listen", "127.0.0.1:99999999999999999999"}, "--listen"},
      {{"task", "expand", tasks, "--from", "2026-11-23", "--days", "-3"}, "--days: '-3'"},
      {{"task", "expand", tasks, "--from", "2026-11-23", "--days", "99999999999999999999"}, "--days"},
      {{"task", "expand", tasks, "--from", "2026-11-23", "--days", "0x10"}, "--days: '0x10'"},
      {edges({"--min-train", "99999999999999999999"}), "--min-train: '99999999999999999999'"},
      {edges({"--min-test", "-5"}), "--min-test: '-5'"},
      {edges({"--min-test", "2.5"}), "--min-test: '2.5'"},
      {robustness({"--seeds", "9223372036854775808"}), "--seeds"},
      {robustness({"--seeds", "9223372036854775807-9223372036854775808"}), "--seeds"},
      {robustness({"--seeds", "1,-2"}), "--seeds"},
      {robustness({"--days", "-3"}), "--days: '-3'"},
      {robustness({"--days", "99999999999999999999"}), "--days"},
      {robustness({"--jobs", "0"}), "--jobs: '0'"},
      {robustness({"--jobs", "99999999999999999999"}), "--jobs"},
      {robustness({"--alphas", "nan"}), "--alphas"},
      {robustness({"--navigation-alphas", "-0.1"}), "--navigation-alphas"},
      {robustness({"--route-thresholds", "-30"}), "--route-thresholds"},
      {plan({"--prior-probability", "0"}), "--prior-probability"},
      {plan({"--prior-probability", "nan"}), "--prior-probability"},
      {plan({"--prior-probability", "-1"}), "--prior-probability"},
      {{"log", "archive", "--db", (dir / "none.db").string(), "--older-than", "99999999999999999999d", "--out",
        (dir / "a.db").string()},
       "--older-than"},
      {{"log", "archive", "--db", (dir / "none.db").string(), "--older-than", "200000000d", "--out",
        (dir / "a.db").string()},
       "--older-than: '200000000d' is not a number of days from 0 to"},
      {{"log", "archive", "--db", (dir / "none.db").string(), "--older-than", "-90d", "--out", (dir / "a.db").string()},
       "--older-than"},
  };
  for (const Case& c : cases) {
    std::string line;
    for (const auto& a : c.args) line += a + " ";
    const auto r = test::run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << line << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.expect)) << line;
    EXPECT_FALSE(std::filesystem::exists(out)) << line;  // nothing ran
    std::filesystem::remove_all(out);
  }
  // A leading zero is decimal, not octal: ten days are ten days.
  const auto expand = [&](const std::string& days) {
    return test::run_cli({"task", "expand", tasks, "--from", "2026-11-23", "--days", days, "--json"});
  };
  const auto ten = expand("10");
  ASSERT_EQ(ten.exit_code, 0) << ten.err;
  EXPECT_EQ(expand("010").out, ten.out);
}

TEST(Hardening, OutOfRangeCountsOnTheCommandLineAreRefused) {
  const std::vector<std::string> base = {
      "eval", "edges", "--witham", "../shared/data/witham_wharf", "--split", "2014-08-01T00:00:00Z"};
  for (const char* option : {"--min-train", "--min-test"}) {
    auto args = base;
    args.insert(args.end(), {option, "-5"});
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << option << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(option)) << r.err;
  }
}

}  // namespace
}  // namespace rondo
