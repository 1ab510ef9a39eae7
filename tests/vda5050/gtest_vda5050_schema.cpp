// Every message rondo sends validates against the official VDA 5050 2.0.0 schemas (patched for
// their known defects in schema_check.cpp), in the standard shape: no key the schema does not
// define, with the compatibility option off.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "rondo/map/map_loader.h"
#include "rondo/vda5050/encode.h"
#include "rondo/vda5050/header.h"
#include "rondo/vda5050/order_builder.h"
#include "vda5050/schema_check.h"
#include "vda5050/vda5050_test_support.h"

namespace rondo::vda5050 {
namespace {

using testing::SchemaCheck;
using testing::Strictness;

const map::TopoMap& g4s() {
  static const map::TopoMap map = *map::load_map("examples/g4s/map.yaml");
  return map;
}

const SchemaCheck& order_schema() {
  static const SchemaCheck check = SchemaCheck::load("order", Strictness::kStandardShape);
  return check;
}

Time now() {
  return *parse_time("2026-12-01T10:00:00.123Z");
}

// A random walk on the G4S map, drawn by RapidCheck.
std::vector<map::NodeIndex> walk(map::NodeIndex start, std::size_t length) {
  std::vector<map::NodeIndex> route{start};
  while (route.size() < length) {
    auto out = g4s().out_edges(route.back());
    if (out.empty()) break;
    route.push_back(g4s().to_index(out[*rc::gen::inRange<std::size_t>(0, out.size())]));
  }
  return route;
}

RC_GTEST_PROP(Vda5050Schema, EveryOrderAndUpdateOnTheG4sMapValidates, ()) {
  HeaderCounter headers("acme", "agv-7");
  RouteSpec spec;
  spec.route = walk(*rc::gen::inRange<std::size_t>(0, g4s().node_count()), *rc::gen::inRange<std::size_t>(1, 8));
  spec.base_edges = *rc::gen::inRange<std::size_t>(0, spec.route.size());
  spec.map_id = "g4s_y2";
  spec.final_actions = {rondo::Action{"noop", {{"duration", "1.5"}, {"say", "hello"}, {"loud", "true"}}}};
  auto order = build_order(g4s(), "nav-" + std::to_string(*rc::gen::inRange(0, 1000)), spec);
  RC_ASSERT(order.ok());
  const std::string p = order_schema().problems(encode_order(headers.next(Topic::kOrder, now()), *order));
  RC_ASSERT(p == "");
  RouteSpec next = spec;
  next.route = walk(*g4s().find_node(last_base_node(*order).node_id), *rc::gen::inRange<std::size_t>(1, 6));
  next.base_edges = *rc::gen::inRange<std::size_t>(0, next.route.size());
  auto update = build_update(g4s(), *order, next);
  RC_ASSERT(update.ok());
  RC_ASSERT(order_schema().problems(encode_order(headers.next(Topic::kOrder, now()), *update)) == "");
}

TEST(Vda5050Schema, InstantActionsValidateInTheStandardShape) {
  HeaderCounter headers("acme", "agv-7");
  InstantActions ia{
      .actions = {cancel_order_action("cancel-1"), state_request_action("sr-1"), factsheet_request_action("fr-1")}};
  Json standard = encode_instant_actions(headers.next(Topic::kInstantActions, now()), ia);
  auto strict = SchemaCheck::load("instantActions", Strictness::kStandardShape);
  EXPECT_EQ(strict.problems(standard), "");
  // With the compatibility option the extra old key is there: the schema still admits it, the
  // standard shape does not.
  Json compat =
      encode_instant_actions(headers.next(Topic::kInstantActions, now()), ia, Compatibility{.vda5050_lib_1_4 = true});
  EXPECT_EQ(SchemaCheck::load("instantActions", Strictness::kSchema).problems(compat), "");
  EXPECT_NE(strict.problems(compat), "");
}

TEST(Vda5050Schema, TheCheckRejectsBrokenMessages) {
  HeaderCounter headers("acme", "agv-7");
  auto order = build_order(g4s(), "nav-1", {.route = {0}, .base_edges = 0, .map_id = "g4s_y2", .final_actions = {}});
  ASSERT_TRUE(order.ok());
  Json good = encode_order(headers.next(Topic::kOrder, now()), *order);
  ASSERT_EQ(order_schema().problems(good), "");
  Json j = good;
  j.erase("orderId");
  EXPECT_NE(order_schema().problems(j), "");
  j = good;
  j["timestamp"] = "yesterday";
  EXPECT_NE(order_schema().problems(j), "");
  j = good;
  j["nodes"][0]["sequenceId"] = -2;
  EXPECT_NE(order_schema().problems(j), "");
  j = good;
  j["nodes"][0]["nodePosition"]["allowedDeviationXy"] = 0.3;  // the schema file's misspelling
  EXPECT_NE(order_schema().problems(j), "");
  InstantActions ia{.actions = {cancel_order_action("c")}};
  j = encode_instant_actions(headers.next(Topic::kInstantActions, now()), ia);
  j["actions"][0]["blockingType"] = "MAYBE";
  EXPECT_NE(SchemaCheck::load("instantActions", Strictness::kStandardShape).problems(j), "");
}

TEST(Vda5050Schema, TheTestsSampleStateIsAValidState) {
  EXPECT_EQ(SchemaCheck::load("state", Strictness::kStandardShape).problems(testing::sample_state_json()), "");
}

}  // namespace
}  // namespace rondo::vda5050
