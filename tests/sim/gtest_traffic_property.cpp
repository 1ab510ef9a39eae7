// Property: on random small maps, with 2-4 SimRobots given random drives and cancels, the traffic's
// bookkeeping always equals a recount from every robot's position, never goes negative, every hold
// ends within the hold timeout, and a collision is counted exactly when the recount sees a robot
// arrive beyond a node's capacity or enter a narrow passage against another.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "rondo/exec/clock.h"
#include "rondo/sim/sim_robot.h"
#include "rondo/sim/traffic.h"
#include "traffic_test_util.h"

namespace rondo::sim {
namespace {

using namespace rondo::sim::testing;
using map::Narrow;

const Time kT0 = parse_time("2026-11-23T10:00:00Z").value();

// A ring of 3-5 nodes with a chord or not, random capacities (1-2) and narrow marks.
map::TopoMap random_map() {
  const auto n = *rc::gen::inRange<std::size_t>(3, 6);
  std::vector<Place> places;
  for (std::size_t i = 0; i < n; ++i)
    places.push_back({"N" + std::to_string(i), 6.0 * static_cast<double>(i), 4.0 * static_cast<double>(i % 2),
                      *rc::gen::inRange(1, 3)});
  std::vector<std::tuple<std::string, std::string, Narrow>> passages;
  const auto mark = [] { return *rc::gen::element(Narrow::kNone, Narrow::kSingle, Narrow::kOneWay); };
  for (std::size_t i = 0; i < n; ++i) passages.emplace_back(places[i].name, places[(i + 1) % n].name, mark());
  if (n > 3 && *rc::gen::arbitrary<bool>()) passages.emplace_back(places[0].name, places[2].name, mark());
  return traffic_map(places, passages);
}

struct Command {
  int at_s = 0;  // after kT0
  std::size_t robot = 0;
  bool cancel = false;
  std::size_t length = 1;            // edges of the route, 1-3
  std::vector<std::size_t> choices;  // out-edge picks along the route
};

// What a recount from the robots' positions says, and what changed since the last one.
struct Recount {
  std::vector<int> standing, inbound, on_edge;
};

Recount recount(const map::TopoMap& m, const Traffic& t) {
  Recount r{std::vector<int>(m.node_count()), std::vector<int>(m.node_count()), std::vector<int>(m.edge_count())};
  for (Traffic::RobotId i = 0; i < t.robot_count(); ++i) {
    if (!t.present(i)) continue;
    const TrafficPosition p = t.position(i);
    if (p.edge) {
      ++r.on_edge[*p.edge];
      ++r.inbound[m.to_index(*p.edge)];
    } else {
      ++r.standing[p.node];
    }
  }
  return r;
}

// Whether the change from `before` to `after` is a collision, seen from the positions alone.
bool sees_collision(const map::TopoMap& m, const Traffic& t, const Recount& before, const Recount& after) {
  for (map::NodeIndex n = 0; n < m.node_count(); ++n)
    if (after.standing[n] > before.standing[n] && after.standing[n] > t.capacity(n)) return true;
  for (map::EdgeIndex e = 0; e < m.edge_count(); ++e) {
    if (after.on_edge[e] <= before.on_edge[e]) continue;
    const Narrow mark = map::passage_narrow(m, e);
    int same = 0, against = 0;
    for (map::EdgeIndex o = 0; o < m.edge_count(); ++o) {
      if (m.from_index(o) == m.from_index(e) && m.to_index(o) == m.to_index(e)) same += after.on_edge[o];
      if (m.from_index(o) == m.to_index(e) && m.to_index(o) == m.from_index(e)) against += after.on_edge[o];
    }
    if ((mark == Narrow::kSingle && same + against > 1) || (mark == Narrow::kOneWay && against > 0)) return true;
  }
  return false;
}

RC_GTEST_PROP(TrafficProperty, BookkeepingHoldsAndCollisionsAgreeWithARecount, ()) {
  const map::TopoMap m = random_map();
  SimWorld world = exact_traffic_world(m, {}, 0.25, 0.3);
  exec::SimClock clock(kT0);
  Traffic traffic(m, {.hold_timeout = seconds(*rc::gen::element(20, 60))});
  std::vector<std::string> wrong;
  Recount last = recount(m, traffic);
  std::size_t collisions = 0;
  traffic.observe([&] {
    const Recount now = recount(m, traffic);
    for (map::NodeIndex n = 0; n < m.node_count(); ++n)
      if (now.standing[n] != traffic.standing(n) || now.inbound[n] != traffic.inbound(n) || traffic.standing(n) < 0 ||
          traffic.inbound(n) < 0)
        wrong.push_back("node counts differ at " + m.node(n).name);
    for (map::EdgeIndex e = 0; e < m.edge_count(); ++e)
      if (now.on_edge[e] != traffic.on_edge(e) || traffic.on_edge(e) < 0) wrong.push_back("edge counts differ");
    const bool counted = traffic.collisions().size() > collisions;
    if (counted != sees_collision(m, traffic, last, now)) wrong.push_back("collision counted != seen");
    collisions = traffic.collisions().size();
    last = now;
  });
  const int robots = *rc::gen::inRange(2, 5);
  std::vector<std::unique_ptr<Attempts>> heard;
  std::vector<std::unique_ptr<SimRobot>> fleet;
  for (int i = 0; i < robots; ++i) {
    const auto start = *rc::gen::inRange<std::size_t>(0, m.node_count());
    fleet.push_back(std::make_unique<SimRobot>(clock, m, world,
                                               SimRobotOptions{.start = start,
                                                               .seed = static_cast<std::uint64_t>(i) + 1,
                                                               .name = "r" + std::to_string(i + 1),
                                                               .traffic = &traffic}));
    heard.push_back(std::make_unique<Attempts>());
    fleet.back()->set_listener(heard.back().get());
  }
  const auto commands = *rc::gen::container<std::vector<Command>>(rc::gen::build<Command>(
      rc::gen::set(&Command::at_s, rc::gen::inRange(0, 600)),
      rc::gen::set(&Command::robot, rc::gen::inRange<std::size_t>(0, static_cast<std::size_t>(robots))),
      rc::gen::set(&Command::cancel, rc::gen::weightedElement<bool>({{1, true}, {4, false}})),
      rc::gen::set(&Command::length, rc::gen::inRange<std::size_t>(1, 4)),
      rc::gen::set(&Command::choices,
                   rc::gen::container<std::vector<std::size_t>>(3, rc::gen::inRange<std::size_t>(0, 3)))));
  for (const Command& c : commands) {
    clock.schedule_at(kT0 + seconds(c.at_s), [&m, &fleet, c] {
      SimRobot& r = *fleet[c.robot];
      if (c.cancel) return r.cancel();
      if (r.busy()) return;
      exec::Route route;
      map::NodeIndex at = r.location();
      for (std::size_t k = 0; k < c.length; ++k) {
        const auto outs = m.out_edges(at);
        route.edges.push_back(outs[c.choices[k] % outs.size()]);
        at = m.to_index(route.edges.back());
      }
      route.committed = route.edges.size();
      r.drive(route);
    });
  }
  clock.run_until(kT0 + hours(2));

  RC_CLASSIFY(!traffic.hold_ups().empty(), "held up");
  RC_CLASSIFY(!traffic.collisions().empty(), "collided");
  RC_ASSERT(wrong.empty());
  for (const HoldUp& h : traffic.hold_ups()) {
    RC_ASSERT(h.how != HoldUp::End::kWaiting);
    RC_ASSERT(h.held() >= Duration{0});
    RC_ASSERT(h.held() <= traffic.options().hold_timeout);
  }
  for (Traffic::RobotId i = 0; i < traffic.robot_count(); ++i) {
    RC_ASSERT(!fleet[i]->busy());
    RC_ASSERT(!traffic.position(i).edge.has_value());
    RC_ASSERT(traffic.position(i).node == fleet[i]->location());
  }
}

}  // namespace
}  // namespace rondo::sim
