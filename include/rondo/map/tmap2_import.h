// Importer for the `tmap2` topological maps of LCAS topological_navigation (the ROS 2 successor of
// STRANDS topological navigation): one YAML mapping with the map's `name`, `pointset`,
// `metric_map`, `meta` and `transformation`, and `nodes: [{meta, node: {name, pose, properties,
// verts, edges: [{edge_id, node, action, ...}], restrictions_planning, ...}}]`, usually written with
// YAML anchors and aliases for the parts that repeat.
//
//   if (is_tmap2_document(doc)) {
//     Result<Tmap2Import> in = tmap2_map_from_document(doc);   // in->map, in->warnings
//   }
//   Result<TopoMap> map = parse_tmap2(text, "riseholme.tmap2");
//
// What is kept: node name, position x/y, yaw from the orientation quaternion, the goal tolerances
// of `properties` (defaults 0.3 m / 0.1 rad when absent), `verts` as the influence polygon, the
// entry's `meta` minus its bookkeeping keys (`map`, `node`, `pointset`) plus a non-empty
// `localise_by_topic` and any node restriction other than 'True', as node metadata; edge target
// (`node`), `action` (default move_base), `edge_id` (else "<from>_<to>", "_2"... if taken),
// `top_vel` (on the edge, or in a `config` mapping as the 2021 files have it) as the top speed.
// Door edges (actions whose name contains "door") get the door id of strands_import.h. The map name
// is `name`, else `pointset`. Execution details that the robot's own navigation applies
// (action_type, goal, config lists, fail_policy, fluid_navigation, recovery_behaviours_config,
// parent_frame, transformation) are read past without checks. Edge restrictions, which rondo does
// not apply, are reported as warnings, not lost silently.
//
// Malformed input is an invalid-input error naming the source, the line and the field path
// ("map.tmap2:42: nodes[3].node.pose.position.x: expected a number").
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/map/topo_map.h"

namespace rondo::map {

struct Tmap2Import {
  TopoMap map;
  // What the file says that rondo does not apply (edge restrictions), one sentence each.
  std::vector<std::string> warnings{};
};

// Whether a parsed document has the tmap2 form: a mapping without `rondo_map` whose `nodes` list
// starts with a `{meta, node}` entry (one with `node`, or with `meta` but neither `name` nor
// `pose`); or, when `nodes` has no such first entry to judge by, a mapping with one of the tmap2
// top-level keys (`meta`, `metric_map`, `pointset`, `transformation`). Rondo's own nodes carry
// `name` and `pose` themselves, so a rondo map with a stray top-level `meta` is still rondo's (and
// is told about the unknown field), and a tmap2 file with a broken node is still reported as tmap2.
bool is_tmap2_document(const Document& doc);

Result<Tmap2Import> tmap2_map_from_document(const Document& doc);

// Parses YAML text and imports it; `source` names the text in error messages.
Result<Tmap2Import> parse_tmap2(std::string_view text, const std::string& source);

}  // namespace rondo::map
