#include "traffic_report.h"

#include <algorithm>

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

Json traffic_report(const sim::Traffic& traffic) {
  return Json{{"hold_timeout_s", to_seconds(traffic.options().hold_timeout)},
              {"hold_ups", hold_ups_json(traffic)},
              {"collisions", collisions_json(traffic)}};
}

}  // namespace rondo::app
