#include "rondo/lang/places.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "rondo/lang/words.h"

namespace rondo::lang {

// Reads a places file into a Places (the format is docs/commands.md, "The places file").
class PlacesDecoder {
 public:
  PlacesDecoder(Places& out, const map::TopoMap& map) : out_(out), map_(map) {}

  Status decode(const Field& root) {
    RONDO_RETURN_IF_ERROR(root.expect_keys({"rondo_places", "time_zone", "rooms", "places", "groups", "people"}));
    if (auto v = root.optional("rondo_places")) {
      RONDO_ASSIGN_OR_RETURN(auto version, v->as_int());
      if (version != 1) return v->error(fmt::format("places format {} is not supported (this build reads 1)", version));
    }
    if (auto z = root.optional("time_zone")) {
      RONDO_ASSIGN_OR_RETURN(auto name, z->as_string());
      auto zone = TimeZone::named(name);
      if (!zone) return z->error(zone.error().message);
      out_.zone_ = *zone;
    }
    // People come last: their place may be any phrase the rest of the file defines.
    for (const char* section : {"rooms", "places", "groups", "people"}) {
      auto list = root.optional(section);
      if (!list) continue;
      RONDO_ASSIGN_OR_RETURN(auto items, list->items());
      for (const auto& item : items) {
        const std::string_view s = section;
        if (s == "rooms") RONDO_RETURN_IF_ERROR(room(item));
        if (s == "places") RONDO_RETURN_IF_ERROR(place(item));
        if (s == "groups") RONDO_RETURN_IF_ERROR(group(item));
        if (s == "people") RONDO_RETURN_IF_ERROR(person(item));
      }
    }
    return {};
  }

 private:
  Result<std::string> node(const Field& f) {
    RONDO_ASSIGN_OR_RETURN(auto name, f.as_string());
    if (map_.find_node(name)) return name;
    std::vector<std::string> all;
    for (const auto& n : map_.nodes()) all.push_back(n.name);
    return f.error(fmt::format("map '{}' has no node '{}' (nearest: {})", map_.name(), name,
                               fmt::join(nearest(name, all, 3), ", ")));
  }

  Result<std::string> name_of(const Field& f, const char* key = "name") {
    RONDO_ASSIGN_OR_RETURN(auto field, f.required(key));
    RONDO_ASSIGN_OR_RETURN(auto name, field.as_string());
    if (normalise_phrase(name).empty()) return field.error("a name needs at least one word");
    return name;
  }

  // The name and its aliases, each with the field it came from.
  Result<std::vector<std::pair<std::string, Field>>> names_of(const Field& f) {
    std::vector<std::pair<std::string, Field>> out;
    RONDO_ASSIGN_OR_RETURN(auto name_field, f.required("name"));
    RONDO_ASSIGN_OR_RETURN(auto name, name_of(f));
    out.emplace_back(name, name_field);
    if (auto aliases = f.optional("aliases")) {
      RONDO_ASSIGN_OR_RETURN(auto items, aliases->items());
      for (const auto& a : items) {
        RONDO_ASSIGN_OR_RETURN(auto alias, a.as_string());
        if (normalise_phrase(alias).empty()) return a.error("a name needs at least one word");
        out.emplace_back(alias, a);
      }
    }
    return out;
  }

  Status add(const std::vector<std::pair<std::string, Field>>& names, const std::vector<std::string>& nodes) {
    for (const auto& [name, where] : names) {
      RONDO_RETURN_IF_ERROR(out_.add_name(normalise_phrase(name), {name, nodes}, &where));
    }
    return {};
  }

