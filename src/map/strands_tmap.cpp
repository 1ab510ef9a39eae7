// The legacy STRANDS `.tmap` text form:
//
//   node:
//   	WayPoint6
//   	waypoint:
//   		2.208513,2.052180,0.000000,-0.000000,-0.000000,-0.502437,0.864614    x,y,z,qx,qy,qz,qw
//   	edges:
//   		 Station, human_aware_navigation                                       target, action
//   	vertices:
//   		0.690000,0.287000                                                     x,y
//
// Indentation is not significant: the `node:` line and the section headers give the structure.
// Blank lines, lines starting with '#' and Windows line ends are accepted.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <vector>

#include "map_locate.h"
#include "rondo/map/map_validation.h"
#include "rondo/map/strands_import.h"
#include "strands_common.h"
#include "rondo/core/utf8.h"

namespace rondo::map {
namespace {

std::string_view trim(std::string_view s) {
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_commas(std::string_view s) {
  std::vector<std::string_view> parts;
  while (true) {
    const auto comma = s.find(',');
    parts.push_back(trim(s.substr(0, comma)));
    if (comma == std::string_view::npos) return parts;
    s.remove_prefix(comma + 1);
  }
}

std::optional<double> parse_number(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || p != s.data() + s.size() || s.empty() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// Line content for a message: trimmed, cut short, control characters shown as '?'.
std::string shown(std::string_view line) {
  return quoted_name(std::string(trim(line)));
}

class TmapParser {
 public:
  explicit TmapParser(const std::string& source) : source_(source) {}

  Result<TopoMap> parse(std::string_view text) {
    // Like every text format rondo reads, a .tmap is UTF-8: names must survive conversion.
    if (auto bad = first_invalid_utf8(text)) {
      const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(*bad), '\n');
      return error(static_cast<int>(line), "the text is not valid UTF-8");
    }
    int line_number = 0;
    for (std::size_t pos = 0; pos <= text.size();) {
      const auto newline = text.find('\n', pos);
      const std::size_t end = newline == std::string_view::npos ? text.size() : newline;
      if (auto s = parse_line(trim(text.substr(pos, end - pos)), ++line_number); !s) return s.error();
      pos = end + 1;
    }
    if (auto s = finish_node(); !s) return s.error();
    if (nodes_.empty()) return Error::invalid(source_ + ": no 'node:' blocks: this is not a STRANDS .tmap map");
    complete_strands_edges(edges_);
    const auto problems = find_map_problems(nodes_, edges_);
    if (!problems.empty()) {
      const MapProblem& p = problems.front();
      const int line = p.subject == MapProblem::Subject::kNode ? node_lines_[p.index] : edge_lines_[p.index];
      std::string message = fmt::format("{}:{}: {}", source_, line, describe(p, nodes_, edges_));
      if (problems.size() > 1) message += fmt::format(" (and {} more problems)", problems.size() - 1);
      return Error::invalid(std::move(message));
    }
    return TopoMap::build(name_from_source(source_), std::move(nodes_), std::move(edges_));
  }

 private:
  enum class Section { kBeforeFirstNode, kName, kNodeBody, kWaypoint, kEdges, kVertices };

  Error error(int line, std::string_view what) const {
    return Error::invalid(fmt::format("{}:{}: {}", source_, line, what));
  }

  Status parse_line(std::string_view line, int n) {
    if (line.empty() || line.front() == '#') return {};
    if (line.starts_with("node:")) {
      if (auto s = finish_node(); !s) return s.error();
      node_ = Node{};
      node_line_ = n;
      has_waypoint_ = false;
      const std::string_view rest = trim(line.substr(5));
      if (rest.empty()) {
        section_ = Section::kName;
      } else {
        node_.name = std::string(rest);
        section_ = Section::kNodeBody;
      }
      return {};
    }
    switch (section_) {
      case Section::kBeforeFirstNode:
        return error(n, fmt::format("expected 'node:' to start the first node, found {}", shown(line)));
      case Section::kName:
        node_.name = std::string(line);
        section_ = Section::kNodeBody;
        return {};
      default:
        break;
    }
    if (line == "waypoint:") {
      if (has_waypoint_)
        return error(n, fmt::format("node {} has a second 'waypoint:' section", quoted_name(node_.name)));
      section_ = Section::kWaypoint;
      return {};
    }
    if (line == "edges:") {
      section_ = Section::kEdges;
      return {};
    }
    if (line == "vertices:") {
      section_ = Section::kVertices;
      return {};
    }
    if (line.back() == ':' && line.find(',') == std::string_view::npos) {
      return error(n, fmt::format("unknown section {} (expected waypoint:, edges: or vertices:)", shown(line)));
    }
    switch (section_) {
      case Section::kWaypoint:
        return parse_waypoint(line, n);
      case Section::kEdges:
        return parse_edge(line, n);
      case Section::kVertices:
        return parse_vertex(line, n);
      default:
        return error(n, fmt::format("expected 'waypoint:', 'edges:' or 'vertices:' in node {}, found {}",
                                    quoted_name(node_.name), shown(line)));
    }
  }

  Status parse_waypoint(std::string_view line, int n) {
    if (has_waypoint_) {
      return error(n, fmt::format("node {} has a second waypoint line {}", quoted_name(node_.name), shown(line)));
    }
    const auto parts = split_commas(line);
    if (parts.size() != 7) {
      return error(n, fmt::format("a waypoint is 7 numbers x,y,z,qx,qy,qz,qw; found {} fields in {}", parts.size(),
                                  shown(line)));
    }
    double v[7] = {};
    for (std::size_t i = 0; i < 7; ++i) {
      auto number = parse_number(parts[i]);
      if (!number) {
        return error(n, fmt::format("waypoint field {} of node {} is not a finite number: {}", i + 1,
                                    quoted_name(node_.name), shown(parts[i])));
      }
      v[i] = *number;
    }
    node_.pose = {v[0], v[1], yaw_from_quaternion(v[3], v[4], v[5], v[6])};
    has_waypoint_ = true;
    return {};
  }

  Status parse_edge(std::string_view line, int n) {
    const auto parts = split_commas(line);
    if (parts.size() != 2 || parts[0].empty() || parts[1].empty()) {
      return error(n, fmt::format("an edge line is 'target, action', found {}", shown(line)));
    }
    Edge edge;
    edge.from = node_.name;
    edge.to = std::string(parts[0]);
    edge.action = std::string(parts[1]);
    edges_.push_back(std::move(edge));
    edge_lines_.push_back(n);
    return {};
  }

  Status parse_vertex(std::string_view line, int n) {
    const auto parts = split_commas(line);
    if (parts.size() != 2) return error(n, fmt::format("a vertex is 'x,y', found {}", shown(line)));
    auto x = parse_number(parts[0]);
    auto y = parse_number(parts[1]);
    if (!x || !y) return error(n, fmt::format("a vertex is two finite numbers 'x,y', found {}", shown(line)));
    node_.influence.push_back({*x, *y});
    return {};
  }

  Status finish_node() {
    if (section_ == Section::kBeforeFirstNode) return {};
    if (section_ == Section::kName) return error(node_line_, "'node:' is not followed by the node's name");
    if (!has_waypoint_) {
      return error(node_line_,
                   fmt::format("node {} has no 'waypoint:' line (x,y,z,qx,qy,qz,qw)", quoted_name(node_.name)));
    }
    nodes_.push_back(std::move(node_));
    node_lines_.push_back(node_line_);
    node_ = Node{};
    section_ = Section::kBeforeFirstNode;
    return {};
  }

  const std::string& source_;
  Section section_ = Section::kBeforeFirstNode;
  Node node_;
  int node_line_ = 0;
  bool has_waypoint_ = false;
  std::vector<Node> nodes_;
  std::vector<int> node_lines_;
  std::vector<Edge> edges_;
  std::vector<int> edge_lines_;
};

}  // namespace

Result<TopoMap> parse_strands_tmap(std::string_view text, const std::string& source) {
  return TmapParser(source).parse(text);
}

}  // namespace rondo::map
