#include "deployment_robots.h"

#include <fmt/format.h>

#include <map>
#include <set>

#include "rondo/sim/sim_world.h"

namespace rondo::app {
namespace {

// The keys of a `robots:` entry besides the kind's own (a vehicle's connection).
constexpr std::string_view kEntryKeys[] = {"name", "kind", "dock", "start", "actions", "capacity", "battery", "speed"};

Result<std::string> node_name(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(std::string name, f.as_string());
  if (name.empty()) return f.error("empty node name");
  return name;
}

// robot: {kind: sim} (the default) or a VDA 5050 vehicle (docs/vda5050.md), with `also` the keys a
// fleet's entry adds.
Status decode_kind(const Field& f, std::span<const std::string_view> also, RobotSpec& r) {
  std::string kind = "sim";
  if (auto k = f.optional("kind")) {
    RONDO_ASSIGN_OR_RETURN(kind, k->as_string());
  }
  if (kind == "sim") {
    std::vector<std::string_view> keys{"kind"};
    keys.insert(keys.end(), also.begin(), also.end());
    RONDO_RETURN_IF_ERROR(f.expect_keys(keys));
    r.vda5050.reset();
    return Status{};
  }
  if (kind != "vda5050") return f.error_at("kind", fmt::format("'{}' is not a robot kind (sim or vda5050)", kind));
  RONDO_ASSIGN_OR_RETURN(r.vda5050, vda5050::parse_vda5050_config(f, also));
  return Status{};
}

Status decode_actions(const Field& f, RobotSpec& r) {
  RONDO_ASSIGN_OR_RETURN(const std::vector<Field> items, f.items());
  if (items.empty()) return f.error("lists no action (leave it out for a robot that runs any)");
  std::vector<std::string> actions;
  for (const Field& a : items) {
    RONDO_ASSIGN_OR_RETURN(std::string name, a.as_string());
    if (name.empty()) return a.error("empty action name");
    actions.push_back(std::move(name));
  }
  r.actions = std::move(actions);
  return Status{};
}

// One entry of `robots:`: the kind's keys and the fleet's (name, dock, start, actions, capacity,
// battery, speed); a vehicle has no simulated battery or speed.
Result<RobotSpec> decode_entry(const Field& f) {
  RobotSpec r;
  r.where = f.where();
  RONDO_RETURN_IF_ERROR(decode_kind(f, kEntryKeys, r));
  RONDO_ASSIGN_OR_RETURN(const Field name, f.required("name"));
  RONDO_ASSIGN_OR_RETURN(r.name, name.as_string());
  if (r.name.empty() || r.name.find_first_of(" /\t\n") != std::string::npos)
    return name.error(fmt::format("'{}' is not a robot name (a word: no spaces or slashes)", r.name));
  if (auto v = f.optional("dock")) {
    RONDO_ASSIGN_OR_RETURN(r.dock, node_name(*v));
  }
  if (auto v = f.optional("start")) {
    RONDO_ASSIGN_OR_RETURN(r.start, node_name(*v));
  }
  if (auto v = f.optional("actions")) RONDO_RETURN_IF_ERROR(decode_actions(*v, r));
  if (auto v = f.optional("capacity")) {
    RONDO_ASSIGN_OR_RETURN(const std::int64_t n, v->as_int());
    if (n < 0 || n > 1000000) return v->error("must be between 0 (unlimited) and 1000000");
    r.capacity = static_cast<int>(n);
  }
  for (const char* key : {"battery", "speed"})
    if (r.vda5050 && f.has(key))
      return f.error_at(key, "a vda5050 vehicle reports its own; this is for robot kind sim only");
  if (auto v = f.optional("battery")) {
    RONDO_ASSIGN_OR_RETURN(r.battery, sim::decode_battery(*v));
  }
  if (auto v = f.optional("speed")) {
    RONDO_ASSIGN_OR_RETURN(r.speed, v->as_number());
    if (!(r.speed >= 0.1 && r.speed <= 10)) return v->error("must be a factor from 0.1 to 10");
  }
  return r;
}

Result<std::vector<RobotSpec>> decode_fleet(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(const std::vector<Field> items, f.items());
  if (items.empty()) return f.error("lists no robot (a deployment needs one at least)");
  std::vector<RobotSpec> robots;
  std::map<std::string, std::string> seen;  // name -> where
  for (const Field& item : items) {
    RONDO_ASSIGN_OR_RETURN(RobotSpec r, decode_entry(item));
    if (auto [it, fresh] = seen.emplace(r.name, r.where); !fresh)
      return item.error_at("name", fmt::format("two robots are named '{}' (the other at {})", r.name, it->second));
    robots.push_back(std::move(r));
  }
  return robots;
}

Result<std::vector<DockSpec>> decode_docks(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(const std::vector<Field> items, f.items());
  std::vector<DockSpec> docks;
  std::set<std::string> seen;
  for (const Field& item : items) {
    RONDO_RETURN_IF_ERROR(item.expect_keys({"node", "capacity"}));
    DockSpec dock{.node = {}, .capacity = 1, .where = item.where()};
    RONDO_ASSIGN_OR_RETURN(const Field node, item.required("node"));
    RONDO_ASSIGN_OR_RETURN(dock.node, node_name(node));
    if (!seen.insert(dock.node).second) return node.error(fmt::format("dock '{}' is listed twice", dock.node));
    if (auto v = item.optional("capacity")) {
      RONDO_ASSIGN_OR_RETURN(const std::int64_t n, v->as_int());
      if (n < 1 || n > 1000) return v->error("must be between 1 and 1000 robots");
      dock.capacity = static_cast<int>(n);
    }
    docks.push_back(std::move(dock));
  }
  return docks;
}

// No dock is home to more robots than it has room for: the first robot beyond its room is named.
Status check_dock_room(const Field& root, const Deployment& d) {
  std::map<std::string, std::vector<std::size_t>> homes;  // dock -> the robots docking there
  for (std::size_t i = 0; i < d.robots.size(); ++i) {
    const std::string& node = d.robots[i].dock.empty() ? d.dock : d.robots[i].dock;
    std::vector<std::size_t>& robots = homes[node];
    robots.push_back(i);
    const int room = d.dock_capacity(node);
    if (static_cast<int>(robots.size()) <= room) continue;
    std::string names;
    for (const std::size_t r : robots) names += (names.empty() ? "'" : ", '") + d.robots[r].name + "'";
    return root.error_at(
        fmt::format("robots[{}]", i),
        fmt::format("dock '{}' has room for {} robot{}, and {} robots have it as their dock ({}); give them other "
                    "docks, or list it under docks: with its capacity",
                    node, room, room == 1 ? "" : "s", robots.size(), names));
  }
  return Status{};
}

Result<AllocatorKind> decode_allocator(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(const std::string kind, f.as_string());
  if (kind == "fleet") return AllocatorKind::kFleet;
  if (kind == "greedy") return AllocatorKind::kGreedy;
  return f.error(fmt::format("'{}' is not an allocator (fleet or greedy)", kind));
}

}  // namespace

bool Deployment::has_vehicle() const {
  for (const RobotSpec& r : robots)
    if (r.vda5050) return true;
  return false;
}

bool Deployment::has_simulated() const {
  for (const RobotSpec& r : robots)
    if (!r.vda5050) return true;
  return false;
}

const RobotSpec* Deployment::find_robot(std::string_view robot) const {
  for (const RobotSpec& r : robots)
    if (r.name == robot) return &r;
  return nullptr;
}

int Deployment::dock_capacity(std::string_view node) const {
  for (const DockSpec& listed : docks)
    if (listed.node == node) return listed.capacity;
  return 1;
}

Status decode_robots(const Field& root, Deployment& d) {
  if (root.has("robot") && root.has("robots"))
    return root.error_at("robots", "robot and robots are both given: a fleet lists every robot under robots");
  if (auto f = root.optional("docks")) {
    RONDO_ASSIGN_OR_RETURN(d.docks, decode_docks(*f));
  }
  if (auto f = root.optional("allocator")) {
    RONDO_ASSIGN_OR_RETURN(d.allocator, decode_allocator(*f));
  }
  if (auto f = root.optional("balance")) {
    RONDO_ASSIGN_OR_RETURN(d.balance, f->as_bool());
  }
  if (auto f = root.optional("traffic")) {
    RONDO_RETURN_IF_ERROR(f->expect_keys({"reservations", "lookahead", "plan_around"}));
    if (auto r = f->optional("reservations")) {
      RONDO_ASSIGN_OR_RETURN(d.traffic.reservations, r->as_bool());
    }
    if (auto p = f->optional("plan_around")) {
      RONDO_ASSIGN_OR_RETURN(d.traffic.plan_around, p->as_bool());
    }
    if (auto l = f->optional("lookahead")) {
      RONDO_ASSIGN_OR_RETURN(const std::int64_t n, l->as_int());
      if (n < 1 || n > 100) return l->error(fmt::format("lookahead {} is not in 1..100 edges", n));
      d.traffic.lookahead = static_cast<std::size_t>(n);
    }
  }
  if (auto f = root.optional("robots")) {
    if (root.has("battery"))
      return root.error_at("battery", "with robots:, each simulated robot's battery is given in its entry");
    RONDO_ASSIGN_OR_RETURN(d.robots, decode_fleet(*f));
    return check_dock_room(root, d);
  }
  // robot: (or nothing, the simulated robot): a fleet of one named "robot".
  RobotSpec one;
  one.where = root.where();
  if (auto f = root.optional("robot")) {
    one.where = f->where();
    RONDO_RETURN_IF_ERROR(decode_kind(*f, {}, one));
  }
  if (auto f = root.optional("battery")) {
    if (one.vda5050)
      return f->error(
          "a vda5050 vehicle drives in the real building; the simulated battery is for robot kind sim only (remove "
          "it, or run the simulated robot)");
    RONDO_ASSIGN_OR_RETURN(one.battery, sim::decode_battery(*f));
  }
  d.robots = {std::move(one)};
  return Status{};
}

}  // namespace rondo::app
