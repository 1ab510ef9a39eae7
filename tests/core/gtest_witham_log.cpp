#include <gtest/gtest.h>

#include <fstream>

#include "rondo/core/traversal.h"

namespace rondo {
namespace {

namespace fs = std::filesystem;

const fs::path kWitham = "../shared/data/witham_wharf";

TEST(WithamLog, ReadsAllAttemptsOfTheRealLogs) {
  auto all = read_witham_logs(kWitham);
  ASSERT_TRUE(all.ok()) << all.error().message;
  EXPECT_EQ(all->size(), 32078u);
  std::size_t successes = 0;
  for (const auto& t : *all) successes += t.success ? 1 : 0;
  EXPECT_EQ(successes, 21916u);
  EXPECT_TRUE(std::is_sorted(all->begin(), all->end(),
                             [](const Traversal& a, const Traversal& b) { return a.start < b.start; }));
  const auto& first = all->front();
  EXPECT_EQ(first.edge_id, first.from + "_" + first.to);
  EXPECT_EQ(first.origin.rfind("witham:", 0), 0u);
}

TEST(WithamLog, MalformedLinesNameFileAndLine) {
  const fs::path dir = fs::temp_directory_path() / ("rondo_witham_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(dir);
  struct Case {
    const char* file;
    const char* text;
    const char* expect;
  };
  const Case cases[] = {
      {"A_B.data", "1404842483 67.6 0\n1404842551 ten 1\n", "A_B.data:2: duration 'ten'"},
      {"A_B.data", "1404842483 67.6 2\n", "A_B.data:1: success flag '2' must be 0 or 1"},
      {"A_B.data", "1404842483 67.6\n", "A_B.data:1: expected 'unix_time duration_seconds success(0|1)'"},
      {"A_B.data", "1404842483 67.6 1 extra\n", "A_B.data:1: expected"},
      {"A_B.data", "-5 1 1\n", "A_B.data:1: start time '-5'"},
      {"AB.data", "1404842483 67.6 1\n", "AB.data: file name must be <From>_<To>.data"},
  };
  for (const auto& c : cases) {
    const fs::path file = dir / c.file;
    std::ofstream(file) << c.text;
    auto r = read_witham_edge_log(file);
    ASSERT_FALSE(r.ok()) << c.text;
    EXPECT_NE(r.error().message.find(c.expect), std::string::npos) << r.error().message;
    fs::remove(file);
  }
  EXPECT_EQ(read_witham_logs(dir).error().code, ErrorCode::kInvalidInput);  // no .data files
  EXPECT_EQ(read_witham_logs(dir / "missing").error().code, ErrorCode::kNotFound);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rondo
