#include "rondo/vda5050/information.h"

#include <fmt/format.h>

#include <algorithm>

#include "rondo/vda5050/messages.h"

namespace rondo::vda5050 {
namespace {

constexpr std::string_view kKinds[] = {exec::Observation::kDoorOpen, exec::Observation::kEdgeBlocked,
                                       exec::Observation::kPersonPresent};

Result<std::string> text(const Field& f, std::string_view key) {
  RONDO_ASSIGN_OR_RETURN(Field v, f.required(key));
  RONDO_ASSIGN_OR_RETURN(std::string s, v.as_string());
  if (s.empty()) return v.error("must not be empty");
  return s;
}

Result<InformationRule> parse_rule(const Field& f) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"info_type", "kind", "where", "where_key", "value_key", "values"}));
  InformationRule r;
  RONDO_ASSIGN_OR_RETURN(r.info_type, text(f, "info_type"));
  RONDO_ASSIGN_OR_RETURN(r.kind, text(f, "kind"));
  if (std::find(std::begin(kKinds), std::end(kKinds), r.kind) == std::end(kKinds))
    return f.error_at("kind", fmt::format("'{}' is not an observation kind (door_open, edge_blocked or person_present)",
                                          r.kind));
  r.origin = f.where();
  if (f.has("where") == f.has("where_key"))
    return f.error("give the place either as where (a fixed place) or as where_key (an infoReferences key), "
                   "exactly one of them");
  if (f.has("where")) {
    RONDO_ASSIGN_OR_RETURN(r.where, text(f, "where"));
    r.origin = f.required("where")->where();
  } else {
    RONDO_ASSIGN_OR_RETURN(r.where_key, text(f, "where_key"));
  }
  if (f.has("value_key")) {
    RONDO_ASSIGN_OR_RETURN(r.value_key, text(f, "value_key"));
    if (r.value_key == r.where_key) return f.error_at("value_key", "must not be the where_key");
  }
  RONDO_ASSIGN_OR_RETURN(Field values, f.required("values"));
  RONDO_ASSIGN_OR_RETURN(auto members, values.members());
  if (members.empty()) return values.error("must map at least one text to a value, e.g. {OPEN: 1, CLOSED: 0}");
  for (const auto& [said, value] : members) {
    RONDO_ASSIGN_OR_RETURN(const double v, value.as_number());
    if (v != 0 && v != 1) return value.error("must be 1 or 0 (the observation is binary)");
    r.values[said] = v;
  }
  return r;
}

}  // namespace

Result<std::vector<InformationRule>> parse_information_rules(const Field& list) {
  RONDO_ASSIGN_OR_RETURN(auto items, list.items());
  std::vector<InformationRule> rules;
  for (const Field& f : items) {
    RONDO_ASSIGN_OR_RETURN(InformationRule r, parse_rule(f));
    for (std::size_t i = 0; i < rules.size(); ++i)
      if (rules[i].info_type == r.info_type)
        return f.error_at("info_type", fmt::format("'{}' is mapped already by {}[{}]", r.info_type, list.path(), i));
    rules.push_back(std::move(r));
  }
  return rules;
}

Status check_place(const std::string& kind, const std::string& place, const map::TopoMap& map) {
  if (kind == exec::Observation::kDoorOpen) {
    for (const map::Edge& e : map.edges())
      if (e.door && *e.door == place) return Status{};
    return Error::invalid(fmt::format("'{}' is not a door of map '{}'", place, map.name()));
  }
  if (kind == exec::Observation::kEdgeBlocked) {
    if (map.find_edge(place)) return Status{};
    return Error::invalid(fmt::format("'{}' is not an edge of map '{}'", place, map.name()));
  }
  if (map.find_node(place)) return Status{};
  return Error::invalid(fmt::format("'{}' is not a node of map '{}'", place, map.name()));
}

Status check_information_places(const std::vector<InformationRule>& rules, const map::TopoMap& map) {
  for (const InformationRule& r : rules) {
    if (r.where.empty()) continue;
    if (Status ok = check_place(r.kind, r.where, map); !ok)
      return Error::invalid(fmt::format("{}: {}", r.origin, ok.error().message));
  }
  return Status{};
}

InformationReader::InformationReader(std::vector<InformationRule> rules, const map::TopoMap& map,
                                     Duration repeat_every)
    : rules_(std::move(rules)), map_(&map), repeat_every_(repeat_every) {}

const InformationRule* InformationReader::rule_for(const std::string& info_type) const {
  for (const InformationRule& r : rules_)
    if (r.info_type == info_type) return &r;
  return nullptr;
}

InformationReader::Reading InformationReader::read(const std::vector<Information>& information, Time now) {
  Reading out;
  const auto ignore = [&](std::string why) {
    if (told_.insert(why).second) out.ignored.push_back(std::move(why));
  };
  for (std::size_t i = 0; i < information.size(); ++i) {
    const Information& info = information[i];
    const InformationRule* rule = rule_for(info.info_type);
    if (rule == nullptr) continue;  // not an observation: the vendor's other news
    const auto reference = [&info](const std::string& key) -> std::optional<std::string> {
      for (const ErrorReference& r : info.info_references)
        if (r.reference_key == key) return r.reference_value;
      return std::nullopt;
    };
    const std::string entry = fmt::format("state: information[{}] (infoType {})", i, info.info_type);
    std::string place = rule->where;
    if (!rule->where_key.empty()) {
      const std::optional<std::string> p = reference(rule->where_key);
      if (!p) {
        ignore(fmt::format("{}: no infoReference '{}' naming the place", entry, rule->where_key));
        continue;
      }
      place = *p;
      if (Status ok = check_place(rule->kind, place, *map_); !ok) {
        ignore(fmt::format("{}: {}", entry, ok.error().message));
        continue;
      }
    }
    std::string said = info.info_description;
    if (!rule->value_key.empty()) {
      const std::optional<std::string> v = reference(rule->value_key);
      if (!v) {
        ignore(fmt::format("{}: no infoReference '{}' giving the value", entry, rule->value_key));
        continue;
      }
      said = *v;
    }
    const auto value = rule->values.find(said);
    if (value == rule->values.end()) {
      std::string known;
      for (const auto& [k, v] : rule->values) known += (known.empty() ? "" : ", ") + k;
      ignore(fmt::format("{}: '{}' is not one of {}", entry, said, known));
      continue;
    }
    const auto key = std::make_pair(rule->kind, place);
    const auto last = last_.find(key);
    if (last != last_.end() && last->second.value == value->second && now - last->second.reported < repeat_every_)
      continue;
    last_[key] = {.value = value->second, .reported = now};
    out.seen.push_back({.what = rule->kind,
                        .where = place,
                        .when = now,
                        .value = value->second,
                        .text = fmt::format("VDA 5050 information {}: {}", info.info_type, said)});
  }
  return out;
}

}  // namespace rondo::vda5050
