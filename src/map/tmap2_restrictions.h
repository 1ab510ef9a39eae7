// Private helper of the tmap2 importer: the restrictions of LCAS topological_navigation, which
// rondo keeps (on nodes, in their meta) or reports (on edges) but does not apply.
//
// A restriction is an expression over the robot and its task ('robot_short', '~allowedside_a');
// 'True' means open to every robot. The 2021 files have a `restrictions` mapping instead
// ({robot_type: '', task_name: '', transition: ''}), open when every value is empty.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "rondo/core/document.h"

namespace rondo::map {

inline constexpr std::array<const char*, 3> kRestrictionKeys = {"restrictions_planning", "restrictions_runtime",
                                                                "restrictions"};

// Whether a restriction value lets every robot through: absent or null, 'True' (or true), empty
// text, or a mapping whose values are all empty or null.
bool is_unrestricted(const Json& value);

// Collects the restrictions of a map's nodes and edges, grouped by subject, field and expression,
// and words them as warnings, one per group, in order of first appearance.
class RestrictionReport {
 public:
  enum Subject { kNode, kEdge };

  // Notes every restriction key of `item` (a tmap2 node or edge) that restricts.
  void add(Subject subject, const Field& item, const std::string& name);

  // "restrictions_planning 'robot_short' on 3 edges (the first 'A_B') is not applied: ..." At most
  // kMaxGroups sentences, then one that counts the rest.
  std::vector<std::string> warnings() const;

  static constexpr std::size_t kMaxGroups = 10;

 private:
  struct Group {
    std::size_t count = 0;
    std::string first;
  };
  using Key = std::tuple<Subject, std::string, std::string>;  // subject, field, expression
  std::map<Key, std::size_t> index_;
  std::vector<std::pair<Key, Group>> groups_;
};

}  // namespace rondo::map
