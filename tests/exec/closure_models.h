// Edge models fitted on a history in which one edge, once it fails, fails every immediate retry:
// the shape of a closure in a robot's own log. For the scripted-robot tests of blocked ways.
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "rondo/core/timezone.h"
#include "rondo/core/traversal.h"
#include "rondo/learn/edge_models.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/learned_edge_models.h"

namespace rondo::exec::testing {

// Two weeks before 2026-11-23 (a Monday): every edge crossed at every even hour from 08:00 to
// 18:00, and `closed` (an edge id) closed each day from `hour`:00 for 40 minutes, found so at
// `hour`:00 and retried at once 8 times. `hour` is even, 8 to 18. Read online (the live model).
inline std::shared_ptr<plan::LearnedEdgeModels> models_where_edge_stays_closed(const map::TopoMap& map,
                                                                               const TimeZone& zone,
                                                                               const std::string& closed, int hour) {
  std::vector<Traversal> log;
  const Time monday = zone.parse_time("2026-11-23T00:00").value();
  for (int day = 14; day >= 1; --day) {
    const Time midnight = monday - hours(24 * day);
    for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) {
      const map::Edge& edge = map.edge(e);
      for (int h = 8; h <= 18; h += 2) {
        const bool shut = edge.id == closed && h == hour;
        Time t = midnight + hours(h);
        for (int i = 0; i < (shut ? 9 : 1); ++i, t += seconds(20))
          log.push_back({.edge_id = edge.id, .from = edge.from, .to = edge.to, .start = t, .duration = seconds(20),
                         .success = !shut});
      }
    }
  }
  std::sort(log.begin(), log.end(), [](const Traversal& a, const Traversal& b) { return a.start < b.start; });
  learn::EdgeModelsOptions options;
  options.episode.zone = zone;
  auto fitted = learn::EdgeModels::fit(plan::edge_specs(map), log, options).value();
  return std::make_shared<plan::LearnedEdgeModels>(map, fitted, plan::DistancePriorOptions{},
                                                   plan::LearnedEdgeModels::Reading::kOnline);
}

}  // namespace rondo::exec::testing
