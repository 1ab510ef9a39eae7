#include "rondo/store/observations.h"

#include <gtest/gtest.h>

#include <limits>

#include "store/store_backends.h"

namespace rondo::store {
namespace {


Time at(int s) {
  return Time{seconds(s)};
}

class Observations : public testing::BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    if (HasFatalFailure()) return;
    auto opened = temp().open();
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    db_.emplace(std::move(*opened));
  }
  Store& db() { return *db_; }

  std::optional<Store> db_;
};

TEST_P(Observations, RoundTripWithAndWithoutText) {
  const Observation door{"door_open", "door_A110", at(100), 1.0, std::nullopt};
  const Observation load{"load_time", "A-114", at(50), 37.25, "the librarian, green book"};
  auto first = add_observation(db(), door);
  auto second = add_observation(db(), load);
  ASSERT_TRUE(first.ok()) << first.error().message;
  ASSERT_TRUE(second.ok());
  EXPECT_LT(*first, *second);
  auto all = find_observations(db());
  ASSERT_TRUE(all.ok()) << all.error().message;
  EXPECT_EQ(*all, (std::vector<Observation>{load, door}));  // by time
}

TEST_P(Observations, Queries) {
  const Observation rows[] = {
      {"door_open", "door_A", at(10), 1, {}},
      {"door_open", "door_B", at(20), 0, {}},
      {"door_open", "door_A", at(30), 0, {}},
      {"person_present", "door_A", at(25), 1, {}},
  };
  for (const auto& o : rows) ASSERT_TRUE(add_observation(db(), o).ok());
  struct Case {
    const char* name;
    ObservationQuery query;
    std::vector<int> times;
  };
  const Case cases[] = {
      {"all", {}, {10, 20, 25, 30}},
      {"what", {.what = "door_open"}, {10, 20, 30}},
      {"where", {.where = "door_A"}, {10, 25, 30}},
      {"what and where", {.what = "door_open", .where = "door_A"}, {10, 30}},
      {"range", {.from = at(20), .until = at(30)}, {20, 25}},
      {"nothing", {.what = "smoke"}, {}},
  };
  for (const Case& c : cases) {
    auto found = find_observations(db(), c.query);
    ASSERT_TRUE(found.ok()) << c.name;
    std::vector<int> times;
    for (const auto& o : *found) times.push_back(static_cast<int>(to_unix_seconds(o.when)));
    EXPECT_EQ(times, c.times) << c.name;
  }
}

TEST_P(Observations, RefusesAValueThatIsNotANumber) {
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    auto id = add_observation(db(), {"door_open", "door_A", at(1), bad, {}});
    ASSERT_FALSE(id.ok());
    EXPECT_EQ(id.error().code, ErrorCode::kInvalidInput);
  }
  EXPECT_TRUE(find_observations(db())->empty());
}

RONDO_ON_BOTH_BACKENDS(Observations);

}  // namespace
}  // namespace rondo::store
