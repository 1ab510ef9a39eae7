// DeadEnds: rooms behind doors and corridor ends are found; on random maps every region is cut off
// from the rest by its door, regions are disjoint and small, doors are in the core; and M_t's
// exits are each region node's shortest route to its door (against a plain Dijkstra on the map).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <set>

#include "random_map.h"
#include "rondo/plan/dead_ends.h"
#include "rondo/plan/exact_solver.h"
#include "small_maps.h"

namespace rondo::plan {
namespace {

using testing::small_map;

std::set<NodeIndex> members(const DeadEnds& d, std::uint32_t r) {
  return {d.nodes(r).begin(), d.nodes(r).end()};
}

TEST(DeadEnds, ARoomBehindItsDoorAndTheEndOfACorridor) {
  // Corridor A-B-C-D-E (both ways), the lift L off A keeps A in the core; room R1-R2 behind B.
  const map::TopoMap m = small_map({"A", "B", "C", "D", "E", "R1", "R2", "L"},
                                   {"A>B", "B>A", "B>C", "C>B", "C>D", "D>C", "D>E", "E>D", "B>R1", "R1>B",
                                    "R1>R2", "R2>R1", "A>L", "L>A", "L>C", "C>L"});
  const DeadEnds d = DeadEnds::find(m);
  ASSERT_EQ(d.region_count(), 2u);
  std::set<std::pair<NodeIndex, std::set<NodeIndex>>> found;
  for (std::uint32_t r = 0; r < 2; ++r) found.emplace(d.door(r), members(d, r));
  const auto at = [&](const char* name) { return *m.find_node(name); };
  EXPECT_TRUE(found.count({at("B"), {at("R1"), at("R2")}}));  // the room
  EXPECT_TRUE(found.count({at("C"), {at("D"), at("E")}}));    // the corridor's end
  for (const char* core : {"A", "B", "C", "L"}) EXPECT_TRUE(d.in_core(at(core))) << core;
  EXPECT_EQ(d.region_of(at("R2")), d.region_of(at("R1")));
}

TEST(DeadEnds, TheLimitOnARegionsSizeAndMapsWithoutAny) {
  // A - B - C - D: a path. With regions of at most one node only the ends qualify.
  const map::TopoMap path = small_map({"A", "B", "C", "D", "E"}, {"A>B", "B>C", "C>D", "D>E"});
  const DeadEnds small = DeadEnds::find(path, 1);
  for (std::uint32_t r = 0; r < small.region_count(); ++r) EXPECT_EQ(small.nodes(r).size(), 1u);
  EXPECT_GE(small.region_count(), 1u);
  EXPECT_EQ(DeadEnds::find(path, 0).region_count(), 0u);
  // A ring has no articulation point; a single node or an empty map has nothing to cut off.
  EXPECT_EQ(DeadEnds::find(small_map({"A", "B", "C"}, {"A>B", "B>C", "C>A"})).region_count(), 0u);
  EXPECT_EQ(DeadEnds::find(small_map({"A"}, {})).region_count(), 0u);
  EXPECT_EQ(DeadEnds::find(map::TopoMap{}).node_count(), 0u);
  // Two nodes: neither may be a region of the other (fewer than half the nodes).
  EXPECT_EQ(DeadEnds::find(small_map({"A", "B"}, {"A>B", "B>A"})).region_count(), 0u);
}

TEST(DeadEnds, TheCorridorBuildingsRoomsAreRegions) {
  const map::TopoMap m = testing::corridor_building_map({});
  const DeadEnds d = DeadEnds::find(m);
  // Every room (6 places) is in a region; the lift stops are in the core.
  EXPECT_GE(d.region_members().size(), 4u * 36u * 6u);
  EXPECT_TRUE(d.in_core(0));
}

TEST(DeadEnds, AnMdpRejectsTheDeadEndsOfAnotherMap) {
  const map::TopoMap m = small_map({"A", "B"}, {"A>B"});
  const auto other = std::make_shared<const DeadEnds>(DeadEnds::find(small_map({"A"}, {})));
  EXPECT_FALSE(Mdp::from_outcomes(m, {{1.0, 1.0}}, Time{}, other).ok());
  EXPECT_TRUE(Mdp::from_outcomes(m, {{1.0, 1.0}}, Time{}, std::make_shared<const DeadEnds>(DeadEnds::find(m))).ok());
}

RC_GTEST_PROP(DeadEndsProperties, EveryRegionIsCutOffByItsDoor, ()) {
  const auto nodes = *rc::gen::inRange<std::size_t>(1, 300);
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const auto limit = *rc::gen::element<std::size_t>(1, 4, 64, 1000);
  const map::TopoMap m = testing::random_map({.nodes = nodes, .seed = seed, .max_out_degree = 2});
  const DeadEnds d = DeadEnds::find(m, limit);
  RC_ASSERT(d.node_count() == nodes);
  std::vector<int> seen(nodes, 0);
  for (std::uint32_t r = 0; r < d.region_count(); ++r) {
    const auto span = d.nodes(r);
    RC_ASSERT(!span.empty());
    RC_ASSERT(span.size() <= limit);
    RC_ASSERT(2 * span.size() < nodes);
    RC_ASSERT(d.in_core(d.door(r)));
    for (NodeIndex v : span) {
      ++seen[v];
      RC_ASSERT(d.region_of(v) == std::optional<std::uint32_t>(r));
    }
  }
  for (NodeIndex v = 0; v < nodes; ++v) RC_ASSERT(seen[v] == (d.in_core(v) ? 0 : 1));
  // Separation: an edge leaving or entering a region joins it to itself or to its door.
  for (EdgeIndex e = 0; e < m.edge_count(); ++e) {
    const NodeIndex a = m.from_index(e), b = m.to_index(e);
    for (auto [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
      if (const auto r = d.region_of(x)) RC_ASSERT(d.region_of(y) == r || y == d.door(*r));
    }
  }
}

RC_GTEST_PROP(DeadEndsProperties, ExitsAreTheShortestRoutesToTheDoor, ()) {
  const auto nodes = *rc::gen::inRange<std::size_t>(3, 120);
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const map::TopoMap m = testing::random_map({.nodes = nodes, .seed = seed, .max_out_degree = 2});
  const Mdp mdp = testing::outcomes_mdp(m, testing::random_outcomes(m, {.seed = seed, .closed_fraction = 0.2}));
  const DeadEnds& d = mdp.dead_ends();
  const ExactSolver plain({.use_dead_ends = false});
  for (std::uint32_t r = 0; r < d.region_count(); ++r) {
    // The whole map's shortest routes to the door: a region node's route never leaves the region.
    const Policy to_door = plain.solve(mdp, d.door(r)).value().policy;
    const Mdp::Exit* exit = mdp.exits().data() + d.first_member(r);
    for (NodeIndex v : d.nodes(r)) {
      const double truth = to_door.expected_seconds(v);
      if (truth == kInfinity) {
        RC_ASSERT(exit->seconds == kInfinity);
        RC_ASSERT(exit->edge == Mdp::kNoExit);
      } else {
        RC_ASSERT(std::abs(exit->seconds - truth) <= 1e-12 * std::max(1.0, truth));
        RC_ASSERT(m.from_index(exit->edge) == v);
        RC_ASSERT(mdp.usable(exit->edge));
      }
      ++exit;
    }
  }
}

}  // namespace
}  // namespace rondo::plan
