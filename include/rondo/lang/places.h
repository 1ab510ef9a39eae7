// The places a command may name (docs/commands.md, "Places"): the map's node names, and a places
// file of rooms (with the things in them), other aliases, people and named groups of nodes.
//
//   Result<Places> places = Places::load("examples/office/places.yaml", map);
//   Result<Place> p = places->resolve("the librarian's desk in room A-110");   // {A-110-Desk}
//   Result<Place> g = places->resolve("the emergency exits");                  // {Exit-West, Exit-East}
//   places->resolve("A-121");   // error: no place called 'A-121'; nearest known places: A-120, ...
//
// A phrase matches a name exactly after normalise_phrase() (case, articles, "room"/"office");
// nothing is matched by similarity. Two names that normalise alike must mean the same nodes, or
// the file is rejected.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/timezone.h"
#include "rondo/map/topo_map.h"

namespace rondo::lang {

// What a place phrase means: one node, or several for a group.
struct Place {
  std::string name;                // the name it matched, as written in the map or the places file
  std::vector<std::string> nodes;  // map node names, at least one, no repeats
  bool operator==(const Place&) const = default;
};

class Places {
 public:
  // Only the map's node names.
  static Places from_map(const map::TopoMap& map);
  // The map's node names and a places file; every node it names must be on `map`.
  static Result<Places> decode(const Document& doc, const map::TopoMap& map);
  static Result<Places> load(const std::filesystem::path& file, const map::TopoMap& map);

  // `suggest` false leaves the nearest names out of a not-found error (they cost a scan of every
  // name), for callers that try several readings before they report one.
  Result<Place> resolve(std::string_view phrase, bool suggest = true) const;
  // Whether the normalised phrase names a room ("room A-120", "the kitchen").
  bool is_room(std::string_view phrase) const;

  // The places file's `time_zone`, if it has one.
  const std::optional<TimeZone>& zone() const { return zone_; }
  // Every name a phrase can match, as written (for suggestions and documentation).
  std::vector<std::string> names() const;

 private:
  struct Entry {
    std::string display;
    std::vector<std::string> nodes;
    bool ambiguous = false;  // map nodes whose names normalise alike ("Desk" and "desk")
  };
  struct Room {
    std::string display;
    std::map<std::string, Entry> things;  // normalised name -> thing in the room
  };

  Status add_name(const std::string& key, Entry entry, const Field* where);
  Error unknown(std::string_view phrase, const std::string& key, bool suggest) const;

  std::optional<TimeZone> zone_;
  std::map<std::string, Entry> names_;                            // normalised name -> entry
  std::map<std::string, Room> rooms_;                             // normalised room name (and aliases) -> room
  std::size_t longest_room_ = 0;                                  // the longest key of rooms_
  std::vector<std::pair<std::string, std::string>> suggestions_;  // (normalised, display)

  friend class PlacesDecoder;
};

}  // namespace rondo::lang
