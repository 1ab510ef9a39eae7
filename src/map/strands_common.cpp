#include "strands_common.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <unordered_map>
#include <unordered_set>

#include "rondo/map/map_geometry.h"
#include "rondo/map/strands_import.h"
#include "rondo/core/utf8.h"

namespace rondo::map {

double yaw_from_quaternion(double x, double y, double z, double w) {
  // Scale first so that large components cannot overflow into inf - inf. The formula below is
  // homogeneous (both arguments scale with the squared norm), so it needs no unit quaternion:
  // STRANDS files hold unnormalised ones, and the zero quaternion.
  const double scale = std::max({std::abs(x), std::abs(y), std::abs(z), std::abs(w)});
  if (!(scale > 0) || !std::isfinite(scale)) return 0.0;
  x /= scale;
  y /= scale;
  z /= scale;
  w /= scale;
  return std::atan2(2.0 * (w * z + x * y), w * w + x * x - y * y - z * z);
}

std::string door_id_between(std::string_view a, std::string_view b) {
  return a < b ? fmt::format("{}_{}", a, b) : fmt::format("{}_{}", b, a);
}

void complete_strands_edges(std::vector<Edge>& edges) {
  std::unordered_set<std::string> taken;
  for (const Edge& e : edges) {
    if (!e.id.empty()) taken.insert(e.id);
  }
  // The next suffix to try per "<from>_<to>", so that many parallel edges stay linear, not quadratic.
  std::unordered_map<std::string, int> next_suffix;
  for (Edge& e : edges) {
    if (e.id.empty()) {
      const std::string base = e.from + "_" + e.to;
      std::string id = base;
      if (taken.contains(id)) {
        int& n = next_suffix.try_emplace(base, 2).first->second;
        do {
          id = fmt::format("{}_{}", base, n++);
        } while (taken.contains(id));
      }
      taken.insert(id);
      e.id = std::move(id);
    }
    if (!e.door && action_kind(e.action) == ActionKind::kDoor) e.door = door_id_between(e.from, e.to);
  }
}

Result<std::string> name_value(const Field& f) {
  if (f.json().is_number_integer() || f.json().is_number_unsigned()) return f.json().dump();
  return f.as_string();
}

Result<double> number_or(const Field& parent, std::string_view key, double fallback) {
  auto f = parent.optional(key);
  if (!f) return fallback;
  return f->as_number();
}

Result<double> required_number(const Field& parent, std::string_view key) {
  RONDO_ASSIGN_OR_RETURN(const Field f, parent.required(key));
  return f.as_number();
}

Result<Pose> decode_ros_pose(const Field& node) {
  RONDO_ASSIGN_OR_RETURN(const Field pose, node.required("pose"));
  RONDO_ASSIGN_OR_RETURN(const Field position, pose.required("position"));
  Pose out;
  RONDO_ASSIGN_OR_RETURN(out.x, required_number(position, "x"));
  RONDO_ASSIGN_OR_RETURN(out.y, required_number(position, "y"));
  if (auto orientation = pose.optional("orientation")) {
    if (!orientation->is_object()) return orientation->error("expected a quaternion mapping with x, y, z, w");
    std::array<double, 4> q{};  // a missing component counts as 0
    constexpr std::array<const char*, 4> kKeys = {"x", "y", "z", "w"};
    for (std::size_t i = 0; i < q.size(); ++i) {
      RONDO_ASSIGN_OR_RETURN(q[i], number_or(*orientation, kKeys[i], 0.0));
    }
    out.yaw = yaw_from_quaternion(q[0], q[1], q[2], q[3]);
  }
  return out;
}

Result<std::vector<Point2>> decode_verts(const Field& node) {
  std::vector<Point2> out;
  auto verts = node.optional("verts");
  if (!verts) return out;
  RONDO_ASSIGN_OR_RETURN(const std::vector<Field> items, verts->items());
  out.reserve(items.size());
  for (const Field& v : items) {
    Point2 p;
    RONDO_ASSIGN_OR_RETURN(p.x, required_number(v, "x"));
    RONDO_ASSIGN_OR_RETURN(p.y, required_number(v, "y"));
    out.push_back(p);
  }
  return out;
}

std::string name_from_source(const std::string& source) {
  return replace_invalid_utf8(std::filesystem::path(source).stem().string());
}

Result<Edge> decode_ros_edge(const Field& f, const std::string& from, std::string_view expected) {
  if (!f.is_object()) return f.error(expected);
  Edge edge;
  edge.from = from;
  RONDO_ASSIGN_OR_RETURN(const Field target, f.required("node"));
  RONDO_ASSIGN_OR_RETURN(edge.to, name_value(target));
  edge.action = std::string(kDefaultAction);
  if (auto action = f.optional("action")) {
    RONDO_ASSIGN_OR_RETURN(edge.action, action->as_string());
  }
  if (auto id = f.optional("edge_id")) {
    RONDO_ASSIGN_OR_RETURN(edge.id, name_value(*id));
    if (edge.id.empty()) return id->error("an edge id must not be empty");
  }
  if (auto speed = f.optional("top_vel")) {
    RONDO_ASSIGN_OR_RETURN(edge.top_speed, speed->as_number());
  }
  return edge;
}

}  // namespace rondo::map
