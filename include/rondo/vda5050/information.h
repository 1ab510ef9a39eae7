// The vehicle's information[] entries that are observations (docs/vda5050.md, "Observations"):
// which infoType means a door's state, a blocked edge or a person seen is the deployment's, per
// vehicle, because vendors differ.
//
//   robot:
//     kind: vda5050
//     ...
//     information:
//       - info_type: DOOR_STATE        # infoType, exactly
//         kind: door_open              # door_open, edge_blocked or person_present
//         where_key: doorId            # the infoReferences key whose value is the place (or where: A-120-door)
//         value_key: state             # the infoReferences key whose value is read (absent: infoDescription)
//         values: {OPEN: 1, CLOSED: 0} # what it says -> the observation's value
//
//   InformationReader reader(config.information, map);
//   InformationReader::Reading r = reader.read(state.information, now);   // r.seen, r.ignored
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/exec/robot.h"
#include "rondo/map/topo_map.h"

namespace rondo::vda5050 {

struct Information;  // messages.h (not included here: config.h is read where rondo::Action is meant)

// One infoType that is an observation.
struct InformationRule {
  std::string info_type;
  std::string kind;       // exec::Observation::kDoorOpen, kEdgeBlocked or kPersonPresent
  std::string where;      // a fixed place (a door, an edge id, a node), or ""
  std::string where_key;  // the infoReferences key whose value is the place, or ""
  std::string value_key;  // the infoReferences key whose value is read; "": infoDescription
  std::map<std::string, double> values;  // what the entry says -> the observation's value (0 or 1)
  std::string origin;  // "deployment.yaml:12: robot.information[0]": for the checks against the map
  bool operator==(const InformationRule&) const = default;
};

// The robot section's `information` list. Errors name the file, line and field
// ("deployment.yaml:14: robot.information[1].kind: 'door' is not an observation kind ...").
Result<std::vector<InformationRule>> parse_information_rules(const Field& list);

// Whether `place` is a place of `kind` on `map` (a door for door_open, an edge id for
// edge_blocked, a node for person_present); the error says what it is not.
Status check_place(const std::string& kind, const std::string& place, const map::TopoMap& map);
// The rules' fixed places against the map: the first that is not there, named by its origin.
Status check_information_places(const std::vector<InformationRule>& rules, const map::TopoMap& map);

// Reads the information[] of the vehicle's states into observations. An entry is reported when
// it is first seen, when its value changes, and again every `repeat_every` while it holds (a door
// that stays shut is seen shut over time, as the simulated sensor sees it at every pass); an
// entry that goes away reports nothing (not knowing is not "open"). An entry of a mapped infoType
// that cannot be read (no place, a place not on the map, a value not in `values`) is ignored,
// with the reason, once per distinct reason. Pure: time is an argument.
class InformationReader {
 public:
  struct Reading {
    std::vector<exec::Observation> seen;
    std::vector<std::string> ignored;  // reasons, each once
  };

  InformationReader(std::vector<InformationRule> rules, const map::TopoMap& map, Duration repeat_every = minutes(5));

  Reading read(const std::vector<Information>& information, Time now);

 private:
  const InformationRule* rule_for(const std::string& info_type) const;
  struct Last {
    double value = 0;
    Time reported{};
  };
  std::vector<InformationRule> rules_;
  const map::TopoMap* map_;
  Duration repeat_every_;
  std::map<std::pair<std::string, std::string>, Last> last_;  // (kind, place)
  std::set<std::string> told_;                                // reasons already given
};

}  // namespace rondo::vda5050
