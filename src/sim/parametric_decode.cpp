#include "parametric_decode.h"

#include <algorithm>

#include <fmt/format.h>

#include "decode_util.h"

namespace rondo::sim::detail {
namespace {

constexpr double kMaxFactor = 1000.0;

Status decode_noise(const Field& f, DurationNoise& n) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"sigma", "tail_probability", "tail_alpha", "tail_max"}));
  RONDO_RETURN_IF_ERROR(read_number(f, "sigma", 0, 3, n.sigma));
  RONDO_RETURN_IF_ERROR(read_number(f, "tail_probability", 0, 1, n.tail_probability));
  RONDO_RETURN_IF_ERROR(read_number(f, "tail_alpha", 0.1, 100, n.tail_alpha));
  RONDO_RETURN_IF_ERROR(read_number(f, "tail_max", 1, kMaxFactor, n.tail_max));
  return {};
}

Status decode_failed(const Field& f, FailedDuration& d) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"min_factor", "max_factor"}));
  RONDO_RETURN_IF_ERROR(read_number(f, "min_factor", 0, kMaxFactor, d.min_factor));
  RONDO_RETURN_IF_ERROR(read_number(f, "max_factor", 0, kMaxFactor, d.max_factor));
  if (d.max_factor < d.min_factor) return f.error_at("max_factor", "must not be below min_factor");
  return {};
}

Status decode_bursts(const Field& f, BurstSpec& b) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"mean_normal", "mean_blocked", "failure_probability", "duration_factor"}));
  RONDO_RETURN_IF_ERROR(read_duration(f, "mean_normal", b.mean_normal));
  RONDO_RETURN_IF_ERROR(read_duration(f, "mean_blocked", b.mean_blocked));
  RONDO_RETURN_IF_ERROR(read_number(f, "failure_probability", 0, 1, b.failure_probability));
  RONDO_RETURN_IF_ERROR(read_number(f, "duration_factor", 0, kMaxFactor, b.duration_factor));
  if (b.mean_blocked > Duration{0} && b.mean_normal <= Duration{0}) {
    return f.error_at("mean_normal", "must be positive when mean_blocked is");
  }
  return {};
}

void add_unique(std::vector<map::EdgeIndex>& edges, map::EdgeIndex e) {
  if (std::find(edges.begin(), edges.end(), e) == edges.end()) edges.push_back(e);
}

// The edges one selector entry names: an edge id, the edges at a node, the edges with an action or
// through a door. An error when there are none.
Result<std::vector<map::EdgeIndex>> edges_named(const Field& item, std::string_view kind, const map::TopoMap& map) {
  RONDO_ASSIGN_OR_RETURN(auto name, item.as_string());
  std::vector<map::EdgeIndex> out;
  if (kind == "edges") {
    if (auto e = map.find_edge(name)) out.push_back(*e);
  } else if (kind == "nodes") {
    const auto n = map.find_node(name);
    if (!n) return item.error(fmt::format("map '{}' has no node '{}'", map.name(), name));
    out.assign(map.out_edges(*n).begin(), map.out_edges(*n).end());
    out.insert(out.end(), map.in_edges(*n).begin(), map.in_edges(*n).end());
  } else {
    for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) {
      const map::Edge& edge = map.edge(e);
      if ((kind == "actions" && edge.action == name) || (kind == "doors" && edge.door == name)) out.push_back(e);
    }
  }
  if (out.empty()) {
    const char* what = kind == "edges"     ? "no edge"
                       : kind == "nodes"   ? "no edge at node"
                       : kind == "actions" ? "no edge with action"
                                           : "no edge through door";
    return item.error(fmt::format("map '{}' has {} '{}'", map.name(), what, name));
  }
  return out;
}

// Adds the edges of one selector list (edges, nodes, actions or doors) of an effect.
Status select(const Field& list, std::string_view kind, const map::TopoMap& map, std::vector<map::EdgeIndex>& out) {
  RONDO_ASSIGN_OR_RETURN(auto items, list.items());
  for (const auto& item : items) {
    RONDO_ASSIGN_OR_RETURN(auto edges, edges_named(item, kind, map));
    for (map::EdgeIndex e : edges) add_unique(out, e);
  }
  return {};
}

}  // namespace

Status decode_edge_settings(const Field& f, bool with_bursts, ParametricSpec& spec) {
  RONDO_RETURN_IF_ERROR(read_number(f, "speed", 0.01, 10, spec.default_speed));
  RONDO_RETURN_IF_ERROR(read_number(f, "failure_probability", 0, 1, spec.failure_probability));
  if (auto n = f.optional("noise")) RONDO_RETURN_IF_ERROR(decode_noise(*n, spec.noise));
  if (auto d = f.optional("failed_duration")) RONDO_RETURN_IF_ERROR(decode_failed(*d, spec.failed));
  if (auto b = f.optional("bursts"); b && with_bursts) RONDO_RETURN_IF_ERROR(decode_bursts(*b, spec.bursts));
  return {};
}

Result<EdgeEffect> decode_effect(const Field& f, const map::TopoMap& map, const TimeZone& zone) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"name", "edges", "nodes", "actions", "doors", "all", "when", "unless",
                                       "failure_probability", "duration_factor", "closed", "spells"}));
  EdgeEffect effect;
  if (auto name = f.optional("name")) {
    RONDO_ASSIGN_OR_RETURN(effect.name, name->as_string());
  }
  bool any_selector = false;
  for (std::string_view kind : {"edges", "nodes", "actions", "doors"}) {
    if (auto list = f.optional(kind)) {
      any_selector = true;
      RONDO_RETURN_IF_ERROR(select(*list, kind, map, effect.edges));
    }
  }
  if (auto all = f.optional("all")) {
    RONDO_ASSIGN_OR_RETURN(bool every, all->as_bool());
    any_selector = true;
    if (every) {
      for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) add_unique(effect.edges, e);
    }
  }
  if (!any_selector) return f.error("an effect needs edges, nodes, actions, doors or all: true to select its edges");
  std::sort(effect.edges.begin(), effect.edges.end());
  if (auto when = f.optional("when")) {
    RONDO_ASSIGN_OR_RETURN(effect.when, time_conditions(*when, zone));
  }
  if (auto unless = f.optional("unless")) {
    RONDO_ASSIGN_OR_RETURN(effect.unless, time_conditions(*unless, zone));
  }
  RONDO_RETURN_IF_ERROR(read_number(f, "failure_probability", 0, 1, effect.failure_probability));
  RONDO_RETURN_IF_ERROR(read_number(f, "duration_factor", 0, kMaxFactor, effect.duration_factor));
  if (auto closed = f.optional("closed")) {
    RONDO_ASSIGN_OR_RETURN(effect.closed, closed->as_bool());
  }
  if (auto spells = f.optional("spells")) {
    RONDO_RETURN_IF_ERROR(spells->expect_keys({"mean_open", "mean_shut"}));
    ShutSpells s;
    RONDO_RETURN_IF_ERROR(read_duration(*spells, "mean_open", s.mean_open));
    RONDO_RETURN_IF_ERROR(read_duration(*spells, "mean_shut", s.mean_shut));
    if (s.mean_open <= Duration{0} || s.mean_shut <= Duration{0})
      return spells->error("mean_open and mean_shut must both be given, and positive");
    effect.spells = s;
  }
  return effect;
}

}  // namespace rondo::sim::detail
