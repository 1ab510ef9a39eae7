#include "rondo/service/stored_routines.h"
#include "rondo/ltl/task_formula.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "api.h"
#include "rondo/core/task_codec.h"
#include "rondo/store/robot_state.h"

namespace rondo::service {
namespace {

constexpr const char* kKey = kStoredRoutinesKey;

// A stored routine's name, or empty when it has none.
std::string name_of(const Json& routine) {
  if (!routine.is_object()) return {};
  const auto it = routine.find("name");
  return it != routine.end() && it->is_string() ? it->get<std::string>() : std::string{};
}

Result<Json> load(const store::Store& store) {
  RONDO_ASSIGN_OR_RETURN(const std::optional<std::string> text, store::get_meta(store, kKey));
  if (!text) return Json{{"added", Json::array()}, {"removed", Json::array()}};
  Json j = Json::parse(*text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("added") || !j["added"].is_array() || !j.contains("removed") ||
      !j["removed"].is_array())
    return Error::invalid(fmt::format("store meta '{}': not {{\"added\": [...], \"removed\": [...]}}", kKey));
  return j;
}

void erase_added(Json& j, const std::string& name) {
  Json& added = j["added"];
  for (auto it = added.begin(); it != added.end();) it = name_of(*it) == name ? added.erase(it) : std::next(it);
}

}  // namespace

Status remember_added_routine(store::Store& store, const Routine& routine) {
  RONDO_ASSIGN_OR_RETURN(const std::string value, stored_with_added(store, {routine}));
  return store::set_meta(store, kKey, value);
}

Result<std::string> stored_with_added(const store::Store& store, const std::vector<Routine>& routines) {
  RONDO_ASSIGN_OR_RETURN(Json j, load(store));
  for (const Routine& routine : routines) {
    erase_added(j, routine.name);
    j["added"].push_back(encode(routine));
  }
  return j.dump();
}

Status remember_removed_routine(store::Store& store, const std::string& name) {
  RONDO_ASSIGN_OR_RETURN(Json j, load(store));
  erase_added(j, name);
  Json& removed = j["removed"];
  if (std::find(removed.begin(), removed.end(), Json(name)) == removed.end()) removed.push_back(name);
  return store::set_meta(store, kKey, j.dump());
}

Result<std::vector<Routine>> routines_to_run(store::Store& store, std::vector<Routine> deployment,
                                             const map::TopoMap& map, const TimeZone& zone,
                                             std::vector<std::string>* skipped) {
  RONDO_ASSIGN_OR_RETURN(Json j, load(store));
  std::set<std::string> gone;
  for (const Json& name : j.at("removed"))
    if (name.is_string()) gone.insert(name.get<std::string>());
  const auto known = [&map](std::string_view n) { return map.find_node(n).has_value(); };
  const PlaceCheck places{known, map.name(),
                          [&](std::string_view f) { return ltl::check_task_formula(f, known, map.name()); }};
  std::vector<Routine> added;
  for (const Json& r : j.at("added")) {
    const std::string name = name_of(r);
    if (!name.empty()) gone.insert(name);
    auto file = parse_task_file(with_default_zone(Json{{"routines", Json::array({r})}}, zone), DocumentFormat::kJson,
                                fmt::format("store meta '{}'", kKey), &places);
    if (!file || file->routines.size() != 1) {
      if (skipped)
        skipped->push_back(
            fmt::format("{}: {}", name.empty() ? "?" : name, file ? "not one routine" : file.error().message));
      continue;
    }
    added.push_back(std::move(file->routines.front()));
  }
  std::erase_if(deployment, [&gone](const Routine& r) { return gone.contains(r.name); });
  for (Routine& r : added) deployment.push_back(std::move(r));
  return deployment;
}

}  // namespace rondo::service
