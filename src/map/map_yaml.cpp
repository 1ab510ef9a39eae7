#include "rondo/map/map_yaml.h"

#include <fmt/format.h>

#include "map_locate.h"
#include "rondo/map/map_validation.h"

namespace rondo::map {
namespace {

Result<double> required_number(const Field& parent, std::string_view key) {
  RONDO_ASSIGN_OR_RETURN(const Field f, parent.required(key));
  return f.as_number();
}

Result<double> optional_number(const Field& parent, std::string_view key, double fallback) {
  auto f = parent.optional(key);
  if (!f) return fallback;
  return f->as_number();
}

Result<std::string> required_text(const Field& parent, std::string_view key) {
  RONDO_ASSIGN_OR_RETURN(const Field f, parent.required(key));
  return f.as_string();
}

Result<std::optional<std::string>> optional_text(const Field& parent, std::string_view key) {
  auto f = parent.optional(key);
  if (!f) return std::optional<std::string>();
  RONDO_ASSIGN_OR_RETURN(std::string text, f->as_string());
  return std::optional<std::string>(std::move(text));
}

// `capacity`: a whole number of robots, 1 (the default) to kMaxNodeCapacity.
Result<int> decode_capacity(const Field& node) {
  auto f = node.optional("capacity");
  if (!f) return 1;
  auto n = f->as_int();
  if (!n || *n < 1 || *n > kMaxNodeCapacity) {
    return f->error(fmt::format("expected a whole number of robots the place holds at once, from 1 to {}{}",
                                kMaxNodeCapacity, n ? fmt::format(", not {}", *n) : std::string()));
  }
  return static_cast<int>(*n);
}

// `narrow`: single or one_way; absent, robots pass each other freely.
Result<Narrow> decode_narrow(const Field& edge) {
  auto f = edge.optional("narrow");
  if (!f) return Narrow::kNone;
  auto word = f->as_string();
  const std::optional<Narrow> narrow = word ? narrow_from_string(*word) : std::nullopt;
  if (!narrow) return f->error("expected single (one robot at a time) or one_way (one direction at a time)");
  return *narrow;
}

Result<Node> decode_node(const Field& f) {
  RONDO_RETURN_IF_ERROR(
      f.expect_keys({"name", "pose", "xy_goal_tolerance", "yaw_goal_tolerance", "influence", "meta", "capacity"}));
  Node node;
  RONDO_ASSIGN_OR_RETURN(node.name, required_text(f, "name"));
  RONDO_ASSIGN_OR_RETURN(const Field pose, f.required("pose"));
  RONDO_RETURN_IF_ERROR(pose.expect_keys({"x", "y", "yaw"}));
  RONDO_ASSIGN_OR_RETURN(node.pose.x, required_number(pose, "x"));
  RONDO_ASSIGN_OR_RETURN(node.pose.y, required_number(pose, "y"));
  RONDO_ASSIGN_OR_RETURN(node.pose.yaw, optional_number(pose, "yaw", 0.0));
  RONDO_ASSIGN_OR_RETURN(node.xy_goal_tolerance, optional_number(f, "xy_goal_tolerance", kDefaultXyGoalTolerance));
  RONDO_ASSIGN_OR_RETURN(node.yaw_goal_tolerance, optional_number(f, "yaw_goal_tolerance", kDefaultYawGoalTolerance));
  if (auto influence = f.optional("influence")) {
    RONDO_ASSIGN_OR_RETURN(const std::vector<Field> vertices, influence->items());
    for (const Field& v : vertices) {
      RONDO_RETURN_IF_ERROR(v.expect_keys({"x", "y"}));
      Point2 p;
      RONDO_ASSIGN_OR_RETURN(p.x, required_number(v, "x"));
      RONDO_ASSIGN_OR_RETURN(p.y, required_number(v, "y"));
      node.influence.push_back(p);
    }
  }
  if (auto meta = f.optional("meta")) {
    if (!meta->is_object()) return meta->error("expected a mapping of free-form facts about the place");
    node.meta = meta->json();
  }
  RONDO_ASSIGN_OR_RETURN(node.capacity, decode_capacity(f));
  return node;
}

Result<Edge> decode_edge(const Field& f) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"id", "from", "to", "action", "top_speed", "door", "narrow"}));
  Edge edge;
  RONDO_ASSIGN_OR_RETURN(edge.from, required_text(f, "from"));
  RONDO_ASSIGN_OR_RETURN(edge.to, required_text(f, "to"));
  RONDO_ASSIGN_OR_RETURN(const std::optional<std::string> id, optional_text(f, "id"));
  edge.id = id.value_or(edge.from + "_" + edge.to);
  RONDO_ASSIGN_OR_RETURN(const std::optional<std::string> action, optional_text(f, "action"));
  edge.action = action.value_or(std::string(kDefaultAction));
  if (auto speed = f.optional("top_speed")) {
    RONDO_ASSIGN_OR_RETURN(edge.top_speed, speed->as_number());
  }
  RONDO_ASSIGN_OR_RETURN(edge.door, optional_text(f, "door"));
  RONDO_ASSIGN_OR_RETURN(edge.narrow, decode_narrow(f));
  return edge;
}

