// The Witham Wharf log split the way the reference figures were computed (data/README.md).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rondo/core/traversal.h"
#include "rondo/learn/edge_predictor.h"
#include "source_dir.h"

namespace rondo::learn::testing {

inline const std::string kWithamDir = (rondo::testing::source_dir() / ".." / "shared" / "data" / "witham_wharf").string();

struct WithamEdge {
  std::string id;
  std::vector<Attempt> train, test;
};

// The edges with >= 20 attempts before 2014-09-02T16:24:00Z and >= 5 after it; empty when the
// data is not on this machine.
inline std::vector<WithamEdge> witham_split() {
  auto log = read_witham_logs(kWithamDir);
  if (!log) return {};
  const Time split = *parse_time("2014-09-02T16:24:00Z");
  std::map<std::string, WithamEdge> by_id;
  for (const Traversal& t : *log) {
    auto& e = by_id[t.edge_id];
    e.id = t.edge_id;
    (t.start < split ? e.train : e.test).push_back({t.start, t.start + t.duration, to_seconds(t.duration), t.success});
  }
  std::vector<WithamEdge> out;
  for (auto& [id, e] : by_id) {
    if (e.train.size() >= 20 && e.test.size() >= 5) out.push_back(std::move(e));
  }
  return out;
}

}  // namespace rondo::learn::testing
