// Properties of the reservation rule on random small maps with 2-4 robots asking for random routes,
// crossing what they hold, stopping, and making way when told: after every call the holdings equal
// a recount from each robot's node and grants (the reference), no node holds more robots than its
// room, no single passage holds two robots and no one-way passage two directions, every robot's
// grants are consecutive edges from its node; and once every robot has stopped, every grant is
// released.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "reservation_test_util.h"
#include "rondo/traffic/reservations.h"

namespace rondo::traffic {
namespace {

using namespace rondo::traffic::testing;
using map::Narrow;

// A ring of 4-7 nodes with chords or not, random capacities (1-2) and narrow marks.
map::TopoMap random_map() {
  const auto n = *rc::gen::inRange<std::size_t>(4, 8);
  std::vector<Place> places;
  for (std::size_t i = 0; i < n; ++i) places.push_back({"N" + std::to_string(i), *rc::gen::inRange(1, 3)});
  std::vector<std::tuple<std::string, std::string, Narrow>> passages;
  const auto mark = [] { return *rc::gen::element(Narrow::kNone, Narrow::kSingle, Narrow::kOneWay); };
  for (std::size_t i = 0; i < n; ++i) passages.emplace_back(places[i].name, places[(i + 1) % n].name, mark());
  for (std::size_t i = 0; i + 3 < n && !(i == 0 && n == 4); ++i)
    if (*rc::gen::arbitrary<bool>()) passages.emplace_back(places[i].name, places[i + 3].name, mark());
  return reservation_map(places, passages);
}

// A walk of 1-4 edges from `from` that visits no node twice.
std::vector<map::EdgeIndex> random_route(const map::TopoMap& m, map::NodeIndex from) {
  const auto length = *rc::gen::inRange<std::size_t>(1, 5);
  std::vector<map::EdgeIndex> route;
  std::vector<bool> seen(m.node_count(), false);
  seen[from] = true;
  map::NodeIndex at = from;
  while (route.size() < length) {
    std::vector<map::EdgeIndex> next;
    for (map::EdgeIndex e : m.out_edges(at))
      if (!seen[m.to_index(e)]) next.push_back(e);
    if (next.empty()) break;
    const map::EdgeIndex e = next[*rc::gen::inRange<std::size_t>(0, next.size())];
    route.push_back(e);
    at = m.to_index(e);
    seen[at] = true;
  }
  return route;
}

// The reference: holdings recounted from each robot's node and grants.
void check(const map::TopoMap& m, const Reservations& r) {
  std::vector<std::vector<RobotId>> nodes(m.node_count());
  for (RobotId i = 0; i < r.robot_count(); ++i) {
    if (!r.present(i)) continue;
    nodes[r.at(i)].push_back(i);
    map::NodeIndex at = r.at(i);
    for (map::EdgeIndex e : r.granted(i)) {
      RC_ASSERT(m.from_index(e) == at);  // consecutive from its node
      at = m.to_index(e);
      nodes[at].push_back(i);
    }
  }
  for (map::NodeIndex n = 0; n < m.node_count(); ++n) {
    std::vector<RobotId> held = r.holders(n);
    std::sort(held.begin(), held.end());
    std::sort(nodes[n].begin(), nodes[n].end());
    RC_ASSERT(held == nodes[n]);
    RC_ASSERT(static_cast<int>(held.size()) <= r.capacity(n));
  }
  for (map::EdgeIndex e = 0; e < m.edge_count(); ++e) {
    const Narrow mark = map::passage_narrow(m, e);
    std::vector<RobotId> holding;  // recounted: robots granted an edge of this passage
    bool with = false, against = false;
    for (RobotId i = 0; i < r.robot_count(); ++i)
      for (map::EdgeIndex g : r.granted(i)) {
        const bool same = m.from_index(g) == m.from_index(e) && m.to_index(g) == m.to_index(e);
        const bool back = m.from_index(g) == m.to_index(e) && m.to_index(g) == m.from_index(e);
        if (!same && !back) continue;
        holding.push_back(i);
        (same ? with : against) = true;
      }
    std::vector<RobotId> held = r.passage_holders(e);
    std::sort(held.begin(), held.end());
    std::sort(holding.begin(), holding.end());
    if (mark == Narrow::kNone) {
      RC_ASSERT(held.empty());
      continue;
    }
    RC_ASSERT(held == holding);
    if (mark == Narrow::kSingle) RC_ASSERT(held.size() <= 1u);
    if (mark == Narrow::kOneWay) RC_ASSERT(!(with && against));
  }
}

RC_GTEST_PROP(ReservationProperties, NeverTwoRobotsOnOnePlaceAndEveryGrantReleased, ()) {
  const map::TopoMap m = random_map();
  Reservations r(m, {.lookahead = *rc::gen::inRange<std::size_t>(1, 4)});
  const auto robots = *rc::gen::inRange<std::size_t>(2, 5);
  std::vector<Told> told(robots);
  // Distinct start nodes (each has room for one at least).
  for (std::size_t i = 0; i < robots; ++i) {
    const RobotId id = r.join("r" + std::to_string(i), i, &told[i]);
    r.set_rank(id, *rc::gen::inRange(0, 3));
  }
  check(m, r);
  const auto steps = *rc::gen::inRange(1, 60);
  for (int s = 0; s < steps; ++s) {
    const RobotId i = *rc::gen::inRange<std::size_t>(0, robots);
    switch (*rc::gen::inRange(0, 5)) {
      case 0:
      case 1:
        r.request(i, r.at(i), random_route(m, r.at(i)));
        break;
      case 2:
      case 3:
        if (!r.granted(i).empty()) r.crossed(i, r.granted(i).front());
        break;
      case 4:
        if (*rc::gen::arbitrary<bool>()) {
          r.stop(i, r.at(i));
        } else {
          r.set_parked(i, *rc::gen::arbitrary<bool>());
        }
        break;
    }
    check(m, r);
  }
  // Every robot stops where it is: it holds its node and nothing else.
  for (RobotId i = 0; i < robots; ++i) r.stop(i, r.at(i));
  check(m, r);
  for (RobotId i = 0; i < robots; ++i) RC_ASSERT(r.granted(i).empty());
  for (map::EdgeIndex e = 0; e < m.edge_count(); ++e) RC_ASSERT(r.passage_holders(e).empty());
  for (map::NodeIndex n = 0; n < m.node_count(); ++n) {
    std::size_t standing = 0;
    for (RobotId i = 0; i < robots; ++i) standing += r.at(i) == n ? 1u : 0u;
    RC_ASSERT(r.holders(n).size() == standing);
  }
}

// Robots that drive what they hold, ask again when told, and park where they arrive: once nobody
// moves, a robot still waiting waits only for robots that wait too, in a deadlock that was counted
// unresolved (no grant is forgotten, no waiting robot left untold, no parked robot left in the way
// when it could move).
RC_GTEST_PROP(ReservationProperties, WaitingRobotsAreWokenWhenTheirWayClears, ()) {
  const map::TopoMap m = random_map();
  Reservations r(m, {.lookahead = 2});
  const auto robots = *rc::gen::inRange<std::size_t>(2, 4);
  std::vector<Told> told(robots);
  std::vector<std::vector<map::EdgeIndex>> routes(robots);
  for (std::size_t i = 0; i < robots; ++i) {
    r.join("r" + std::to_string(i), i, &told[i]);
    routes[i] = random_route(m, i);
  }
  for (RobotId i = 0; i < robots; ++i) {
    if (routes[i].empty()) {
      r.set_parked(i, true);
    } else {
      r.request(i, r.at(i), routes[i]);
    }
  }
  for (int round = 0; round < 200; ++round) {
    bool moved = false;
    for (RobotId i = 0; i < robots; ++i) {
      if (!told[i].make_way.empty()) {  // sent aside: it drives there and gives up its route
        for (std::size_t k = 0; k < told[i].make_way.back().route.size(); ++k) r.crossed(i, r.granted(i).front());
        told[i].make_way.clear();
        routes[i].clear();
        r.stop(i, r.at(i));
        r.set_parked(i, true);
        moved = true;
        continue;
      }
      if (r.granted(i).empty()) continue;
      const map::EdgeIndex e = r.granted(i).front();
      r.crossed(i, e);
      routes[i].erase(routes[i].begin());
      if (routes[i].empty()) {  // arrived: it parks there
        r.stop(i, r.at(i));
        r.set_parked(i, true);
      } else if (r.granted(i).empty()) {
        r.request(i, r.at(i), routes[i]);
      }
      moved = true;
    }
    for (RobotId i = 0; i < robots; ++i)  // woken robots ask again
      if (told[i].clear > 0) {
        told[i].clear = 0;
        if (r.waiting(i) && r.request(i, r.at(i), routes[i]) > 0) moved = true;
      }
    check(m, r);
    if (!moved) break;
  }
  // Nobody moves any more: a robot still waiting waits for robots that wait too or are parked with
  // nowhere to go (a deadlock left unresolved, and counted), never for one that holds a way it will
  // not use.
  std::vector<bool> parked(robots);
  for (RobotId i = 0; i < robots; ++i) parked[i] = routes[i].empty();
  for (RobotId i = 0; i < robots; ++i) {
    RC_ASSERT(r.granted(i).empty());
    if (!r.waiting(i)) continue;
    RC_ASSERT(r.unresolved() > 0u);
    for (RobotId b : r.waits_for(i)) RC_ASSERT(r.waiting(b) || parked[b]);
  }
}

}  // namespace
}  // namespace rondo::traffic
