// POST /api/v1/commands: a command in words (docs/commands.md, rondo::lang), e.g. {"text": "check
// WayPoint2 before 15:00"}: its tasks are submitted as POST /api/v1/tasks would (201), a repeated
// command's routines are added as POST /api/v1/routines would (201, {"routines": [...]}), a
// cancellation cancels the tasks it names that are not finished (200). A sentence outside the
// grammar or a place that is not on the map is 422 naming the word, with the field "text". The
// places are the deployment's places file (ServiceContext::places), else the map's node names; "now" (to the
// minute, as `rondo task add` takes it) and local times are the service's clock in the deployment's zone.
// The same sentence said again in the same minute adds nothing: 200 with the tasks (routines) it
// made the first time and "already queued: ID"; a different one never takes another's id
// (lang::settle_ids: "~2" after its ids).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "api.h"
#include "rondo/core/task_codec.h"
#include "rondo/lang/command.h"
#include "rondo/service/said_again.h"

namespace rondo::service {
namespace {

// 200: the command was said before and its tasks (routines) are still to do.
Reply already_queued(Api& api, const lang::Command& c, const std::vector<std::string>& ids) {
  Reply r;
  r.body = Json{{"message", already_queued_text(ids)}, {"already_queued", ids}};
  if (!c.routines.empty()) {
    Json routines = Json::array();
    for (const Routine& routine : api.ctx.fleet.routines())
      if (std::find(ids.begin(), ids.end(), routine.name) != ids.end()) routines.push_back(encode(routine));
    r.body["routines"] = std::move(routines);
    return r;
  }
  Json tasks = Json::array();
  for (const std::string& id : ids)
    if (auto found = api.ctx.fleet.task(id); found && *found) tasks.push_back(task_json(**found));
  r.body["tasks"] = std::move(tasks);
  return r;
}

Reply command(Api& api, const httplib::Request& req) {
  Json body;
  if (auto refused = read_json_object(req, body)) return *refused;
  for (const auto& [k, v] : body.items())
    if (k != "text") return error_reply(422, "invalid", fmt::format("request: {}: unknown field (text)", k), k);
  if (!body.contains("text") || !body["text"].is_string())
    return error_reply(422, "invalid", "request: text: expected the command as text", "text");
  return api.on_clock([&api, text = body["text"].get<std::string>()] {
    std::optional<lang::Places> node_names;
    if (!api.ctx.places) node_names = lang::Places::from_map(api.ctx.map);
    const lang::Places& places = api.ctx.places ? *api.ctx.places : *node_names;
    const Time now = std::chrono::floor<std::chrono::minutes>(api.ctx.clock.now());
    auto parsed = lang::parse_command(text, {.places = &places, .zone = api.ctx.zone, .now = now});
    if (!parsed) return error_reply(422, "invalid", "text: " + parsed.error().message, "text");
    auto repeated = settle_against_fleet(*parsed, api.ctx.fleet);
    if (!repeated) {
      Reply e = error_reply(repeated.error());
      e.body["error"]["field"] = "text";
      return e;
    }
    if (!repeated->empty()) return already_queued(api, *parsed, *repeated);
    if (!parsed->routines.empty()) {  // a repeated command: as POST /api/v1/routines would
      Reply added = add_routines_now(api, std::move(parsed->routines));
      if (added.status >= 400) added.body["error"]["field"] = "text";
      return added;
    }
    Reply r;
    if (parsed->cancel) {
      std::vector<TaskId> ids;
      for (const auto& [id, record] : api.ctx.fleet.tasks())
        if (!is_final(record.state) && lang::matches(*parsed->cancel, record.task)) ids.push_back(id);
      Json cancelled = Json::array();
      for (const TaskId& id : ids)
        if (api.ctx.fleet.cancel_task(id, "cancelled in words: " + text)) cancelled.push_back(id);
      r.body = Json{{"cancelled", std::move(cancelled)}};
      return r;
    }
    std::vector<TaskId> ids;
    for (const Task& t : parsed->tasks) ids.push_back(t.id);
    if (Status ok = api.ctx.fleet.add_tasks(std::move(parsed->tasks), "api"); !ok) {
      Reply e = error_reply(ok.error());
      e.body["error"]["field"] = "text";
      return e;
    }
    Json tasks = Json::array();
    for (const TaskId& id : ids)
      if (auto found = api.ctx.fleet.task(id); found && *found) tasks.push_back(task_json(**found));
    r.status = 201;
    r.body = Json{{"tasks", std::move(tasks)}};
    return r;
  });
}

}  // namespace

void add_command_endpoints(std::vector<Endpoint>& routes) {
  routes.push_back({"POST", "/api/v1/commands", true, command});
}

}  // namespace rondo::service
