#include "rondo/store/robot_state.h"

#include <gtest/gtest.h>

#include <cmath>

#include "store/store_backends.h"

namespace rondo::store {
namespace {


class RobotStates : public testing::BackendTest {};
class Meta : public testing::BackendTest {};

TEST_P(RobotStates, IsSavedReplacedAndReadBackAfterReopening) {
  {
    auto db = temp().open().value();
    EXPECT_FALSE(load_robot_state(db, "r1").value().has_value());
    ASSERT_TRUE(save_robot_state(db, {.robot = "r1", .node = "Hall", .updated = Time{seconds(5)}}).ok());
    const RobotState later{.robot = "r1", .node = "Office", .x = 2.0, .y = -1.5, .yaw = 0.25, .battery = 0.75,
                           .on_board = Json::array({"red letter"}), .fault = "bumper", .updated = Time{seconds(9)}};
    ASSERT_TRUE(save_robot_state(db, later).ok());
  }
  auto db = temp().open({.mode = OpenMode::kMustExist}).value();
  const auto back = load_robot_state(db, "r1").value();
  ASSERT_TRUE(back);
  EXPECT_EQ(back->node, "Office");
  EXPECT_EQ(back->battery, 0.75);
  EXPECT_EQ(back->on_board, Json::array({"red letter"}));
  EXPECT_EQ(back->fault, "bumper");
  EXPECT_EQ(back->updated, Time{seconds(9)});
  EXPECT_FALSE(load_robot_state(db, "r2").value().has_value());
}

TEST_P(RobotStates, BadValuesAreRefused) {
  auto db = temp().open().value();
  EXPECT_EQ(save_robot_state(db, {.robot = "", .node = "Hall"}).error().code, ErrorCode::kInvalidInput);
  EXPECT_EQ(save_robot_state(db, {.robot = "r", .node = "Hall", .battery = 1.5}).error().code,
            ErrorCode::kInvalidInput);
  EXPECT_EQ(save_robot_state(db, {.robot = "r", .node = "Hall", .x = std::nan("")}).error().code,
            ErrorCode::kInvalidInput);
  EXPECT_FALSE(load_robot_state(db, "r").value().has_value());
}

TEST_P(Meta, KeysAreSetReplacedAndRead) {
  auto db = temp().open().value();
  EXPECT_FALSE(get_meta(db, "run.seed").value().has_value());
  ASSERT_TRUE(set_meta(db, "run.seed", "7").ok());
  ASSERT_TRUE(set_meta(db, "run.seed", "8").ok());
  EXPECT_EQ(get_meta(db, "run.seed").value(), "8");
}

RONDO_ON_BOTH_BACKENDS(RobotStates);
RONDO_ON_BOTH_BACKENDS(Meta);

}  // namespace
}  // namespace rondo::store
