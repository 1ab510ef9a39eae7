#include "rondo/lang/command.h"

#include <algorithm>

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

}  // namespace rondo::lang