  Status room(const Field& f) {
    RONDO_RETURN_IF_ERROR(f.expect_keys({"name", "node", "aliases", "places"}));
    RONDO_ASSIGN_OR_RETURN(auto names, names_of(f));
    RONDO_ASSIGN_OR_RETURN(auto node_field, f.required("node"));
    RONDO_ASSIGN_OR_RETURN(auto room_node, node(node_field));
    RONDO_RETURN_IF_ERROR(add(names, {room_node}));
    Places::Room room{names.front().first, {}};
    if (auto things = f.optional("places")) {
      RONDO_ASSIGN_OR_RETURN(auto items, things->items());
      for (const auto& t : items) {
        RONDO_RETURN_IF_ERROR(t.expect_keys({"name", "node", "aliases"}));
        RONDO_ASSIGN_OR_RETURN(auto thing_names, names_of(t));
        RONDO_ASSIGN_OR_RETURN(auto thing_node_field, t.required("node"));
        RONDO_ASSIGN_OR_RETURN(auto thing_node, node(thing_node_field));
        for (const auto& [thing, where] : thing_names) {
          const std::string key = normalise_phrase(thing);
          auto [it, fresh] = room.things.emplace(key, Places::Entry{thing_names.front().first, {thing_node}});
          if (!fresh && it->second.nodes != std::vector<std::string>{thing_node}) {
            return where.error(
                fmt::format("'{}' already names {} in room {}", thing, it->second.nodes.front(), room.display));
          }
          out_.suggestions_.emplace_back(key + " in " + normalise_phrase(room.display), thing + " in " + room.display);
        }
      }
    }
    for (const auto& [name, where] : names) {
      const std::string key = normalise_phrase(name);
      if (!out_.rooms_.emplace(key, room).second) return where.error(fmt::format("room '{}' is defined twice", name));
      out_.longest_room_ = std::max(out_.longest_room_, key.size());
    }
    return {};
  }

  Status place(const Field& f) {
    RONDO_RETURN_IF_ERROR(f.expect_keys({"name", "node", "aliases"}));
    RONDO_ASSIGN_OR_RETURN(auto names, names_of(f));
    RONDO_ASSIGN_OR_RETURN(auto node_field, f.required("node"));
    RONDO_ASSIGN_OR_RETURN(auto n, node(node_field));
    return add(names, {n});
  }

  Status group(const Field& f) {
    RONDO_RETURN_IF_ERROR(f.expect_keys({"name", "nodes", "aliases"}));
    RONDO_ASSIGN_OR_RETURN(auto names, names_of(f));
    RONDO_ASSIGN_OR_RETURN(auto list, f.required("nodes"));
    RONDO_ASSIGN_OR_RETURN(auto items, list.items());
    if (items.empty()) return list.error("a group needs at least one node");
    std::vector<std::string> nodes;
    for (const auto& item : items) {
      RONDO_ASSIGN_OR_RETURN(auto n, node(item));
      if (std::find(nodes.begin(), nodes.end(), n) != nodes.end())
        return item.error(fmt::format("node '{}' is listed twice", n));
      nodes.push_back(std::move(n));
    }
    return add(names, nodes);
  }

  // A person's name, "NAME's", "NAME's desk" and "NAME's place" all mean the person's place.
  Status person(const Field& f) {
    RONDO_RETURN_IF_ERROR(f.expect_keys({"name", "place", "aliases"}));
    RONDO_ASSIGN_OR_RETURN(auto names, names_of(f));
    RONDO_ASSIGN_OR_RETURN(auto place_field, f.required("place"));
    RONDO_ASSIGN_OR_RETURN(auto phrase, place_field.as_string());
    auto where = out_.resolve(phrase);
    if (!where) return place_field.error(where.error().message);
    if (where->nodes.size() != 1)
      return place_field.error(fmt::format("'{}' is {} places; a person has one", phrase, where->nodes.size()));
    for (const auto& [name, field] : names) {
      const std::string key = normalise_phrase(name);
      for (const char* form : {"", "'s", "'s desk", "'s place"}) {
        RONDO_RETURN_IF_ERROR(out_.add_name(key + form, {name + form, where->nodes}, &field));
      }
    }
    return {};
  }

