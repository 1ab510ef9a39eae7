// The STRANDS YAML and JSON forms: a list of {meta, node} entries, one per node, with its edges.
#include <fmt/format.h>

#include "map_locate.h"
#include "rondo/map/map_validation.h"
#include "rondo/map/strands_import.h"
#include "strands_common.h"

namespace rondo::map {
namespace {

// Where an entry's node object is: entry.node, or the entry itself when it is a bare node.
Result<Field> node_of(const Field& entry) {
  if (!entry.is_object()) return entry.error("expected a map entry: a mapping with 'meta' and 'node'");
  if (auto node = entry.optional("node"); node && node->is_object()) return *node;
  if (entry.has("name") && entry.has("pose")) return entry;
  return entry.error("expected a map entry with a 'node' mapping (or a node with 'name' and 'pose')");
}

// The entry's meta block without the bookkeeping keys every entry repeats.
Result<Json> decode_meta(const Field& entry, const Field& node) {
  Json meta = Json::object();
  if (entry.json().is_object() && &entry.json() != &node.json()) {
    if (auto m = entry.optional("meta")) {
      if (!m->is_object()) return m->error("expected a mapping");
      for (auto it = m->json().begin(); it != m->json().end(); ++it) {
        if (it.key() != "map" && it.key() != "node" && it.key() != "pointset") meta[it.key()] = it.value();
      }
    }
  }
  if (auto topic = node.optional("localise_by_topic"); topic && topic->is_string()) {
    if (!topic->json().get_ref<const std::string&>().empty()) meta["localise_by_topic"] = topic->json();
  }
  if (meta.empty()) return Json(nullptr);
  return meta;
}


// The node's name: node.name, or for older exports the entry's meta.node.
Result<std::string> decode_name(const Field& entry, const Field& node) {
  if (auto f = node.optional("name")) return name_value(*f);
  if (auto meta = entry.optional("meta"); meta && meta->optional("node")) return name_value(*meta->optional("node"));
  return node.error("missing field 'name'");
}

// Where a problem's field (in rondo's naming) sits in a STRANDS node or edge.
std::string strands_path(const MapProblem& p) {
  if (p.subject == MapProblem::Subject::kEdge) {
    if (p.field == "id") return "edge_id";
    if (p.field == "to") return "node";
    if (p.field == "top_speed") return "top_vel";
    if (p.field == "action" || p.field == "door") return "action";
    return "";
  }
  if (p.field == "pose.x") return "pose.position.x";
  if (p.field == "pose.y") return "pose.position.y";
  if (p.field == "pose.yaw") return "pose.orientation";
  if (p.field.starts_with("influence")) return "verts" + p.field.substr(std::string_view("influence").size());
  if (p.field == "meta") return "";
  return p.field;
}

}  // namespace

Result<TopoMap> strands_map_from_document(const Document& doc) {
  const Field root = doc.root();
  std::vector<Field> entries;
  if (root.is_array()) {
    RONDO_ASSIGN_OR_RETURN(entries, root.items());
  } else if (root.is_object()) {
    entries.push_back(root);
  } else {
    return root.error("expected a STRANDS topological map: a list of entries with 'meta' and 'node'");
  }
  if (entries.empty()) return root.error("the map has no nodes");

  std::string name;
  std::vector<Node> nodes;
  std::vector<Field> node_fields;
  std::vector<Edge> edges;
  std::vector<Field> edge_fields;
  for (const Field& entry : entries) {
    RONDO_ASSIGN_OR_RETURN(const Field node_field, node_of(entry));
    Node node;
    RONDO_ASSIGN_OR_RETURN(node.name, decode_name(entry, node_field));
    if (name.empty()) {
      if (auto pointset = node_field.optional("pointset"); pointset && pointset->is_string()) {
        name = pointset->json().get<std::string>();
      }
    }
    RONDO_ASSIGN_OR_RETURN(node.pose, decode_ros_pose(node_field));
    RONDO_ASSIGN_OR_RETURN(node.xy_goal_tolerance, number_or(node_field, "xy_goal_tolerance", kDefaultXyGoalTolerance));
    RONDO_ASSIGN_OR_RETURN(node.yaw_goal_tolerance,
                           number_or(node_field, "yaw_goal_tolerance", kDefaultYawGoalTolerance));
    RONDO_ASSIGN_OR_RETURN(node.influence, decode_verts(node_field));
    RONDO_ASSIGN_OR_RETURN(node.meta, decode_meta(entry, node_field));
    if (auto edge_list = node_field.optional("edges")) {
      RONDO_ASSIGN_OR_RETURN(const std::vector<Field> items, edge_list->items());
      for (const Field& f : items) {
        RONDO_ASSIGN_OR_RETURN(Edge edge, decode_ros_edge(f, node.name, "expected an edge: a mapping with 'node' and 'action'"));
        edges.push_back(std::move(edge));
        edge_fields.push_back(f);
      }
    }
    nodes.push_back(std::move(node));
    node_fields.push_back(node_field);
  }
  if (name.empty() && root.is_array()) {
    // Older exports keep the pointset only in the meta block.
    if (auto meta = entries.front().optional("meta"); meta && meta->is_object()) {
      if (auto pointset = meta->optional("pointset"); pointset && pointset->is_string()) {
        name = pointset->json().get<std::string>();
      }
    }
  }
  complete_strands_edges(edges);

  const auto problems = find_map_problems(nodes, edges);
  if (!problems.empty()) {
    const MapProblem& p = problems.front();
    if (p.subject == MapProblem::Subject::kNode) {
      return locate_problem(node_fields[p.index], strands_path(p), p.message, problems.size());
    }
    return locate_problem(edge_fields[p.index], strands_path(p),
                          fmt::format("edge {}: {}", quoted_name(edges[p.index].id), p.message), problems.size());
  }
  return TopoMap::build(std::move(name), std::move(nodes), std::move(edges));
}

Result<TopoMap> parse_strands_yaml(std::string_view text, const std::string& source) {
  RONDO_ASSIGN_OR_RETURN(const Document doc, Document::parse(text, DocumentFormat::kYaml, source));
  return strands_map_from_document(doc);
}

Result<TopoMap> parse_strands_json(std::string_view text, const std::string& source) {
  RONDO_ASSIGN_OR_RETURN(const Document doc, Document::parse(text, DocumentFormat::kJson, source));
  return strands_map_from_document(doc);
}

}  // namespace rondo::map
