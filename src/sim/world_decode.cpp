#include <fmt/format.h>

#include <algorithm>

#include "decode_util.h"
#include "parametric_decode.h"
#include "rondo/core/traversal.h"
#include "rondo/sim/parametric_world.h"
#include "rondo/sim/replay_world.h"
#include "rondo/sim/sim_world.h"

namespace rondo::sim {
namespace {

Result<ActionProfile> decode_profile(const Field& f, ActionProfile p) {
  RONDO_RETURN_IF_ERROR(f.expect_keys(
      {"sigma", "failure_probability", "overrun_probability", "overrun_factor", "non_interruptible"}));
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "sigma", 0, 3, p.sigma));
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "failure_probability", 0, 1, p.failure_probability));
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "overrun_probability", 0, 1, p.overrun_probability));
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "overrun_factor", 1, 1000, p.overrun_factor));
  RONDO_RETURN_IF_ERROR(detail::read_duration(f, "non_interruptible", p.non_interruptible));
  return p;
}

// `actions: {default: {...}, talk: {...}}`: named profiles start from the default one.
Result<ActionModel> decode_actions(const Field& f) {
  ActionProfile fallback;
  if (auto d = f.optional("default")) {
    RONDO_ASSIGN_OR_RETURN(fallback, decode_profile(*d, fallback));
  }
  RONDO_ASSIGN_OR_RETURN(auto members, f.members());
  std::map<std::string, ActionProfile> by_name;
  for (const auto& [name, value] : members) {
    if (name == "default") continue;
    RONDO_ASSIGN_OR_RETURN(by_name[name], decode_profile(value, fallback));
  }
  return ActionModel(fallback, std::move(by_name));
}

Result<DoorSensor> decode_door_sensor(const Field& f) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"range", "miss_rate"}));
  DoorSensor d{.enabled = true};
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "range", 0, 1000, d.range_m));
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "miss_rate", 0, 1, d.miss_rate));
  return d;
}

// traffic: {hold_timeout: 60s}: how long a robot waits for another to clear its way.
Result<TrafficOptions> decode_traffic(const Field& f) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"hold_timeout"}));
  TrafficOptions traffic;
  if (auto v = f.optional("hold_timeout")) {
    RONDO_ASSIGN_OR_RETURN(traffic.hold_timeout, v->as_duration());
    if (traffic.hold_timeout <= Duration{0} || traffic.hold_timeout > hours(24))
      return v->error("must be a duration above 0 and at most 24h, such as 60s");
  }
  return traffic;
}

Result<Confirmation> decode_confirmation(const Field& f, const map::TopoMap& map) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"actions", "default", "places"}));
  Confirmation c;
  if (auto actions = f.optional("actions")) {
    c.actions.clear();
    RONDO_ASSIGN_OR_RETURN(auto items, actions->items());
    for (const auto& item : items) {
      RONDO_ASSIGN_OR_RETURN(auto name, item.as_string());
      if (name.empty()) return item.error("an action needs a name");
      c.actions.push_back(std::move(name));
    }
  }
  if (f.optional("default")) {
    Duration d{0};
    RONDO_RETURN_IF_ERROR(detail::read_duration(f, "default", d));
    if (d <= Duration{0}) return f.error_at("default", "must be positive");
    c.fallback = d;
  }
  if (auto places = f.optional("places")) {
    RONDO_ASSIGN_OR_RETURN(auto entries, places->members());
    for (const auto& [name, value] : entries) {
      if (!map.find_node(name)) return value.error(fmt::format("map '{}' has no node '{}'", map.name(), name));
      Duration d{0};
      RONDO_RETURN_IF_ERROR(detail::read_duration(*places, name, d));
      if (d <= Duration{0}) return value.error("must be positive");
      c.places[name] = d;
    }
  }
  return c;
}

Result<std::unique_ptr<EdgeWorld>> decode_parametric(const Field& root, const map::TopoMap& map, const TimeZone& zone) {
  RONDO_RETURN_IF_ERROR(root.expect_keys({"kind", "speed", "failure_probability", "noise", "failed_duration", "bursts",
                                          "effects", "actions", "battery", "door_sensor", "confirmation", "traffic"}));
  ParametricSpec spec;
  RONDO_RETURN_IF_ERROR(detail::decode_edge_settings(root, true, spec));
  if (auto effects = root.optional("effects")) {
    RONDO_ASSIGN_OR_RETURN(auto items, effects->items());
    for (const auto& item : items) {
      RONDO_ASSIGN_OR_RETURN(auto effect, detail::decode_effect(item, map, zone));
      spec.effects.push_back(std::move(effect));
    }
  }
  return std::unique_ptr<EdgeWorld>(std::make_unique<ParametricWorld>(map, zone, std::move(spec)));
}