  Places& out_;
  const map::TopoMap& map_;
};

Places Places::from_map(const map::TopoMap& map) {
  Places p;
  for (const auto& n : map.nodes()) {
    const std::string key = normalise_phrase(n.name);
    auto [it, fresh] = p.names_.emplace(key, Entry{n.name, {n.name}});
    if (fresh) {
      p.suggestions_.emplace_back(key, n.name);
    } else {
      // Two node names that differ only in case or spacing: neither may be named by a phrase
      // alone (an empty entry is reported as ambiguous).
      it->second.nodes.push_back(n.name);
      it->second.display += " / " + n.name;
      it->second.ambiguous = true;
    }
  }
  return p;
}

Result<Places> Places::decode(const Document& doc, const map::TopoMap& map) {
  Places p = from_map(map);
  PlacesDecoder decoder(p, map);
  RONDO_RETURN_IF_ERROR(decoder.decode(doc.root()));
  return p;
}

Result<Places> Places::load(const std::filesystem::path& file, const map::TopoMap& map) {
  RONDO_ASSIGN_OR_RETURN(auto doc, Document::load(file));
  return decode(doc, map);
}

Status Places::add_name(const std::string& key, Entry entry, const Field* where) {
  auto [it, fresh] = names_.emplace(key, entry);
  if (fresh) {
    suggestions_.emplace_back(key, entry.display);
    return {};
  }
  if (it->second.nodes == entry.nodes) return {};
  const std::string message =
      fmt::format("'{}' already names {} ({})", entry.display, fmt::join(it->second.nodes, ", "), it->second.display);
  return where ? where->error(message) : Error::invalid(message);
}

bool Places::is_room(std::string_view phrase) const {
  return rooms_.count(normalise_phrase(phrase)) > 0;
}

std::vector<std::string> Places::names() const {
  std::vector<std::string> out;
  for (const auto& s : suggestions_) out.push_back(s.second);
  return out;
}

Error Places::unknown(std::string_view phrase, const std::string& key, bool suggest) const {
  if (!suggest) return Error::not_found(fmt::format("no place called '{}'", phrase));
  std::vector<std::string> keys;
  for (const auto& s : suggestions_) keys.push_back(s.first);
  std::vector<std::string> shown;
  for (const auto& k : nearest(key, keys, 3)) {
    for (const auto& s : suggestions_) {
      if (s.first == k) {
        shown.push_back(s.second);
        break;
      }
    }
  }
  return Error::not_found(
      fmt::format("no place called '{}'; nearest known places: {}", phrase, fmt::join(shown, ", ")));
}

Result<Place> Places::resolve(std::string_view phrase, bool suggest) const {
  const std::string key = normalise_phrase(phrase);
  if (key.empty()) return Error::invalid("a place is missing (nothing where a place should be)");
  if (auto it = names_.find(key); it != names_.end()) {
    if (it->second.ambiguous) {
      return Error::invalid(
          fmt::format("'{}' could be any of the nodes {}; use a places-file alias", phrase, it->second.display));
    }
    return Place{it->second.display, it->second.nodes};
  }
  // "THING in ROOM": the last " in " whose right side is a room.
  std::optional<Error> room_error;
  for (std::size_t at = key.rfind(" in "); at != std::string::npos && at > 0; at = key.rfind(" in ", at - 1)) {
    if (key.size() - (at + 4) > longest_room_) break;  // every room name further left is longer still
    const auto room = rooms_.find(key.substr(at + 4));
    if (room == rooms_.end()) continue;
    const std::string thing = key.substr(0, at);
    if (auto t = room->second.things.find(thing); t != room->second.things.end()) {
      return Place{t->second.display + " in " + room->second.display, t->second.nodes};
    }
    std::vector<std::string> has;
    for (const auto& [k, e] : room->second.things) {
      if (std::find(has.begin(), has.end(), e.display) == has.end()) has.push_back(e.display);
    }
    room_error = Error::not_found(
        fmt::format("room {} has no place called '{}' ({})", room->second.display, thing,
                    has.empty() ? "it has no named places" : "it has: " + fmt::format("{}", fmt::join(has, ", "))));
    break;
  }
  if (room_error) return *room_error;
  // A thing named in exactly one room needs no room; in several it is ambiguous.
  std::vector<std::pair<const Room*, const Entry*>> found;
  for (const auto& [room_key, room] : rooms_) {
    if (auto t = room.things.find(key); t != room.things.end()) {
      const bool seen =
          std::any_of(found.begin(), found.end(), [&](const auto& f) { return f.second->nodes == t->second.nodes; });
      if (!seen) found.emplace_back(&room, &t->second);
    }
  }
  if (found.size() == 1)
    return Place{found[0].second->display + " in " + found[0].first->display, found[0].second->nodes};
  if (found.size() > 1) {
    std::vector<std::string> which;
    which.reserve(found.size());
    for (const auto& [room, entry] : found) which.push_back("'" + entry->display + " in " + room->display + "'");
    return Error::invalid(
        fmt::format("'{}' is in more than one room; say which: {}", phrase, fmt::join(which, " or ")));
  }
  return unknown(phrase, key, suggest);
}

}  // namespace rondo::lang