Status check_version(const Field& root) {
  auto version = root.optional("rondo_map");
  if (!version) return {};
  auto v = version->as_int();
  if (!v) return version->error("expected the format version, an integer such as 1");
  if (*v != kMapFormatVersion) {
    return version->error(
        fmt::format("format version {} is not supported: this build reads version {}", *v, kMapFormatVersion));
  }
  return {};
}

}  // namespace

bool is_rondo_map_document(const Document& doc) {
  const Field root = doc.root();
  return root.is_object() && (root.has("rondo_map") || root.has("nodes"));
}

Result<TopoMap> map_from_document(const Document& doc) {
  const Field root = doc.root();
  if (!root.is_object()) {
    return root.error("expected a rondo map: a mapping with 'rondo_map', 'name', 'nodes' and 'edges'");
  }
  RONDO_RETURN_IF_ERROR(root.expect_keys({"rondo_map", "name", "nodes", "edges"}));
  RONDO_RETURN_IF_ERROR(check_version(root));
  RONDO_ASSIGN_OR_RETURN(const std::optional<std::string> name, optional_text(root, "name"));
  RONDO_ASSIGN_OR_RETURN(const Field nodes_field, root.required("nodes"));
  RONDO_ASSIGN_OR_RETURN(const std::vector<Field> node_items, nodes_field.items());
  if (node_items.empty()) return nodes_field.error("a map needs at least one node");
  std::vector<Node> nodes;
  nodes.reserve(node_items.size());
  for (const Field& f : node_items) {
    RONDO_ASSIGN_OR_RETURN(Node node, decode_node(f));
    nodes.push_back(std::move(node));
  }
  std::vector<Field> edge_items;
  if (auto edges_field = root.optional("edges")) {
    RONDO_ASSIGN_OR_RETURN(edge_items, edges_field->items());
  }
  std::vector<Edge> edges;
  edges.reserve(edge_items.size());
  for (const Field& f : edge_items) {
    RONDO_ASSIGN_OR_RETURN(Edge edge, decode_edge(f));
    edges.push_back(std::move(edge));
  }
  const auto problems = find_map_problems(nodes, edges);
  if (!problems.empty()) {
    const MapProblem& p = problems.front();
    const Field& item = p.subject == MapProblem::Subject::kNode ? node_items[p.index] : edge_items[p.index];
    return locate_problem(item, p, problems.size());
  }
  return TopoMap::build(name.value_or(""), std::move(nodes), std::move(edges));
}

Result<TopoMap> parse_map_yaml(std::string_view text, const std::string& source) {
  RONDO_ASSIGN_OR_RETURN(const Document doc, Document::parse(text, DocumentFormat::kYaml, source));
  return map_from_document(doc);
}

Json map_to_json(const TopoMap& map) {
  Json nodes = Json::array();
  for (const Node& n : map.nodes()) {
    Json j = Json::object();
    j["name"] = n.name;
    j["pose"] = Json{{"x", n.pose.x}, {"y", n.pose.y}, {"yaw", n.pose.yaw}};
    j["xy_goal_tolerance"] = n.xy_goal_tolerance;
    j["yaw_goal_tolerance"] = n.yaw_goal_tolerance;
    if (!n.influence.empty()) {
      Json vertices = Json::array();
      for (const Point2& v : n.influence) vertices.push_back(Json{{"x", v.x}, {"y", v.y}});
      j["influence"] = std::move(vertices);
    }
    if (!n.meta.is_null()) j["meta"] = n.meta;
    if (n.capacity != 1) j["capacity"] = n.capacity;
    nodes.push_back(std::move(j));
  }
  Json edges = Json::array();
  for (const Edge& e : map.edges()) {
    Json j = Json::object();
    j["id"] = e.id;
    j["from"] = e.from;
    j["to"] = e.to;
    j["action"] = e.action;
    if (e.top_speed) j["top_speed"] = *e.top_speed;
    if (e.door) j["door"] = *e.door;
    if (e.narrow != Narrow::kNone) j["narrow"] = to_string(e.narrow);
    edges.push_back(std::move(j));
  }
  Json out = Json::object();
  out["rondo_map"] = kMapFormatVersion;
  out["name"] = map.name();
  out["nodes"] = std::move(nodes);
  out["edges"] = std::move(edges);
  return out;
}

std::string write_map_yaml(const TopoMap& map) {
  return fmt::format("# rondo topological map, format version {} (docs/map-format.md)\n", kMapFormatVersion) +
         to_yaml(map_to_json(map));
}

}  // namespace rondo::map
