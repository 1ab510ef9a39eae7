// Importers for the three forms of STRANDS topological maps (the maps of the G4S, TSC and AAF
// deployments): the legacy `.tmap` text, the YAML list of {meta, node} documents exported from
// MongoDB, and the JSON variant of the same.
//
//   Result<TopoMap> g4s = parse_strands_tmap(read_text_file("g4s_y2.tmap").value(), "g4s_y2.tmap");
//   Result<TopoMap> tsc = parse_strands_yaml(text, "tsc_1605.yaml");
//
// What is kept: node name, position x/y, yaw from the orientation quaternion (a zero quaternion,
// which real files contain, gives yaw 0), goal tolerances (STRANDS defaults 0.3 m / 0.1 rad when
// absent), influence polygon (`verts` / `vertices`), the `meta` block minus its bookkeeping keys
// (`map`, `node`, `pointset`) and a non-empty `localise_by_topic`, as node metadata; edge target,
// action, `top_vel` as top speed, `edge_id` as the id (else "<from>_<to>", with "_2", "_3"... added
// if that id is already taken). The map name is the `pointset` (for `.tmap`: the file name's stem).
// Other STRANDS fields (inflation_radius, map_2d, recovery_behaviours_config, config...) are read
// past without checks. Door edges (actions whose name contains "door", see map_geometry.h) get a
// door id shared by both directions: the two node names, smaller first, joined by '_'.
//
// Malformed input is an invalid-input error naming the source, the line when the format records
// it (YAML, .tmap; not JSON), the field or line content, and what is wrong.
#pragma once

#include <string>
#include <string_view>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/map/topo_map.h"

namespace rondo::map {

Result<TopoMap> parse_strands_tmap(std::string_view text, const std::string& source);
Result<TopoMap> parse_strands_yaml(std::string_view text, const std::string& source);
Result<TopoMap> parse_strands_json(std::string_view text, const std::string& source);

// Decodes an already parsed STRANDS YAML or JSON document: a list of {meta, node} entries (an
// entry may also be the bare node object, and the root may be a single entry).
Result<TopoMap> strands_map_from_document(const Document& doc);

// The door id both directions of a door edge between `a` and `b` share.
std::string door_id_between(std::string_view a, std::string_view b);

}  // namespace rondo::map
