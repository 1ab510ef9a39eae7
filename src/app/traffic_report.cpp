#include "traffic_report.h"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

namespace rondo::app {
namespace {

Json hold_up_json(const sim::HoldUp& h, const map::TopoMap& map) {
  return Json{{"start", format_time(h.start)},
              {"robot", h.robot},
              {"node", h.node},
              {"edge", map.edge(h.edge).id},
              {"held_by", h.blocker.robot},
              {"place", h.blocker.place},
              {"held_s", to_seconds(h.held())},
              {"end", sim::to_string(h.how)}};
}

Json hold_ups_json(const sim::Traffic& traffic) {
  std::size_t passed = 0, timed_out = 0, stopped = 0;
  Duration total{0}, longest{0};
  Json first = Json::array();
  for (const sim::HoldUp& h : traffic.hold_ups()) {
    if (h.how == sim::HoldUp::End::kPassed) ++passed;
    if (h.how == sim::HoldUp::End::kTimedOut) ++timed_out;
    if (h.how == sim::HoldUp::End::kStopped) ++stopped;
    total += h.held();
    longest = std::max(longest, h.held());
    if (first.size() < kTrafficListed) first.push_back(hold_up_json(h, traffic.map()));
  }
  return Json{{"count", traffic.hold_ups().size()},
              {"total_s", to_seconds(total)},
              {"longest_s", to_seconds(longest)},
              {"passed", passed},
              {"timed_out", timed_out},
              {"stopped", stopped},
              {"first", std::move(first)}};
}

Json collisions_json(const sim::Traffic& traffic) {
  std::size_t at_nodes = 0;
  Json first = Json::array();
  for (const sim::Collision& c : traffic.collisions()) {
    if (c.kind == sim::Collision::Kind::kNode) ++at_nodes;
    if (first.size() < kTrafficListed)
      first.push_back(Json{{"at", format_time(c.at)},
                           {"place", c.place},
                           {"kind", c.kind == sim::Collision::Kind::kNode ? "node" : "narrow edge"},
                           {"robots", c.robots}});
  }
  return Json{{"count", traffic.collisions().size()},
              {"at_nodes", at_nodes},
              {"on_narrow_edges", traffic.collisions().size() - at_nodes},
              {"first", std::move(first)}};
}

}  // namespace

Json reservation_report(const traffic::Reservations& reservations, const std::vector<exec::TrafficWait>& waits,
                        Time end) {
  struct Tally {
    std::size_t count = 0;
    Duration total{0};
  };
  std::map<std::string, Tally> robots, nodes;
  std::size_t passed = 0, made_way = 0, stopped = 0, over = 0;
  Duration total{0}, longest{0};
  for (const exec::TrafficWait& w : waits) {
    const Duration d = w.end.value_or(end) - w.start;
    total += d;
    longest = std::max(longest, d);
    if (d > minutes(2)) ++over;
    if (w.how == "passed") ++passed;
    if (w.how == "made way") ++made_way;
    if (w.how == "stopped") ++stopped;
    for (Tally* t : {&robots[w.robot], &nodes[w.node]}) {
      ++t->count;
      t->total += d;
    }
  }
  Json per_robot = Json::object();
  for (const auto& [name, t] : robots) per_robot[name] = Json{{"count", t.count}, {"total_s", to_seconds(t.total)}};
  std::vector<std::pair<std::string, Tally>> busiest(nodes.begin(), nodes.end());
  std::sort(busiest.begin(), busiest.end(), [](const auto& a, const auto& b) {
    return a.second.total != b.second.total ? a.second.total > b.second.total : a.first < b.first;
  });
  Json busiest_nodes = Json::array();
  for (std::size_t i = 0; i < busiest.size() && i < 10; ++i)
    busiest_nodes.push_back(Json{{"node", busiest[i].first},
                                 {"waits", busiest[i].second.count},
                                 {"total_s", to_seconds(busiest[i].second.total)}});
  std::size_t deadlocks = 0;
  Json first = Json::array();
  for (const traffic::Resolution& r : reservations.resolutions()) {
    if (r.why == traffic::MakeWay::Why::kDeadlock) ++deadlocks;
    if (first.size() >= kTrafficListed) continue;
    std::vector<std::string> for_robots;
    for (traffic::RobotId o : r.for_robots) for_robots.push_back(reservations.name(o));
    first.push_back(Json{{"why", traffic::to_string(r.why)},
                         {"robot", reservations.name(r.robot)},
                         {"to", reservations.map().node(r.to).name},
                         {"for", for_robots}});
  }
  return Json{{"lookahead", reservations.options().lookahead},
              {"waits", Json{{"count", waits.size()},
                             {"total_s", to_seconds(total)},
                             {"longest_s", to_seconds(longest)},
                             {"over_2_min", over},
                             {"passed", passed},
                             {"made_way", made_way},
                             {"stopped", stopped},
                             {"robots", std::move(per_robot)},
                             {"busiest_nodes", std::move(busiest_nodes)}}},
              {"resolutions", Json{{"deadlocks", deadlocks},
                                   {"parked", reservations.resolutions().size() - deadlocks},
                                   {"unresolved", reservations.unresolved()},
                                   {"first", std::move(first)}}}};
}

Json plan_around_report(const exec::TrafficDeferrals& deferrals) {
  return Json{{"departures_put_off", deferrals.count}, {"put_off_s", to_seconds(deferrals.total)}};
}

Json traffic_report(const sim::Traffic& traffic) {
  return Json{{"hold_timeout_s", to_seconds(traffic.options().hold_timeout)},
              {"hold_ups", hold_ups_json(traffic)},
              {"collisions", collisions_json(traffic)}};
}

}  // namespace rondo::app
