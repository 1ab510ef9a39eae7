// POST /api/v1/observations: what the building's own sensors see (a door open or closed, an edge
// blocked, a person present), handed to the executor as the robot's observations are: stored,
// learned from (door models) and acted on (broken assumptions, opportunities).
#include <fmt/format.h>

#include <algorithm>

#include "api.h"

namespace rondo::service {
namespace {

constexpr std::size_t kMaxText = 1000;
constexpr Duration kFutureSlack = minutes(1);  // the sensor's clock may run a little ahead
constexpr Duration kMaxAge = hours(1);         // older news is not acted on as news

Reply invalid(const std::string& field, const std::string& what) {
  return error_reply(422, "invalid", fmt::format("request: {}: {}", field, what), field);
}

// Whether `place` is a place of `kind` on the map; the problem when it is not.
std::optional<std::string> not_a_place(const map::TopoMap& map, std::string_view kind, const std::string& place) {
  if (kind == exec::Observation::kDoorOpen) {
    const auto& edges = map.edges();
    if (std::any_of(edges.begin(), edges.end(), [&](const map::Edge& e) { return e.door && *e.door == place; }))
      return std::nullopt;
    return fmt::format("'{}' is not a door of map '{}' (a door_open observation names a door)", place, map.name());
  }
  if (kind == exec::Observation::kEdgeBlocked) {
    if (map.find_edge(place)) return std::nullopt;
    return fmt::format("'{}' is not an edge of map '{}' (an edge_blocked observation names an edge)", place,
                       map.name());
  }
  if (map.find_node(place)) return std::nullopt;
  return fmt::format("'{}' is not a node of map '{}' (a person_present observation names a node)", place, map.name());
}

Result<std::string> text_field(const Json& body, const char* key, bool required, std::size_t max) {
  const auto it = body.find(key);
  if (it == body.end() || it->is_null()) {
    if (required) return Error::invalid(fmt::format("request: {}: missing", key));
    return std::string();
  }
  if (!it->is_string()) return Error::invalid(fmt::format("request: {}: must be a string", key));
  std::string s = it->get<std::string>();
  if (required && s.empty()) return Error::invalid(fmt::format("request: {}: must not be empty", key));
  if (s.size() > max) return Error::invalid(fmt::format("request: {}: longer than {} characters", key, max));
  return s;
}

Reply post_observation(Api& api, const httplib::Request& req) {
  Json body;
  if (auto refused = read_json_object(req, body)) return *refused;
  for (const auto& [key, value] : body.items())
    if (key != "kind" && key != "place" && key != "value" && key != "time" && key != "source" && key != "text")
      return invalid(key, "unknown field (an observation has kind, place, value, time, source and text)");
  exec::Observation o;
  for (auto [key, out, max] : {std::tuple{"kind", &o.what, std::size_t{100}}, std::tuple{"place", &o.where, kMaxText}}) {
    auto s = text_field(body, key, true, max);
    if (!s) return error_reply(s.error());
    *out = std::move(*s);
  }
  constexpr std::string_view kinds[] = {exec::Observation::kDoorOpen, exec::Observation::kEdgeBlocked,
                                        exec::Observation::kPersonPresent};
  if (std::find(std::begin(kinds), std::end(kinds), o.what) == std::end(kinds))
    return invalid("kind", fmt::format("'{}' is not an observation kind (door_open, edge_blocked or person_present)",
                                       o.what));
  if (auto problem = not_a_place(api.ctx.map, o.what, o.where)) return invalid("place", *problem);
  const auto value = body.find("value");
  if (value == body.end() || value->is_null()) return invalid("value", "missing (1 or 0, or true or false)");
  if (value->is_boolean()) {
    o.value = value->get<bool>() ? 1 : 0;
  } else if (value->is_number() && (value->get<double>() == 0 || value->get<double>() == 1)) {
    o.value = value->get<double>();
  } else {
    return invalid("value", fmt::format("{} is not 1 or 0 (or true or false): the observation is binary",
                                        value->dump()));
  }
  auto source = text_field(body, "source", false, 100);
  if (!source) return error_reply(source.error());
  o.source = source->empty() ? "building" : *source;
  auto text = text_field(body, "text", false, kMaxText);
  if (!text) return error_reply(text.error());
  o.text = std::move(*text);
  std::optional<Time> when;
  if (const auto t = body.find("time"); t != body.end() && !t->is_null()) {
    if (!t->is_string()) return invalid("time", "must be a string (RFC 3339 with its zone, e.g. 2026-11-25T10:00:00Z)");
    auto parsed = parse_time(t->get<std::string>());
    if (!parsed) return invalid("time", parsed.error().message);
    when = *parsed;
  }
  return api.on_clock([&api, o = std::move(o), when]() mutable {
    const Time now = api.ctx.clock.now();
    o.when = when.value_or(now);
    if (o.when > now + kFutureSlack)
      return invalid("time", fmt::format("{} is after the service's clock ({})", format_time(o.when), format_time(now)));
    if (o.when < now - kMaxAge)
      return invalid("time", fmt::format("{} is more than an hour before the service's clock ({}): post observations "
                                         "as they are made",
                                         format_time(o.when), format_time(now)));
    const std::size_t errors = api.ctx.executor.write_errors().size();
    api.ctx.executor.observe(o);
    if (api.ctx.executor.write_errors().size() > errors)
      return error_reply(500, "storage", api.ctx.executor.write_errors().back());
    Reply reply;
    reply.status = 201;
    reply.body = Json{{"observation", Json{{"kind", o.what},
                                           {"place", o.where},
                                           {"value", o.value},
                                           {"time", format_time(o.when)},
                                           {"source", o.source},
                                           {"text", o.text}}}};
    return reply;
  });
}

}  // namespace

void add_observation_endpoints(std::vector<Endpoint>& routes) {
  routes.push_back({"POST", "/api/v1/observations", true, post_observation});
}

}  // namespace rondo::service
