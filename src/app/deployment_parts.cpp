#include "deployment_parts.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "rondo/ltl/task_formula.h"
#include "rondo/map/map_loader.h"

namespace rondo::app {
namespace {

Result<map::NodeIndex> node_on_map(const map::TopoMap& map, const std::string& node, const std::string& where,
                                   const Deployment& d) {
  if (const auto n = map.find_node(node)) return *n;
  return Error::invalid(
      fmt::format("{}: node '{}' is not on the map '{}' ({})", where, node, map.name(), d.map.string()));
}

// Each robot's dock and start (its dock unless it names one), and the listed docks, on the map.
Result<std::vector<RobotNodes>> robot_nodes(const Deployment& d, const map::TopoMap& map, map::NodeIndex dock) {
  for (const DockSpec& listed : d.docks)
    RONDO_RETURN_IF_ERROR(node_on_map(map, listed.node, listed.where + ".node", d));
  std::vector<RobotNodes> nodes;
  for (const RobotSpec& r : d.robots) {
    RobotNodes n{.dock = dock, .start = dock};
    if (!r.dock.empty()) {
      RONDO_ASSIGN_OR_RETURN(n.dock, node_on_map(map, r.dock, r.where + ".dock", d));
    }
    n.start = n.dock;
    if (!r.start.empty()) {
      RONDO_ASSIGN_OR_RETURN(n.start, node_on_map(map, r.start, r.where + ".start", d));
    }
    nodes.push_back(n);
  }
  return nodes;
}

// Simulated robots of a fleet start no more of them on a node than it holds: else they would
// collide before the run begins.
Status check_starts(const Deployment& d, const map::TopoMap& map, const std::vector<RobotNodes>& nodes) {
  std::map<map::NodeIndex, std::vector<std::size_t>> starts;  // node -> the simulated robots starting there
  for (std::size_t i = 0; i < d.robots.size(); ++i) {
    if (d.robots[i].vda5050) continue;
    std::vector<std::size_t>& here = starts[nodes[i].start];
    here.push_back(i);
    const int room = node_room(d, map, nodes[i].start);
    if (here.size() <= static_cast<std::size_t>(room)) continue;
    std::string names;
    for (const std::size_t r : here) names += (names.empty() ? "'" : ", '") + d.robots[r].name + "'";
    return Error::invalid(fmt::format(
        "{}.start: node '{}' holds {} robot{} at once, and {} simulated robots start there ({}); give them other "
        "starts, or the node a capacity on the map",
        d.robots[i].where, map.node(nodes[i].start).name, room, room == 1 ? "" : "s", here.size(), names));
  }
  return Status{};
}

// Why no robot of the deployment can do `task` (at `path` of the task file): the field's path and
// the message, or nothing.
std::optional<std::pair<std::string, std::string>> no_robot_for(const Deployment& d, const Task& task,
                                                                const std::string& path) {
  if (!task.robot.empty() && !d.find_robot(task.robot)) {
    std::string names;
    for (const RobotSpec& r : d.robots) names += (names.empty() ? "" : ", ") + r.name;
    const std::string field = path + ".robot";
    return std::pair{field,
                     fmt::format("{}: '{}' is not a robot of the deployment (it has: {})", field, task.robot, names)};
  }
  for (std::size_t i = 0; i < task.actions.size(); ++i) {
    const std::string& action = task.actions[i].name;
    bool runs = false;
    for (const RobotSpec& r : d.robots) {
      if (!task.robot.empty() && r.name != task.robot) continue;
      runs = runs || !r.actions || std::find(r.actions->begin(), r.actions->end(), action) != r.actions->end();
    }
    if (runs) continue;
    const std::string field = fmt::format("{}.actions[{}]", path, i);
    return std::pair{field, fmt::format("{}: no robot of the deployment runs '{}'{}", field, action,
                                        task.robot.empty() ? std::string()
                                                           : fmt::format(" (the task names robot '{}')", task.robot))};
  }
  return std::nullopt;
}

// Every task and routine of the file can go to a robot: errors name the file's line.
Status check_robots(const Deployment& d, const Document& doc, const TaskFile& plan) {
  const auto refuse = [&doc](const std::pair<std::string, std::string>& why) {
    const std::optional<int> line = doc.line_of(why.first);
    return Error::invalid(line ? fmt::format("{}:{}: {}", doc.source(), *line, why.second)
                               : fmt::format("{}: {}", doc.source(), why.second));
  };
  for (std::size_t i = 0; i < plan.tasks.size(); ++i)
    if (auto why = no_robot_for(d, plan.tasks[i], fmt::format("tasks[{}]", i))) return refuse(*why);
  for (std::size_t i = 0; i < plan.routines.size(); ++i)
    if (auto why = no_robot_for(d, plan.routines[i].task, fmt::format("routines[{}].task", i))) return refuse(*why);
  return Status{};
}

}  // namespace

int node_room(const Deployment& d, const map::TopoMap& map, map::NodeIndex node) {
  const map::Node& n = map.node(node);
  return std::max(n.capacity, d.dock_capacity(n.name));
}

Result<DeploymentParts> load_parts(const Deployment& d) {
  RONDO_ASSIGN_OR_RETURN(map::TopoMap map, map::load_map(d.map));
  const std::optional<map::NodeIndex> dock = map.find_node(d.dock);
  if (!dock) {
    return Error::invalid(fmt::format("{}: node '{}' is not on the map '{}' ({})", d.dock_where, d.dock, map.name(),
                                      d.map.string()));
  }
  if (!d.executor.return_to.empty() && !map.find_node(d.executor.return_to))
    return Error::invalid(fmt::format("{}: executor.return_to: node '{}' is not on the map '{}'", d.file.string(),
                                      d.executor.return_to, map.name()));
  RONDO_ASSIGN_OR_RETURN(std::vector<RobotNodes> robots, robot_nodes(d, map, *dock));
  RONDO_RETURN_IF_ERROR(check_starts(d, map, robots));
  TaskFile plan;
  if (d.routines) {
    const auto known = [&map](std::string_view node) { return map.find_node(node).has_value(); };
    const PlaceCheck places{.known = known, .map_name = map.name(), .spec = [&](std::string_view f) {
                              return ltl::check_task_formula(f, known, map.name());
                            }};
    RONDO_ASSIGN_OR_RETURN(const Document doc, Document::load(*d.routines));
    RONDO_ASSIGN_OR_RETURN(plan, decode_task_file(doc, &places));
    RONDO_RETURN_IF_ERROR(check_robots(d, doc, plan));
  }
  // The world and the requests decoders check their nodes against the map themselves.
  std::optional<sim::SimWorld> world;
  if (d.world) {
    RONDO_ASSIGN_OR_RETURN(world, sim::load_world(*d.world, map, d.zone));
    // A fleet of one: the deployment's battery replaces the world's (a fleet's robots carry their own).
    if (d.robots.size() == 1 && d.robots.front().battery) world->battery = *d.robots.front().battery;
  }
  std::optional<sim::RequestGenerator> people;
  if (d.requests) { RONDO_ASSIGN_OR_RETURN(people, sim::RequestGenerator::load(*d.requests, map, d.zone)); }
  std::optional<lang::Places> places;
  if (d.places) { RONDO_ASSIGN_OR_RETURN(places, lang::Places::load(*d.places, map)); }
  return DeploymentParts{
      std::move(map),    *dock,  std::move(robots), std::move(plan), std::move(world), std::move(people),
      std::move(places), nullptr};
}

}  // namespace rondo::app
