#include "tmap2_restrictions.h"

#include <fmt/format.h>

#include "map_locate.h"

namespace rondo::map {

bool is_unrestricted(const Json& value) {
  if (value.is_null()) return true;
  if (value.is_boolean()) return value.get<bool>();
  if (value.is_string()) {
    const auto& s = value.get_ref<const std::string&>();
    return s.empty() || s == "True" || s == "true";
  }
  if (value.is_object()) {
    for (const auto& v : value) {
      if (!(v.is_null() || (v.is_string() && v.get_ref<const std::string&>().empty()))) return false;
    }
    return true;
  }
  return false;
}

void RestrictionReport::add(Subject subject, const Field& item, const std::string& name) {
  for (const char* key : kRestrictionKeys) {
    auto f = item.optional(key);
    if (!f || is_unrestricted(f->json())) continue;
    std::string expression =
        f->is_string() ? f->json().get<std::string>() : f->json().dump(-1, ' ', false, Json::error_handler_t::replace);
    Key k{subject, key, std::move(expression)};
    auto [it, inserted] = index_.try_emplace(k, groups_.size());
    if (inserted) groups_.push_back({std::move(k), Group{0, name}});
    ++groups_[it->second].second.count;
  }
}

std::vector<std::string> RestrictionReport::warnings() const {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < groups_.size() && i < kMaxGroups; ++i) {
    const auto& [key, group] = groups_[i];
    const auto& [subject, field, expression] = key;
    const bool node = subject == kNode;
    const char* what = node ? (group.count == 1 ? "node" : "nodes") : (group.count == 1 ? "edge" : "edges");
    out.push_back(fmt::format("{} {} on {} {} (the first {}) is {}not applied: rondo plans as if open to every robot",
                              field, quoted_name(expression), group.count, what, quoted_name(group.first),
                              node ? "kept in the node's meta but " : ""));
  }
  if (groups_.size() > kMaxGroups) {
    out.push_back(fmt::format("and {} more kinds of restriction, not applied either", groups_.size() - kMaxGroups));
  }
  return out;
}

}  // namespace rondo::map
