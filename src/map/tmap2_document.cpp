// The tmap2 form of LCAS topological_navigation: one mapping with `nodes: [{meta, node}]`.
#include <fmt/format.h>

#include <optional>

#include "map_locate.h"
#include "rondo/map/map_validation.h"
#include "rondo/map/tmap2_import.h"
#include "strands_common.h"
#include "tmap2_restrictions.h"

namespace rondo::map {
namespace {

Status decode_tolerances(const Field& node, Node& out) {
  auto properties = node.optional("properties");
  if (!properties) return {};
  if (!properties->is_object()) return properties->error("expected a mapping with the goal tolerances");
  RONDO_ASSIGN_OR_RETURN(out.xy_goal_tolerance, number_or(*properties, "xy_goal_tolerance", kDefaultXyGoalTolerance));
  RONDO_ASSIGN_OR_RETURN(out.yaw_goal_tolerance,
                         number_or(*properties, "yaw_goal_tolerance", kDefaultYawGoalTolerance));
  return {};
}

// The entry's meta without the bookkeeping keys every entry repeats, plus the node's facts that
// rondo keeps without interpreting: a non-empty localise_by_topic and its restrictions.
Result<Json> decode_meta(const Field& entry, const Field& node) {
  Json meta = Json::object();
  if (auto m = entry.optional("meta")) {
    if (!m->is_object()) return m->error("expected a mapping");
    for (auto it = m->json().begin(); it != m->json().end(); ++it) {
      if (it.key() != "map" && it.key() != "node" && it.key() != "pointset") meta[it.key()] = it.value();
    }
  }
  if (auto topic = node.optional("localise_by_topic"); topic && topic->is_string()) {
    if (!topic->json().get_ref<const std::string&>().empty()) meta["localise_by_topic"] = topic->json();
  }
  for (const char* key : kRestrictionKeys) {
    if (auto r = node.optional(key); r && !is_unrestricted(r->json())) meta[key] = r->json();
  }
  if (meta.empty()) return Json(nullptr);
  return meta;
}

struct DecodedEdge {
  Edge edge;
  Field field;
  bool top_speed_in_config = false;  // the 2021 files keep top_vel in a `config` mapping
};

Result<DecodedEdge> decode_edge(const Field& f, const std::string& from) {
  RONDO_ASSIGN_OR_RETURN(Edge decoded,
                         decode_ros_edge(f, from, "expected an edge: a mapping with 'edge_id', 'node' and 'action'"));
  DecodedEdge out{.edge = std::move(decoded), .field = f};
  // Without its own top_vel, an edge may keep it in a `config` mapping (the 2021 files).
  if (auto config = f.optional("config"); !f.optional("top_vel") && config && config->is_object()) {
    if (auto in_config = config->optional("top_vel")) {
      RONDO_ASSIGN_OR_RETURN(out.edge.top_speed, in_config->as_number());
      out.top_speed_in_config = true;
    }
  }
  return out;
}

Result<Field> node_of(const Field& entry) {
  if (!entry.is_object()) return entry.error("expected a tmap2 node entry: a mapping with 'meta' and 'node'");
  RONDO_ASSIGN_OR_RETURN(const Field node, entry.required("node"));
  if (!node.is_object()) return node.error("expected a mapping with 'name', 'pose' and 'edges'");
  return node;
}

// The map's name: `name`, else `pointset`; empty when the file has neither.
Result<std::string> decode_map_name(const Field& root) {
  for (const char* key : {"name", "pointset"}) {
    if (auto f = root.optional(key)) return name_value(*f);
  }
  return std::string();
}

// Where a problem's field (in rondo's naming) sits in a tmap2 node or edge.
std::string tmap2_path(const MapProblem& p, const DecodedEdge* edge) {
  if (p.subject == MapProblem::Subject::kEdge) {
    if (p.field == "id") return "edge_id";
    if (p.field == "to") return "node";
    if (p.field == "top_speed") return edge && edge->top_speed_in_config ? "config.top_vel" : "top_vel";
    if (p.field == "action" || p.field == "door") return "action";
    return "";
  }
  if (p.field == "pose.x") return "pose.position.x";
  if (p.field == "pose.y") return "pose.position.y";
  if (p.field == "pose.yaw") return "pose.orientation";
  if (p.field.ends_with("goal_tolerance")) return "properties." + p.field;
  if (p.field.starts_with("influence")) return "verts" + p.field.substr(std::string_view("influence").size());
  if (p.field == "meta") return "";
  return p.field;
}

}  // namespace

bool is_tmap2_document(const Document& doc) {
  const Field root = doc.root();
  if (!root.is_object() || root.has("rondo_map")) return false;
  const Json& json = root.json();
  if (auto it = json.find("nodes"); it != json.end() && it->is_array() && !it->empty() && it->front().is_object()) {
    // The first entry decides: {meta, node} is tmap2; a rondo node has its name and pose itself.
    const Json& first = it->front();
    return first.contains("node") || (first.contains("meta") && !first.contains("name") && !first.contains("pose"));
  }
  for (const char* key : {"meta", "metric_map", "pointset", "transformation"}) {
    if (root.has(key)) return true;
  }
  return false;
}

Result<Tmap2Import> tmap2_map_from_document(const Document& doc) {
  const Field root = doc.root();
  if (!root.is_object()) return root.error("expected a tmap2 map: a mapping with 'name' and 'nodes'");
  RONDO_ASSIGN_OR_RETURN(std::string name, decode_map_name(root));
  RONDO_ASSIGN_OR_RETURN(const Field node_list, root.required("nodes"));
  RONDO_ASSIGN_OR_RETURN(const std::vector<Field> entries, node_list.items());
  if (entries.empty()) return node_list.error("the map has no nodes");

  std::vector<Node> nodes;
  std::vector<Field> node_fields;
  std::vector<DecodedEdge> decoded;
  RestrictionReport restrictions;
  nodes.reserve(entries.size());
  node_fields.reserve(entries.size());
  for (const Field& entry : entries) {
    RONDO_ASSIGN_OR_RETURN(const Field node_field, node_of(entry));
    Node node;
    RONDO_ASSIGN_OR_RETURN(const Field name_field, node_field.required("name"));
    RONDO_ASSIGN_OR_RETURN(node.name, name_value(name_field));
    RONDO_ASSIGN_OR_RETURN(node.pose, decode_ros_pose(node_field));
    RONDO_RETURN_IF_ERROR(decode_tolerances(node_field, node));
    RONDO_ASSIGN_OR_RETURN(node.influence, decode_verts(node_field));
    RONDO_ASSIGN_OR_RETURN(node.meta, decode_meta(entry, node_field));
    restrictions.add(RestrictionReport::kNode, node_field, node.name);
    if (auto edge_list = node_field.optional("edges")) {
      RONDO_ASSIGN_OR_RETURN(const std::vector<Field> items, edge_list->items());
      for (const Field& f : items) {
        RONDO_ASSIGN_OR_RETURN(DecodedEdge edge, decode_edge(f, node.name));
        decoded.push_back(std::move(edge));
      }
    }
    nodes.push_back(std::move(node));
    node_fields.push_back(node_field);
  }

  std::vector<Edge> edges;
  edges.reserve(decoded.size());
  for (const DecodedEdge& d : decoded) edges.push_back(d.edge);
  complete_strands_edges(edges);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    restrictions.add(RestrictionReport::kEdge, decoded[i].field, edges[i].id);
  }

  const auto problems = find_map_problems(nodes, edges);
  if (!problems.empty()) {
    const MapProblem& p = problems.front();
    if (p.subject == MapProblem::Subject::kNode) {
      return locate_problem(node_fields[p.index], tmap2_path(p, nullptr), p.message, problems.size());
    }
    return locate_problem(decoded[p.index].field, tmap2_path(p, &decoded[p.index]),
                          fmt::format("edge {}: {}", quoted_name(edges[p.index].id), p.message), problems.size());
  }
  RONDO_ASSIGN_OR_RETURN(TopoMap map, TopoMap::build(std::move(name), std::move(nodes), std::move(edges)));
  return Tmap2Import{std::move(map), restrictions.warnings()};
}

Result<Tmap2Import> parse_tmap2(std::string_view text, const std::string& source) {
  RONDO_ASSIGN_OR_RETURN(const Document doc, Document::parse(text, DocumentFormat::kYaml, source));
  if (!is_tmap2_document(doc)) {
    return doc.root().error("expected a tmap2 map: a mapping with 'meta', 'name', 'pointset' and 'nodes'");
  }
  return tmap2_map_from_document(doc);
}

}  // namespace rondo::map
