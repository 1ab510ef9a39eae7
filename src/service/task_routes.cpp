// /api/v1/tasks: submit (with Idempotency-Key), list with filters and paging, one task with its
// events, cancel, and change a waiting task's window or priority.
#include <fmt/format.h>

#include <algorithm>

#include "api.h"
#include "rondo/core/task_codec.h"
#include "rondo/ltl/task_formula.h"
#include "rondo/store/batch.h"
#include "rondo/store/events.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/task_table.h"

namespace rondo::service {
namespace {

constexpr std::size_t kMaxKeyLength = 200;

// FNV-1a: a stable fingerprint of a request body, stored with its idempotency key.
std::string fingerprint(std::string_view text) {
  std::uint64_t h = 1469598103934665603ULL;
  for (char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ULL;
  }
  return fmt::format("{:016x}", h);
}

// A task as the API shows it, from the executor's memory or (a finished one) the store.
Result<Json> task_view(Api& api, const TaskId& id) {
  RONDO_ASSIGN_OR_RETURN(std::optional<exec::TaskRecord> r, api.ctx.fleet.task(id));
  if (!r) return Error::not_found(fmt::format("no task '{}'", id));
  return task_json(*r);
}

Reply created(Api& api, const std::vector<TaskId>& ids) {
  Json tasks = Json::array();
  for (const TaskId& id : ids)
    if (auto view = task_view(api, id)) tasks.push_back(std::move(*view));
  Reply r;
  r.status = 201;
  r.body = Json{{"tasks", std::move(tasks)}};
  return r;
}

// On the clock's thread. The key is written as pending before the tasks and as answered after, so
// a crash between the two still finds the tasks on a retry: pending + every task stored = answered.
Reply submit_on_clock(Api& api, std::vector<Task> tasks, const std::string& key, const std::string& print) {
  store::Store& db = api.ctx.store;
  // The key, the tasks and the answer in one commit (one sync); answered only once it is done.
  store::Batch batch(db);
  std::vector<TaskId> ids;
  for (const Task& t : tasks) ids.push_back(t.id);
  const std::string meta_key = "idempotency." + key;
  if (!key.empty()) {
    // Written as pending unless the key is known (one statement: a round trip on PostgreSQL).
    auto stored = store::claim_meta(db, meta_key, Json{{"fingerprint", print}}.dump());
    if (!stored) return error_reply(stored.error());
    if (*stored) {
      Json rec = Json::parse(**stored, nullptr, false);
      if (rec.is_discarded() || rec.value("fingerprint", "") != print)
        return error_reply(422, "idempotency_mismatch", "this Idempotency-Key was used with another request",
                           "Idempotency-Key");
      if (rec.contains("reply")) {
        Reply r;
        r.status = rec["reply"].value("status", 201);
        r.body = rec["reply"]["body"];
        return r;
      }
      // Pending: the first attempt stopped between its two writes.
      const bool all_stored =
          std::all_of(ids.begin(), ids.end(), [&](const TaskId& id) { return api.ctx.fleet.book().known(id); });
      if (all_stored) return created(api, ids);
    }
  }
  if (Status ok = api.ctx.fleet.add_tasks(std::move(tasks), "api"); !ok) {
    (void)batch.commit();  // the key as pending, and the refusal's event
    return error_reply(ok.error());
  }
  Reply r = created(api, ids);
  if (!key.empty())
    (void)store::set_meta(db, meta_key,
                          Json{{"fingerprint", print}, {"reply", Json{{"status", r.status}, {"body", r.body}}}}.dump());
  if (Status ok = batch.commit(); !ok) return error_reply(ok.error());
  return r;
}

Reply submit(Api& api, const httplib::Request& req) {
  const std::string key = req.get_header_value("Idempotency-Key");
  if (key.size() > kMaxKeyLength || std::any_of(key.begin(), key.end(), [](char c) { return c < 0x21 || c > 0x7e; }))
    return error_reply(422, "invalid", "Idempotency-Key: printable ASCII, at most 200 characters", "Idempotency-Key");
  Json body;
  if (auto refused = read_json_object(req, body)) return *refused;
  const map::TopoMap& map = api.ctx.map;
  const auto known = [&map](std::string_view n) { return map.find_node(n).has_value(); };
  const PlaceCheck places{known, map.name(),
                          [&](std::string_view f) { return ltl::check_task_formula(f, known, map.name()); }};
  auto file = parse_task_file(with_default_zone(body, api.ctx.zone), DocumentFormat::kJson, "request", &places);
  if (!file) return error_reply(file.error());
  if (!file->routines.empty())
    return error_reply(422, "invalid", "request: routines: add routines through /api/v1/routines", "routines");
  if (file->tasks.empty()) return error_reply(422, "invalid", "request: tasks: no task to add", "tasks");
  return api.on_clock_grouped([&api, tasks = std::move(file->tasks), key, print = fingerprint(req.body)]() mutable {
    return submit_on_clock(api, std::move(tasks), key, print);
  });
}

Reply list(Api& api, const httplib::Request& req) {
  std::optional<TaskState> state;
  if (req.has_param("state")) {
    auto s = parse_task_state(req.get_param_value("state"));
    if (!s) return error_reply(422, "invalid", "query: state: " + s.error().message, "state");
    state = *s;
  }
  const std::string source = req.has_param("source") ? req.get_param_value("source") : "";
  auto from = query_time(req, "from");
  if (!from) return error_reply(422, "invalid", from.error().message, "from");
  auto to = query_time(req, "to");
  if (!to) return error_reply(422, "invalid", to.error().message, "to");
  auto limit = query_int(req, "limit", 1, 1000);
  if (!limit) return error_reply(422, "invalid", limit.error().message, "limit");
  auto offset = query_int(req, "offset", 0, std::numeric_limits<int>::max());
  if (!offset) return error_reply(422, "invalid", offset.error().message, "offset");
  const long lim = limit->value_or(100), off = offset->value_or(0);
  // The store holds every task (the executor only those not finished) with its current state.
  const store::TaskFilter filter{.state = state ? std::string(to_string(*state)) : std::string(),
                                 .source = source,
                                 .from = *from,
                                 .to = *to,
                                 .limit = lim,
                                 .offset = off};
  return api.on_clock([&api, filter] {
    auto page = store::find_tasks(api.ctx.store, filter);
    if (!page) return error_reply(page.error());
    Json tasks = Json::array();
    for (const store::TaskRow& row : page->rows) {
      auto view = task_view(api, row.id);
      if (!view) return error_reply(view.error());
      tasks.push_back(std::move(*view));
    }
    Reply reply;
    reply.body =
        Json{{"total", page->total}, {"offset", filter.offset}, {"limit", filter.limit}, {"tasks", std::move(tasks)}};
    return reply;
  });
}

Reply one(Api& api, const httplib::Request& req) {
  const std::string id = req.matches[1];
  return api.on_clock([&api, id] {
    auto events = store::read_events_of(api.ctx.store, id);
    if (!events) return error_reply(events.error());
    Json history = Json::array();
    for (const store::Event& e : *events) history.push_back(event_json(e));
    auto view = task_view(api, id);
    if (!view) return error_reply(view.error());
    Reply reply;
    reply.body = std::move(*view);
    reply.body["events"] = std::move(history);
    return reply;
  });
}

// A body of at most the one text field `name` (none at all is fine): its value into `value`, or
// the error to answer.
std::optional<Reply> read_text_field(const httplib::Request& req, const std::string& name, std::string& value) {
  if (req.body.empty()) return std::nullopt;
  Json body;
  if (auto refused = read_json_object(req, body)) return refused;
  for (const auto& [k, v] : body.items()) {
    if (k != name) return error_reply(422, "invalid", fmt::format("request: {}: unknown field", k), k);
    if (!v.is_string()) return error_reply(422, "invalid", fmt::format("request: {}: expected text", name), name);
    value = v.get<std::string>();
  }
  return std::nullopt;
}

Reply cancel(Api& api, const httplib::Request& req) {
  const std::string id = req.matches[1];
  std::string reason = "cancelled through the API";
  if (auto bad = read_text_field(req, "reason", reason)) return *bad;
  return api.on_clock([&api, id, reason] {
    if (Status ok = api.ctx.fleet.cancel_task(id, reason); !ok) return error_reply(ok.error());
    auto view = task_view(api, id);
    if (!view) return error_reply(view.error());
    Reply r;
    r.body = std::move(*view);
    return r;
  });
}

Reply confirm(Api& api, const httplib::Request& req) {
  const std::string id = req.matches[1];
  std::string by;
  if (auto bad = read_text_field(req, "by", by)) return *bad;
  return api.on_clock([&api, id, by] {
    if (Status ok = api.ctx.fleet.confirm_action(id, by.empty() ? "a person, through the API" : by); !ok)
      return error_reply(ok.error());
    auto view = task_view(api, id);
    if (!view) return error_reply(view.error());
    Reply r;
    r.body = std::move(*view);
    return r;
  });
}

Result<Time> time_field(const Json& j, const std::string& path) {
  if (!j.is_string())
    return Error::invalid(fmt::format("request: {}: expected a time like 2026-11-23T09:00:00Z", path));
  auto t = parse_time(j.get<std::string>());
  if (!t) return Error::invalid(fmt::format("request: {}: {}", path, t.error().message));
  return *t;
}

Reply change(Api& api, const httplib::Request& req) {
  const std::string id = req.matches[1];
  Json body;
  if (auto refused = read_json_object(req, body)) return *refused;
  std::optional<TimeWindow> window;
  std::optional<int> priority;
  for (const auto& [k, v] : body.items()) {
    if (k == "priority") {
      if (!v.is_number_integer())
        return error_reply(422, "invalid", "request: priority: expected a whole number", "priority");
      priority = v.get<int>();
    } else if (k == "window") {
      if (!v.is_object() || !v.contains("release") || !v.contains("deadline") || v.size() != 2)
        return error_reply(422, "invalid", "request: window: expected {release, deadline}", "window");
      auto release = time_field(v["release"], "window.release");
      if (!release) return error_reply(release.error());
      auto deadline = time_field(v["deadline"], "window.deadline");
      if (!deadline) return error_reply(deadline.error());
      window = TimeWindow{*release, *deadline};
    } else {
      return error_reply(422, "invalid", fmt::format("request: {}: unknown field (window, priority)", k), k);
    }
  }
  if (!window && !priority) return error_reply(422, "invalid", "request: nothing to change (window, priority)");
  return api.on_clock([&api, id, window, priority] {
    if (Status ok = api.ctx.fleet.update_task(id, window, priority); !ok) {
      Reply r = error_reply(ok.error());
      // "task t1.window: the deadline ..." from validate(): name the request's field.
      if (r.status == 422 && window && ok.error().message.find("window") != std::string::npos)
        r.body["error"]["field"] = "window";
      return r;
    }
    auto view = task_view(api, id);
    if (!view) return error_reply(view.error());
    Reply r;
    r.body = std::move(*view);
    return r;
  });
}

}  // namespace

void add_task_endpoints(std::vector<Endpoint>& routes) {
  routes.push_back({"POST", "/api/v1/tasks", true, submit});
  routes.push_back({"GET", "/api/v1/tasks", false, list});
  routes.push_back({"GET", "/api/v1/tasks/{id}", false, one});
  routes.push_back({"PATCH", "/api/v1/tasks/{id}", true, change});
  routes.push_back({"POST", "/api/v1/tasks/{id}/cancel", true, cancel});
  routes.push_back({"POST", "/api/v1/tasks/{id}/confirm", true, confirm});
}

}  // namespace rondo::service
