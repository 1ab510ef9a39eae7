// /api/v1: the robot, the map, the schedule (planned against actual), an edge's learned model
// over a day, and the routines.
#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <map>
#include <optional>

#include "api.h"
#include "rondo/core/task_codec.h"
#include "rondo/ltl/task_formula.h"
#include "rondo/map/map_yaml.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/service/stored_routines.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/task_table.h"

namespace rondo::service {
namespace {

Json fault_json(const std::optional<exec::RobotFault>& f) {
  if (!f) return Json(nullptr);
  return Json{{"kind", exec::to_string(f->kind)}, {"message", f->message}};
}

// What one robot is doing: where, its task, battery, faults, the route it expects.
Json robot_view(const Api& api, exec::Executor& executor) {
  const exec::Robot& robot = executor.robot();
  const exec::Executor::Activity a = executor.activity();
  const auto pose = robot.position();
  Json faults = Json::array();
  if (auto f = robot.fault()) faults.push_back(fault_json(f));
  Json route = Json::array();  // the edges the running navigation expects to take
  for (const map::EdgeIndex e : executor.route()) {
    const map::Edge& edge = api.ctx.map.edge(e);
    route.push_back(Json{{"edge", edge.id},
                         {"from", api.ctx.map.node(api.ctx.map.from_index(e)).name},
                         {"to", api.ctx.map.node(api.ctx.map.to_index(e)).name}});
  }
  return Json{{"name", executor.name()},
              {"time", format_time(api.ctx.clock.now())},
              {"node", api.ctx.map.node(robot.location()).name},
              {"pose", pose ? Json{{"x", pose->x}, {"y", pose->y}, {"yaw", pose->yaw}} : Json(nullptr)},
              {"phase", a.phase},
              {"current_task", a.current ? Json(*a.current) : Json(nullptr)},
              {"busy", robot.busy()},
              {"battery", robot.battery()},
              {"charging", robot.charging()},
              {"dispatch_paused", a.fault.has_value() || executor.out_of_service()},
              {"out_of_service", executor.out_of_service()},
              {"faults", std::move(faults)},
              {"route", std::move(route)}};
}

// GET /api/v1/robot: the fleet's first robot (a fleet of one: its robot).
Reply robot(Api& api, const httplib::Request&) {
  return api.on_clock([&api] {
    Reply r;
    r.body = robot_view(api, api.ctx.executor);
    r.body.erase("name");  // as before fleets: the robot's view without a name
    return r;
  });
}

// The tasks allocated to each robot that are not over, by robot.
std::map<std::string, int> open_tasks(const Api& api) {
  std::map<std::string, int> n;
  for (const auto& [id, r] : api.ctx.fleet.tasks())
    if (!is_final(r.state)) ++n[r.robot];
  return n;
}

// What a robot of the fleet adds to the robot's view: the tasks it holds that are not over, and
// every stored task allocated to it by state (the dashboard's totals: one grouped query).
using TaskCounts = std::map<std::string, std::map<std::string, long>>;
void add_fleet_fields(Json& view, const std::string& name, const std::map<std::string, int>& open,
                      const TaskCounts& counts) {
  const auto it = open.find(name);
  view["open_tasks"] = it == open.end() ? 0 : it->second;
  Json by_state = Json::object();
  if (const auto c = counts.find(name); c != counts.end())
    for (const auto& [state, n] : c->second) by_state[state] = n;
  view["tasks"] = std::move(by_state);
}

// GET /api/v1/robots: every robot of the fleet, with the tasks it holds.
Reply robots(Api& api, const httplib::Request&) {
  return api.on_clock([&api] {
    const std::map<std::string, int> open = open_tasks(api);
    auto counts = store::count_tasks_by_robot(api.ctx.store);
    if (!counts) return error_reply(counts.error());
    Json list = Json::array();
    for (const auto& e : api.ctx.fleet.robots()) {
      Json view = robot_view(api, *e);
      add_fleet_fields(view, e->name(), open, *counts);
      list.push_back(std::move(view));
    }
    Reply r;
    r.body = Json{{"robots", std::move(list)}};
    return r;
  });
}

// GET /api/v1/robots/{name}
Reply one_robot(Api& api, const httplib::Request& req) {
  return api.on_clock([&api, name = std::string(req.matches[1])] {
    exec::Executor* e = api.ctx.fleet.find_robot(name);
    if (!e) return error_reply(Error::not_found(fmt::format("no robot '{}'", name)));
    auto counts = store::count_tasks_by_robot(api.ctx.store);
    if (!counts) return error_reply(counts.error());
    Reply r;
    r.body = robot_view(api, *e);
    add_fleet_fields(r.body, name, open_tasks(api), *counts);
    return r;
  });
}

Reply map_view(Api& api, const httplib::Request&) {
  Reply r;
  r.body = map::map_to_json(api.ctx.map);  // the map is immutable: no need for the clock's thread
  return r;
}

// The local day a `date` parameter names ("" : today's).
Result<std::chrono::year_month_day> local_day(const std::string& date, const TimeZone& zone, Time now) {
  if (date.empty()) return zone.local_date(now);
  auto t = parse_time(date + "T12:00:00Z");
  if (!t) return Error::invalid(fmt::format("query: date: expected YYYY-MM-DD, found '{}'", date));
  return std::chrono::year_month_day{std::chrono::floor<std::chrono::days>(*t)};
}

std::string date_param(const httplib::Request& req) {
  return req.has_param("date") ? req.get_param_value("date") : "";
}

std::chrono::year_month_day next_day(std::chrono::year_month_day d) {
  return std::chrono::year_month_day{std::chrono::sys_days{d} + std::chrono::days{1}};
}

Reply schedule(Api& api, const httplib::Request& req) {
  return api.on_clock([&api, date = date_param(req)] {
    const Time now = api.ctx.clock.now();
    auto day = local_day(date, api.ctx.zone, now);
    if (!day) return error_reply(422, "invalid", day.error().message, "date");
    const Time from = api.ctx.zone.at(*day, Duration{0});
    const Time to = api.ctx.zone.at(next_day(*day), Duration{0});
    const exec::Executor::Activity a = api.ctx.executor.activity();
    // The day's tasks from the store (the executor keeps only the tasks not finished in memory):
    // those whose window overlaps the day, and those without a window added that day.
    auto page = store::find_tasks(
        api.ctx.store,
        {.from = from, .to = to, .windowless_by_added = true, .limit = std::numeric_limits<long>::max()});
    if (!page) return error_reply(page.error());
    Json tasks = Json::array();
    for (const store::TaskRow& row : page->rows) {
      auto found = api.ctx.fleet.task(row.id);
      if (!found) return error_reply(found.error());
      if (!*found) continue;
      const exec::TaskRecord& t = **found;
      const TaskId& id = row.id;
      tasks.push_back(Json{{"id", id},
                           {"activity", t.task.activity},
                           {"start_node", t.task.start_node},
                           {"robot", t.robot.empty() ? Json(nullptr) : Json(t.robot)},
                           {"state", to_string(t.state)},
                           {"code", std::string(exec::to_string(t.outcome))},
                           {"reason", t.reason},
                           {"window", t.task.window ? Json{{"release", format_time(t.task.window->release)},
                                                           {"deadline", format_time(t.task.window->deadline)}}
                                                    : Json(nullptr)},
                           {"planned", Json{{"start", time_json(t.planned_start)}, {"end", time_json(t.planned_end)}}},
                           {"actual", Json{{"start", time_json(t.started)}, {"end", time_json(t.ended)}}}});
    }
    // Each robot's lane: its running task and planned order (the top-level pair is the first
    // robot's, as before fleets).
    Json robots = Json::array();
    for (const auto& e : api.ctx.fleet.robots()) {
      const exec::Executor::Activity ra = e->activity();
      robots.push_back(Json{{"name", e->name()},
                            {"current_task", ra.current ? Json(*ra.current) : Json(nullptr)},
                            {"planned_order", ra.planned}});
    }
    Reply reply;
    reply.body = Json{{"date", fmt::format("{:04d}-{:02d}-{:02d}", static_cast<int>(day->year()),
                                           static_cast<unsigned>(day->month()), static_cast<unsigned>(day->day()))},
                      {"zone", api.ctx.zone.name()},
                      {"from", format_time(from)},
                      {"to", format_time(to)},
                      {"now", format_time(now)},
                      {"current_task", a.current ? Json(*a.current) : Json(nullptr)},
                      {"planned_order", a.planned},
                      {"robots", std::move(robots)},
                      {"tasks", std::move(tasks)}};
    return reply;
  });
}

Reply edge_model(Api& api, const httplib::Request& req) {
  const std::string edge_id = req.matches[1];
  const auto edge = api.ctx.map.find_edge(edge_id);
  if (!edge)
    return error_reply(404, "not_found", fmt::format("no edge '{}' on the map '{}'", edge_id, api.ctx.map.name()));
  auto step = query_int(req, "step_minutes", 1, 240);
  if (!step) return error_reply(422, "invalid", step.error().message, "step_minutes");
  const long step_min = step->value_or(15);
  return api.on_clock([&api, e = *edge, edge_id, date = date_param(req), step_min] {
    auto day = local_day(date, api.ctx.zone, api.ctx.clock.now());
    if (!day) return error_reply(422, "invalid", day.error().message, "date");
    const plan::LearnedEdgeModels& models = api.ctx.fleet.models();
    const std::size_t index = models.model_index(e);
    const auto& fitted = models.models();
    const bool learned = fitted && index != plan::LearnedEdgeModels::kUnknown;
    const Time from = api.ctx.zone.at(*day, Duration{0});
    const Time to = api.ctx.zone.at(next_day(*day), Duration{0});
    Json points = Json::array();
    for (Time t = from; t < to; t += minutes(step_min)) {
      const plan::EdgeCrossing o = models.outcome(e, t);
      Json p{{"time", format_time(t)}, {"p", o.success_probability}, {"expected_s", o.expected_seconds}};
      if (learned)
        p["quantiles_s"] = Json{{"q10", fitted->quantile_seconds(index, t, 0.1)},
                                {"q50", fitted->quantile_seconds(index, t, 0.5)},
                                {"q90", fitted->quantile_seconds(index, t, 0.9)}};
      else
        p["quantiles_s"] = nullptr;
      points.push_back(std::move(p));
    }
    Reply reply;
    reply.body = Json{{"edge", edge_id},
                      {"from_node", api.ctx.map.edges()[e].from},
                      {"to_node", api.ctx.map.edges()[e].to},
                      {"model", learned ? "learned" : "prior"},
                      {"attempts", learned ? fitted->attempts(index) : 0},
                      {"zone", api.ctx.zone.name()},
                      {"points", std::move(points)}};
    return reply;
  });
}

// Every edge's success probability and expected travel time at one instant (the map's colours).
Reply edges_now(Api& api, const httplib::Request& req) {
  auto at = query_time(req, "at");
  if (!at) return error_reply(422, "invalid", at.error().message, "at");
  return api.on_clock([&api, at = *at] {
    const Time t = at.value_or(api.ctx.clock.now());
    const plan::LearnedEdgeModels& models = api.ctx.fleet.models();
    Json list = Json::array();
    for (map::EdgeIndex e = 0; e < api.ctx.map.edge_count(); ++e) {
      const plan::EdgeCrossing o = models.outcome(e, t);
      const map::Edge& edge = api.ctx.map.edges()[e];
      list.push_back(Json{{"id", edge.id},
                          {"from", edge.from},
                          {"to", edge.to},
                          {"p", o.success_probability},
                          {"expected_s", o.expected_seconds},
                          {"learned", models.models() && models.model_index(e) != plan::LearnedEdgeModels::kUnknown}});
    }
    Reply reply;
    reply.body = Json{{"time", format_time(t)}, {"edges", std::move(list)}};
    return reply;
  });
}

Reply routines(Api& api, const httplib::Request&) {
  return api.on_clock([&api] {
    Json list = Json::array();
    for (const Routine& r : api.ctx.fleet.routines()) list.push_back(encode(r));
    Reply reply;
    reply.body = Json{{"routines", std::move(list)}};
    return reply;
  });
}

Reply add_routines(Api& api, const httplib::Request& req) {
  Json j;
  if (auto refused = read_json_object(req, j)) return *refused;
  const map::TopoMap& map = api.ctx.map;
  const auto known = [&map](std::string_view n) { return map.find_node(n).has_value(); };
  const PlaceCheck places{known, map.name(),
                          [&](std::string_view f) { return ltl::check_task_formula(f, known, map.name()); }};
  auto file = parse_task_file(with_default_zone(j, api.ctx.zone), DocumentFormat::kJson, "request", &places);
  if (!file) return error_reply(file.error());
  if (!file->tasks.empty())
    return error_reply(422, "invalid", "request: tasks: add tasks through /api/v1/tasks", "tasks");
  if (file->routines.empty()) return error_reply(422, "invalid", "request: routines: no routine to add", "routines");
  return api.on_clock([&api, list = std::move(file->routines)]() mutable { return add_routines_now(api, std::move(list)); });
}

}  // namespace

Reply add_routines_now(Api& api, std::vector<Routine> list) {
  Json added = Json::array();
  for (Routine& r : list) {
    Json encoded = encode(r);
    const Routine kept = r;
    if (Status ok = api.ctx.fleet.add_routine_now(std::move(r)); !ok) return error_reply(ok.error());
    // Stored before the answer, so that it comes back after a restart; not run when it cannot be.
    if (Status ok = remember_added_routine(api.ctx.store, kept); !ok) {
      (void)api.ctx.fleet.remove_routine(kept.name);
      return error_reply(ok.error());
    }
    added.push_back(std::move(encoded));
  }
  Reply reply;
  reply.status = 201;
  reply.body = Json{{"routines", std::move(added)}};
  return reply;
}

namespace {

Reply remove_routine(Api& api, const httplib::Request& req) {
  const std::string name = req.matches[1];
  return api.on_clock([&api, name] {
    const auto& list = api.ctx.fleet.routines();
    if (std::none_of(list.begin(), list.end(), [&name](const Routine& r) { return r.name == name; }))
      return error_reply(Error::not_found(fmt::format("no routine '{}'", name)));
    // Stored first: a deployment routine removed here stays removed after a restart.
    if (Status ok = remember_removed_routine(api.ctx.store, name); !ok) return error_reply(ok.error());
    if (Status ok = api.ctx.fleet.remove_routine(name); !ok) return error_reply(ok.error());
    Reply reply;
    reply.body = Json{{"removed", name}};
    return reply;
  });
}

// POST /api/v1/pause {"halt": bool, "reason": text} and POST /api/v1/resume {"reason": text}:
// dispatch out of service and back, for every robot, or for one (/api/v1/robots/{name}/pause). The
// state is stored (meta serve.out_of_service, or serve.out_of_service.<name>) before the answer,
// so a restart keeps it. A robot out of service for a while hands its unstarted tasks to the
// others (docs/fleet.md, "Re-allocation").
Reply set_service(Api& api, const httplib::Request& req, bool out, std::optional<std::string> robot) {
  bool halt = false;
  std::string reason;
  if (!req.body.empty()) {
    Json j;
    if (auto refused = read_json_object(req, j)) return *refused;
    if (const auto it = j.find("halt"); it != j.end()) {
      if (!out || !it->is_boolean()) return error_reply(422, "invalid", "halt: a boolean, for pause only", "halt");
      halt = it->get<bool>();
    }
    if (const auto it = j.find("reason"); it != j.end()) {
      if (!it->is_string()) return error_reply(422, "invalid", "reason: a string", "reason");
      reason = it->get<std::string>();
    }
  }
  return api.on_clock([&api, out, halt, reason, robot] {
    exec::Executor* one = robot ? api.ctx.fleet.find_robot(*robot) : nullptr;
    if (robot && !one) return error_reply(Error::not_found(fmt::format("no robot '{}'", *robot)));
    const std::string key = robot ? out_of_service_key(*robot) : std::string(kOutOfServiceKey);
    if (Status ok = store::set_meta(api.ctx.store, key, out ? "1" : "0"); !ok) return error_reply(ok.error());
    if (one) {
      one->set_out_of_service(out, halt, reason);
    } else {
      for (const auto& e : api.ctx.fleet.robots()) e->set_out_of_service(out, halt, reason);
    }
    Reply reply;
    reply.body = Json{{"out_of_service", one ? one->out_of_service() : api.ctx.executor.out_of_service()}};
    if (one) reply.body["robot"] = one->name();
    return reply;
  });
}

}  // namespace

void add_robot_endpoints(std::vector<Endpoint>& routes) {
  routes.push_back({"GET", "/api/v1/robot", false, robot});
  routes.push_back({"GET", "/api/v1/robots", false, robots});
  routes.push_back({"GET", "/api/v1/robots/{name}", false, one_robot});
  routes.push_back({"POST", "/api/v1/robots/{name}/pause", true, [](Api& api, const httplib::Request& req) {
                      return set_service(api, req, true, std::string(req.matches[1]));
                    }});
  routes.push_back({"POST", "/api/v1/robots/{name}/resume", true, [](Api& api, const httplib::Request& req) {
                      return set_service(api, req, false, std::string(req.matches[1]));
                    }});
  routes.push_back({"GET", "/api/v1/map", false, map_view});
  routes.push_back({"GET", "/api/v1/schedule", false, schedule});
  routes.push_back({"GET", "/api/v1/edges", false, edges_now});
  routes.push_back({"GET", "/api/v1/edges/{id}/model", false, edge_model});
  routes.push_back({"GET", "/api/v1/routines", false, routines});
  routes.push_back({"POST", "/api/v1/routines", true, add_routines});
  routes.push_back({"DELETE", "/api/v1/routines/{name}", true, remove_routine});
  routes.push_back({"POST", "/api/v1/pause", true,
                    [](Api& api, const httplib::Request& req) { return set_service(api, req, true, std::nullopt); }});
  routes.push_back({"POST", "/api/v1/resume", true,
                    [](Api& api, const httplib::Request& req) { return set_service(api, req, false, std::nullopt); }});
}

}  // namespace rondo::service
