#include <fmt/format.h>

#include "api.h"
#include "rondo/core/task_codec.h"
#include "rondo/store/events.h"

namespace rondo::service {

std::optional<Reply> read_json_object(const httplib::Request& req, Json& body) {
  // nlohmann's syntax check tells text that is not JSON (400) from JSON that cannot be meant (422).
  if (!Json::accept(req.body)) return error_reply(400, "malformed", "the body is not JSON");
  auto doc = Document::parse(req.body, DocumentFormat::kJson, "request body");
  if (!doc) return error_reply(doc.error());
  if (!doc->json().is_object()) return error_reply(400, "malformed", "the body must be a JSON object");
  body = doc->json();
  return std::nullopt;
}

std::string with_default_zone(Json body, const TimeZone& zone) {
  if (body.is_object() && !body.contains("timezone")) body["timezone"] = zone.name();
  return body.dump();
}

Json time_json(std::optional<Time> t) {
  return t ? Json(format_time(*t)) : Json(nullptr);
}

Json task_json(const exec::TaskRecord& r) {
  const Task& t = r.task;
  Json j{{"id", t.id},
         {"activity", t.activity},
         {"kind", to_string(t.kind)},
         {"state", to_string(r.state)},
         {"code", std::string(exec::to_string(r.outcome))},
         {"reason", r.reason},
         {"source", r.source},
         {"robot", r.robot.empty() ? Json(nullptr) : Json(r.robot)},
         {"priority", t.priority},
         {"start_node", t.start_node},
         {"duration_s", to_seconds(t.duration)},
         {"added", time_json(r.added)},
         {"window",
          t.window ? Json{{"release", format_time(t.window->release)}, {"deadline", format_time(t.window->deadline)}}
                   : Json(nullptr)},
         {"planned", Json{{"start", time_json(r.planned_start)}, {"end", time_json(r.planned_end)}}},
         {"actual", Json{{"start", time_json(r.started)}, {"end", time_json(r.ended)}}},
         {"dropped_for_now", r.dropped_for_now ? Json{{"code", std::string(exec::to_string(r.dropped_for_now->first))},
                                                      {"reason", r.dropped_for_now->second}}
                                               : Json(nullptr)},
         {"task", encode(t)}};
  // A task written as a formula: its automaton state (what its journey has done) and the node
  // that satisfied it, once one did.
  if (t.has_spec())
    j["spec"] = Json{{"formula", t.spec},
                     {"state", r.spec_state ? Json(*r.spec_state) : Json(nullptr)},
                     {"satisfied_at", r.spec_place.empty() ? Json(nullptr) : Json(r.spec_place)}};
  return j;
}

Json event_json(const store::Event& e) {
  return Json{{"seq", e.seq},
              {"time", format_time(e.time)},
              {"subject", store::to_string(e.subject)},
              {"task_id", e.task_id.empty() ? Json(nullptr) : Json(e.task_id)},
              {"about", e.about.empty() ? Json(nullptr) : Json(e.about)},
              {"robot", e.robot.empty() ? Json(nullptr) : Json(e.robot)},
              {"event", e.event},
              {"code", e.code},
              {"reason", e.reason}};
}

Result<std::optional<Time>> query_time(const httplib::Request& req, const char* name) {
  if (!req.has_param(name)) return std::optional<Time>{};
  auto t = parse_time(req.get_param_value(name));
  if (!t) return Error::invalid(fmt::format("query: {}: {}", name, t.error().message));
  return std::optional<Time>(*t);
}

Result<std::optional<long>> query_int(const httplib::Request& req, const char* name, long min, long max) {
  if (!req.has_param(name)) return std::optional<long>{};
  const std::string text = req.get_param_value(name);
  long v = 0;
  std::size_t used = 0;
  try {
    v = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || v < min || v > max)
    return Error::invalid(
        fmt::format("query: {}: expected a whole number from {} to {}, found '{}'", name, min, max, text));
  return std::optional<long>(v);
}

}  // namespace rondo::service
