#include "rondo/lang/command.h"

#include <algorithm>

#include <fmt/format.h>

#include "rondo/lang/words.h"

namespace rondo::lang {

const char* to_string(Cancellation::What what) {
  switch (what) {
    case Cancellation::What::kDelivery:
      return "delivery";
    case Cancellation::What::kActivity:
      return "activity";
    case Cancellation::What::kTask:
      return "task";
  }
  return "unknown";
}

bool matches(const Cancellation& c, const Task& task) {
  switch (c.what) {
    case Cancellation::What::kDelivery:
      return task.delivery && normalise_object(task.delivery->object) == c.object;
    case Cancellation::What::kActivity: {
      const bool does =
          std::any_of(task.actions.begin(), task.actions.end(), [&](const Action& a) { return a.name == c.activity; });
      return does && std::find(c.nodes.begin(), c.nodes.end(), task.start_node) != c.nodes.end();
    }
    case Cancellation::What::kTask:
      return task.id == c.id || task.id.rfind(c.id + "@", 0) == 0;
  }
  return false;
}

Json encode(const Cancellation& c) {
  Json what{{"what", to_string(c.what)}};
  switch (c.what) {
    case Cancellation::What::kDelivery:
      what["object"] = c.object;
      break;
    case Cancellation::What::kActivity:
      what["activity"] = c.activity;
      what["nodes"] = c.nodes;
      break;
    case Cancellation::What::kTask:
      what["id"] = c.id;
      break;
  }
  return Json{{"cancel", what}};
}

Result<Cancellation> decode_cancellation(const Json& j) {
  const auto text = [](const Json& o, const char* key) -> Result<std::string> {
    if (!o.is_object() || !o.contains(key) || !o[key].is_string() || o[key].get<std::string>().empty())
      return Error::invalid(fmt::format("cancel.{}: a non-empty text is needed", key));
    return o[key].get<std::string>();
  };
  if (!j.is_object() || !j.contains("cancel") || !j["cancel"].is_object())
    return Error::invalid("cancel: an object is needed");
  const Json& c = j["cancel"];
  RONDO_ASSIGN_OR_RETURN(const std::string what, text(c, "what"));
  Cancellation out;
  if (what == "delivery") {
    out.what = Cancellation::What::kDelivery;
    RONDO_ASSIGN_OR_RETURN(out.object, text(c, "object"));
  } else if (what == "activity") {
    out.what = Cancellation::What::kActivity;
    RONDO_ASSIGN_OR_RETURN(out.activity, text(c, "activity"));
    if (!c.contains("nodes") || !c["nodes"].is_array() || c["nodes"].empty())
      return Error::invalid("cancel.nodes: a non-empty list of node names is needed");
    for (const Json& n : c["nodes"]) {
      if (!n.is_string()) return Error::invalid("cancel.nodes: a non-empty list of node names is needed");
      out.nodes.push_back(n.get<std::string>());
    }
  } else if (what == "task") {
    out.what = Cancellation::What::kTask;
    RONDO_ASSIGN_OR_RETURN(out.id, text(c, "id"));
  } else {
    return Error::invalid(fmt::format("cancel.what: '{}' is not delivery, activity or task", what));
  }
  return out;
}

}  // namespace rondo::lang
