// The OpenAPI 3 document of /api/v1, and the routes that are not about tasks or the robot:
// /healthz, /metrics, /api/v1/openapi.json and the event stream. A test checks that the document
// lists exactly the routes the server answers.
#include <fmt/format.h>

#include "api.h"

namespace rondo::service {

Reply metrics_reply(Api& api);  // metrics.cpp

namespace {

Json error_schema_ref() {
  return Json{{"$ref", "#/components/schemas/Error"}};
}

Json responses(std::initializer_list<std::pair<int, const char*>> codes) {
  Json out = Json::object();
  for (const auto& [code, what] : codes) {
    Json r{{"description", what}};
    if (code >= 400) r["content"] = Json{{"application/json", Json{{"schema", error_schema_ref()}}}};
    out[std::to_string(code)] = std::move(r);
  }
  return out;
}

Json param(const char* name, const char* in, const char* type, const char* what, bool required = false) {
  return Json{{"name", name},
              {"in", in},
              {"required", required || std::string(in) == "path"},
              {"description", what},
              {"schema", Json{{"type", type}}}};
}

Json op(const char* summary, Json resp, Json params = Json::array(), bool body = false, bool write = false) {
  Json o{{"summary", summary}, {"responses", std::move(resp)}};
  if (!params.empty()) o["parameters"] = std::move(params);
  if (body)
    o["requestBody"] =
        Json{{"required", true}, {"content", Json{{"application/json", Json{{"schema", Json{{"type", "object"}}}}}}}};
  if (write) o["security"] = Json::array({Json{{"bearer", Json::array()}}});
  return o;
}

Json document() {
  Json paths = Json::object();
  const Json id = param("id", "path", "string", "the task's id");
  paths["/"]["get"] = op("The dashboard (HTML).", responses({{200, "text/html"}}));
  paths["/dashboard.js"]["get"] = op("The dashboard's script.", responses({{200, "text/javascript"}}));
  paths["/dashboard.css"]["get"] = op("The dashboard's style.", responses({{200, "text/css"}}));
  paths["/favicon.svg"]["get"] = op("The dashboard's icon.", responses({{200, "image/svg+xml"}}));
  paths["/healthz"]["get"] = op("The service is up and its executive answers.",
                                responses({{200, "ok"}, {503, "the executive does not answer"}}));
  paths["/metrics"]["get"] = op("Figures in the Prometheus text format.", responses({{200, "text/plain"}}));
  paths["/api/v1/openapi.json"]["get"] = op("This document.", responses({{200, "OpenAPI 3"}}));
  paths["/api/v1/tasks"]["post"] =
      op("Submit tasks: the task-file JSON of docs/task-format.md. Answered after the commit. A repeated "
         "Idempotency-Key returns the first answer.",
         responses({{201, "accepted and stored"},
                    {400, "not JSON"},
                    {401, "no token"},
                    {403, "wrong token"},
                    {413, "body too large"},
                    {422, "a task that cannot be meant (the field is named)"}}),
         Json::array({param("Idempotency-Key", "header", "string", "makes a retried submission safe")}), true, true);
  paths["/api/v1/tasks"]["get"] =
      op("List tasks, filtered and paged.", responses({{200, "{total, offset, limit, tasks}"}, {422, "a bad filter"}}),
         Json::array({param("state", "query", "string",
                            "queued, waiting, navigating, acting, succeeded, failed, cancelled, dropped"),
                      param("source", "query", "string", "api, routine, request, deployment"),
                      param("from", "query", "string", "windows ending after this time"),
                      param("to", "query", "string", "windows opening before this time"),
                      param("limit", "query", "integer", "1..1000, default 100"),
                      param("offset", "query", "integer", "default 0")}));
  paths["/api/v1/tasks/{id}"]["get"] = op("One task, with its events from the store.",
                                          responses({{200, "the task"}, {404, "no such task"}}), Json::array({id}));
  paths["/api/v1/tasks/{id}"]["patch"] =
      op("Change a queued task's window and/or priority ({window: {release, deadline}, priority}); reschedules.",
         responses({{200, "changed"},
                    {400, "not JSON"},
                    {404, "no such task"},
                    {409, "final or running"},
                    {422, "a change that cannot be meant"}}),
         Json::array({id}), true, true);
  paths["/api/v1/tasks/{id}/cancel"]["post"] =
      op("Cancel a task (body optional: {reason}).",
         responses({{200, "cancelled, or cancel pending"}, {404, "no such task"}, {409, "already final"}}),
         Json::array({id}), false, true);
  paths["/api/v1/commands"]["post"] =
      op("A command in words, {text} (docs/commands.md): its tasks are submitted (201), or the tasks a cancellation "
         "names are cancelled (200). The same sentence again in the same minute adds nothing (200, \"already queued: "
         "ID\").",
         responses({{201, "the tasks (or a repeated command's routines) added"},
                    {200, "the tasks cancelled, or the tasks (routines) already queued by the same sentence"},
                    {400, "malformed JSON"},
                    {422, "the sentence is not understood (the word or place, field text), or a task the robot "
                          "cannot run"}}),
         Json::array(), true, true);
  paths["/api/v1/tasks/{id}/confirm"]["post"] =
      op("Confirm the load or unload the task is doing now (body optional: {by}): the action ends done.",
         responses({{200, "confirmed: the action ends as done"},
                    {404, "no such task"},
                    {409, "the task is not loading or unloading now"}}),
         Json::array({id}), false, true);
  paths["/api/v1/robot"]["get"] =
      op("The robot: node, pose, phase, current task, battery, faults, and the route of its running navigation.",
         responses({{200, "the robot"}}));
  paths["/api/v1/map"]["get"] = op("The topological map (docs/map-format.md, as JSON).", responses({{200, "the map"}}));
  paths["/api/v1/schedule"]["get"] =
      op("One local day's schedule, planned against actual; each task names its robot, and robots gives each "
         "robot's current task and planned order.",
         responses({{200, "the day"}, {422, "a bad date"}}),
         Json::array({param("date", "query", "string", "YYYY-MM-DD, local; default today")}));
  paths["/api/v1/edges"]["get"] =
      op("Every edge's success probability and expected travel time at one time (default now).",
         responses({{200, "{time, edges}"}, {422, "a bad time"}}),
         Json::array({param("at", "query", "string", "a UTC time; default now")}));
  paths["/api/v1/edges/{id}/model"]["get"] =
      op("An edge's learned model over a local day: p(t), expected tau(t) and quantiles.",
         responses({{200, "points"}, {404, "no such edge"}, {422, "a bad date or step"}}),
         Json::array({param("id", "path", "string", "the edge id"), param("date", "query", "string", "YYYY-MM-DD"),
                      param("step_minutes", "query", "integer", "1..240, default 15")}));
  paths["/api/v1/routines"]["get"] = op("The routines.", responses({{200, "{routines}"}}));
  paths["/api/v1/routines"]["post"] =
      op("Add routines ({zone?, routines: [...]} as in a task file); today's instances at once.",
         responses({{201, "added"}, {400, "not JSON"}, {422, "a routine that cannot be meant"}}), Json::array(), true,
         true);
  paths["/api/v1/routines/{name}"]["delete"] =
      op("Remove a routine (today's tasks stay).", responses({{200, "removed"}, {404, "no such routine"}}),
         Json::array({param("name", "path", "string", "the routine's name")}), false, true);
  paths["/api/v1/observations"]["post"] =
      op("An observation of the building's own sensors ({kind: door_open|edge_blocked|person_present, place, "
         "value: 1|0, time?, source?, text?}): stored and acted on as the robot's own (docs/api.md).",
         responses({{201, "{observation}"}, {400, "not JSON"}, {422, "a bad field, named"}}), Json::array(), true, true);
  paths["/api/v1/pause"]["post"] =
      op("Out of service ({halt?: bool, reason?}): nothing new starts, the robot docks; the running task "
         "finishes, or with halt goes back to the queue keeping its progress. Stored: a restart keeps it.",
         responses({{200, "{out_of_service}"}, {400, "not JSON"}, {422, "a bad field"}}), Json::array(), false, true);
  paths["/api/v1/resume"]["post"] =
      op("Back in service ({reason?}): dispatch resumes and the tasks are rescheduled.",
         responses({{200, "{out_of_service}"}, {400, "not JSON"}, {422, "a bad field"}}), Json::array(), false, true);
  const Json robot_name = param("name", "path", "string", "the robot's name in the deployment");
  paths["/api/v1/robots"]["get"] =
      op("Every robot of the fleet: the fields of /api/v1/robot with its name, open_tasks, and tasks (its stored "
         "tasks by state).",
         responses({{200, "{robots}"}}));
  paths["/api/v1/robots/{name}"]["get"] =
      op("One robot of the fleet.", responses({{200, "the robot"}, {404, "no such robot"}}), Json::array({robot_name}));
  paths["/api/v1/robots/{name}/pause"]["post"] =
      op("One robot out of service (as /api/v1/pause); its unstarted tasks go to the others after a while.",
         responses({{200, "{out_of_service, robot}"}, {400, "not JSON"}, {404, "no such robot"}, {422, "a bad field"}}),
         Json::array({robot_name}), false, true);
  paths["/api/v1/robots/{name}/resume"]["post"] =
      op("One robot back in service.",
         responses({{200, "{out_of_service, robot}"}, {400, "not JSON"}, {404, "no such robot"}, {422, "a bad field"}}),
         Json::array({robot_name}), false, true);
  paths["/api/v1/events"]["get"] =
      op("The event log as server-sent events; id is the log's sequence number.",
         responses({{200, "text/event-stream"}, {422, "a bad Last-Event-ID"}}),
         Json::array({param("Last-Event-ID", "header", "integer", "resume after this event"),
                      param("after", "query", "integer", "the same, for clients that cannot set headers"),
                      param("tail", "query", "integer", "start with the last N events of the log")}));
  return Json{
      {"openapi", "3.0.3"},
      {"info", Json{{"title", "rondo"},
                    {"version", "1"},
                    {"description", "The long-term task executive as a service (docs/api.md)."}}},
      {"paths", std::move(paths)},
      {"components",
       Json{{"securitySchemes", Json{{"bearer", Json{{"type", "http"}, {"scheme", "bearer"}}}}},
            {"schemas",
             Json{{"Error",
                   Json{{"type", "object"},
                        {"properties",
                         Json{{"error", Json{{"type", "object"},
                                             {"properties",
                                              Json{{"code", Json{{"type", "string"}}},
                                                   {"message", Json{{"type", "string"}}},
                                                   {"field", Json{{"type", "string"}, {"nullable", true}}}}}}}}}}}}}}}};
}

Reply health(Api& api, const httplib::Request&) {
  return api.on_clock([&api] {
    Reply r;
    r.body = Json{{"status", "ok"}, {"deployment", api.ctx.deployment}, {"time", format_time(api.ctx.clock.now())}};
    if (api.ctx.role) {
      r.body["role"] = api.ctx.role->active() ? "active" : "standby";
      r.body["epoch"] = api.ctx.role->epoch();
    }
    return r;
  });
}

Reply openapi(Api&, const httplib::Request&) {
  Reply r;
  r.text = openapi_document();
  r.content_type = "application/json; charset=utf-8";
  return r;
}

}  // namespace

std::string openapi_document() {
  return document().dump(2) + "\n";
}

void add_meta_endpoints(std::vector<Endpoint>& routes) {
  routes.push_back({"GET", "/healthz", false, health});
  routes.push_back({"GET", "/metrics", false, [](Api& api, const httplib::Request&) { return metrics_reply(api); }});
  routes.push_back({"GET", "/api/v1/openapi.json", false, openapi});
  routes.push_back({"GET", "/api/v1/events", false, nullptr, true});
}

}  // namespace rondo::service