Result<std::unique_ptr<EdgeWorld>> decode_replay(const Field& root, const std::filesystem::path& base,
                                                 const map::TopoMap& map, const TimeZone& zone) {
  RONDO_RETURN_IF_ERROR(root.expect_keys({"kind", "logs", "log_timezone", "window", "prior", "actions", "battery",
                                          "door_sensor", "confirmation", "traffic"}));
  ReplayOptions options;
  RONDO_ASSIGN_OR_RETURN(auto logs_field, root.required("logs"));
  RONDO_ASSIGN_OR_RETURN(auto logs, logs_field.as_string());
  if (auto tz = root.optional("log_timezone")) {
    RONDO_ASSIGN_OR_RETURN(auto name, tz->as_string());
    auto log_zone = TimeZone::named(name);
    if (!log_zone) return tz->error(log_zone.error().message);
    options.log_zone = *log_zone;
  }
  RONDO_RETURN_IF_ERROR(detail::read_duration(root, "window", options.window));
  if (options.window <= Duration{0}) return root.error_at("window", "must be positive");
  if (auto prior = root.optional("prior")) {
    RONDO_RETURN_IF_ERROR(prior->expect_keys({"speed", "failure_probability", "noise", "failed_duration"}));
    RONDO_RETURN_IF_ERROR(detail::decode_edge_settings(*prior, false, options.prior));
  }
  const std::filesystem::path dir = base / logs;
  if (!std::filesystem::is_directory(dir)) {
    return logs_field.error(fmt::format("'{}' is not a folder of edge logs", dir.string()));
  }
  auto log = read_witham_logs(dir);
  if (!log) return logs_field.error(log.error().message);
  if (log->empty()) return logs_field.error(fmt::format("no '*.data' edge logs in '{}'", dir.string()));
  return std::unique_ptr<EdgeWorld>(std::make_unique<ReplayWorld>(map, *log, zone, std::move(options)));
}

}  // namespace

Result<SimWorld> decode_world(const Document& doc, const std::filesystem::path& base, const map::TopoMap& map,
                              const TimeZone& zone) {
  const Field root = doc.root();
  if (!root.is_object()) return root.error("expected a world: a mapping with 'kind: parametric' or 'kind: replay'");
  RONDO_ASSIGN_OR_RETURN(auto kind_field, root.required("kind"));
  RONDO_ASSIGN_OR_RETURN(auto kind, kind_field.as_string());
  SimWorld world;
  if (kind == "parametric") {
    RONDO_ASSIGN_OR_RETURN(world.edges, decode_parametric(root, map, zone));
  } else if (kind == "replay") {
    RONDO_ASSIGN_OR_RETURN(world.edges, decode_replay(root, base, map, zone));
  } else {
    return kind_field.error("unknown kind '" + kind + "' (expected parametric or replay)");
  }
  if (auto actions = root.optional("actions")) {
    RONDO_ASSIGN_OR_RETURN(world.actions, decode_actions(*actions));
  }
  if (auto battery = root.optional("battery")) {
    RONDO_ASSIGN_OR_RETURN(world.battery, decode_battery(*battery));
  }
  if (auto sensor = root.optional("door_sensor")) {
    RONDO_ASSIGN_OR_RETURN(world.door_sensor, decode_door_sensor(*sensor));
  }
  if (auto confirmation = root.optional("confirmation")) {
    RONDO_ASSIGN_OR_RETURN(world.confirmation, decode_confirmation(*confirmation, map));
  }
  if (auto traffic = root.optional("traffic")) {
    RONDO_ASSIGN_OR_RETURN(world.traffic, decode_traffic(*traffic));
  }
  return world;
}

Result<BatteryModel> decode_battery(const Field& f) {
  RONDO_RETURN_IF_ERROR(
      f.expect_keys({"initial", "moving_per_hour", "acting_per_hour", "idle_per_hour", "charging_per_hour", "per_metre",
                      "rescue_after"}));
  BatteryModel b;
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "initial", 0, 1, b.initial));
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "moving_per_hour", 0, 100, b.moving_per_hour));
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "acting_per_hour", 0, 100, b.acting_per_hour));
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "idle_per_hour", 0, 100, b.idle_per_hour));
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "charging_per_hour", 0, 100, b.charging_per_hour));
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "per_metre", 0, 1, b.per_metre));
  if (auto v = f.optional("rescue_after")) {
    RONDO_ASSIGN_OR_RETURN(b.rescue_after, v->as_duration());
    if (*b.rescue_after <= Duration{0}) return v->error("must be positive");
  }
  return b;
}

std::optional<Duration> Confirmation::at(const std::string& action, const std::string& place) const {
  if (std::find(actions.begin(), actions.end(), action) == actions.end()) return std::nullopt;
  if (const auto it = places.find(place); it != places.end()) return it->second;
  return fallback;
}

Result<SimWorld> load_world(const std::filesystem::path& file, const map::TopoMap& map, const TimeZone& zone) {
  RONDO_ASSIGN_OR_RETURN(auto doc, Document::load(file));
  return decode_world(doc, file.parent_path(), map, zone);
}

}  // namespace rondo::sim
