// Private helpers shared by the STRANDS importers (.tmap text and YAML/JSON documents) and the
// tmap2 importer (their successor, with the same node and pose layout).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/map/topo_map.h"

namespace rondo::map {

// The heading of a quaternion about the z axis, in [-pi, pi]. The quaternion need not be of unit
// length; any finite one gives a finite yaw, and the zero quaternion (found in real STRANDS maps)
// gives 0.
double yaw_from_quaternion(double x, double y, double z, double w);

// Gives every edge with an empty id the id "<from>_<to>", or "<from>_<to>_2", "_3"... when that id
// is taken by another edge; and gives door edges (action_kind kDoor) without a door their
// door_id_between(from, to).
void complete_strands_edges(std::vector<Edge>& edges);

// A node name or edge id: text, or an integer (an unquoted YAML name such as 12 reads as a number;
// STRANDS and tmap2 names are text, so it is taken as its digits).
Result<std::string> name_value(const Field& f);

// The number at `parent.key`, or `fallback` when it is absent or null.
Result<double> number_or(const Field& parent, std::string_view key, double fallback);
// The number at `parent.key`; an error naming the field when it is missing or not a finite number.
Result<double> required_number(const Field& parent, std::string_view key);

// `node.pose` in the ROS layout: {position: {x, y, z}, orientation: {x, y, z, w}}. x and y are
// required; z is the floor's height and not kept; a missing quaternion component counts as 0.
Result<Pose> decode_ros_pose(const Field& node);

// `node.verts`, a list of {x, y}; empty when absent.
Result<std::vector<Point2>> decode_verts(const Field& node);

// An edge as STRANDS and tmap2 nodes list them: `node` (the target), `action` (default
// kDefaultAction), `edge_id` (empty when absent, completed later), `top_vel`. `expected` is what a
// non-mapping is told it should be.
Result<Edge> decode_ros_edge(const Field& f, const std::string& from, std::string_view expected);

// The map name of a .tmap file: the stem of its path ("maps/g4s_y2.tmap" gives "g4s_y2").
std::string name_from_source(const std::string& source);

}  // namespace rondo::map
