#include <fmt/format.h>

#include "decode_util.h"
#include "rondo/sim/request_generator.h"

namespace rondo::sim {
namespace {

Result<RequestTemplate> decode_template(const Field& f, const map::TopoMap& map) {
  RONDO_RETURN_IF_ERROR(f.expect_keys(
      {"name", "weight", "places", "activity", "duration", "priority", "actions", "interruptible", "deliver"}));
  RequestTemplate t;
  RONDO_ASSIGN_OR_RETURN(auto name, f.required("name"));
  RONDO_ASSIGN_OR_RETURN(t.name, name.as_string());
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "weight", 0, 1e6, t.weight));
  RONDO_ASSIGN_OR_RETURN(auto places, f.required("places"));
  RONDO_ASSIGN_OR_RETURN(auto items, places.items());
  if (items.empty()) return places.error("a request needs at least one place people ask from");
  for (const auto& item : items) {
    RONDO_ASSIGN_OR_RETURN(auto node, item.as_string());
    if (!map.find_node(node)) return item.error(fmt::format("map '{}' has no node '{}'", map.name(), node));
    t.places.push_back(std::move(node));
  }
  if (auto a = f.optional("activity")) {
    RONDO_ASSIGN_OR_RETURN(t.task.activity, a->as_string());
  }
  RONDO_RETURN_IF_ERROR(detail::read_duration(f, "duration", t.task.duration));
  double priority = 0;
  RONDO_RETURN_IF_ERROR(detail::read_number(f, "priority", -1e6, 1e6, priority));
  t.task.priority = static_cast<int>(priority);
  if (auto actions = f.optional("actions")) {
    RONDO_ASSIGN_OR_RETURN(auto list, actions->items());
    for (const auto& item : list) {
      RONDO_ASSIGN_OR_RETURN(auto a, detail::action(item));
      t.task.actions.push_back(std::move(a));
    }
  }
  if (auto i = f.optional("interruptible")) {
    RONDO_ASSIGN_OR_RETURN(t.task.interruptible, i->as_bool());
  }
  if (auto deliver = f.optional("deliver")) {
    RONDO_RETURN_IF_ERROR(deliver->expect_keys({"to", "objects", "within"}));
    DeliveryTemplate dt;
    RONDO_ASSIGN_OR_RETURN(auto to, deliver->required("to"));
    RONDO_ASSIGN_OR_RETURN(auto to_items, to.items());
    for (const auto& item : to_items) {
      RONDO_ASSIGN_OR_RETURN(auto node, item.as_string());
      if (!map.find_node(node)) return item.error(fmt::format("map '{}' has no node '{}'", map.name(), node));
      dt.to.push_back(std::move(node));
    }
    if (dt.to.empty()) return to.error("a delivery needs at least one place to bring things to");
    if (dt.to.size() == 1 && t.places.size() == 1 && dt.to.front() == t.places.front())
      return to.error("a delivery needs a place to bring things to other than where it collects them");
    RONDO_ASSIGN_OR_RETURN(auto objects, deliver->required("objects"));
    RONDO_ASSIGN_OR_RETURN(auto object_items, objects.items());
    for (const auto& item : object_items) {
      RONDO_ASSIGN_OR_RETURN(auto o, item.as_string());
      if (o.empty()) return item.error("an object needs a name");
      dt.objects.push_back(std::move(o));
    }
    if (dt.objects.empty()) return objects.error("a delivery needs at least one kind of object");
    RONDO_RETURN_IF_ERROR(detail::read_duration(*deliver, "within", dt.within));
    if (dt.within < t.task.duration) return deliver->error_at("within", "shorter than the task's duration");
    t.deliver = std::move(dt);
  }
  Task probe = t.task;
  probe.id = t.name;
  probe.kind = TaskKind::kOnDemand;
  probe.start_node = t.places.front();
  if (auto ok = validate(probe); !ok) return f.error(ok.error().message);
  return t;
}

}  // namespace

Result<RequestGenerator> RequestGenerator::decode(const Document& doc, const map::TopoMap& map,
                                                  const TimeZone& zone) {
  const Field root = doc.root();
  RONDO_RETURN_IF_ERROR(root.expect_keys({"id_prefix", "days", "from", "to", "per_day", "templates"}));
  RequestSpec spec;
  if (auto p = root.optional("id_prefix")) {
    RONDO_ASSIGN_OR_RETURN(spec.id_prefix, p->as_string());
  }
  if (auto d = root.optional("days")) {
    RONDO_ASSIGN_OR_RETURN(spec.days, detail::days(*d));
  }
  if (auto from = root.optional("from")) {
    RONDO_ASSIGN_OR_RETURN(spec.from, detail::time_of_day(*from));
  }
  if (auto to = root.optional("to")) {
    RONDO_ASSIGN_OR_RETURN(spec.to, detail::time_of_day(*to));
  }
  if (spec.to <= spec.from) return root.error_at("to", "office hours must end after they start");
  RONDO_RETURN_IF_ERROR(detail::read_number(root, "per_day", 0, 10'000, spec.per_day));
  RONDO_ASSIGN_OR_RETURN(auto templates, root.required("templates"));
  RONDO_ASSIGN_OR_RETURN(auto items, templates.items());
  if (items.empty()) return templates.error("give at least one request template");
  double total = 0;
  for (const auto& item : items) {
    RONDO_ASSIGN_OR_RETURN(auto t, decode_template(item, map));
    total += t.weight;
    spec.templates.push_back(std::move(t));
  }
  if (total <= 0) return templates.error("the templates' weights add up to 0");
  return RequestGenerator(std::move(spec), zone);
}

Result<RequestGenerator> RequestGenerator::load(const std::filesystem::path& file, const map::TopoMap& map,
                                                const TimeZone& zone) {
  RONDO_ASSIGN_OR_RETURN(auto doc, Document::load(file));
  return decode(doc, map, zone);
}

}  // namespace rondo::sim
