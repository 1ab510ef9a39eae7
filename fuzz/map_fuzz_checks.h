// What every map fuzz target checks about a parse result, beyond "no crash, no hang":
// an error is an invalid-input error with a message; a map survives everything the command line
// does with it (summary, warnings, travel times) and round-trips through rondo's format unchanged.
#pragma once

#include <cstdio>
#include <cstdlib>

#include "rondo/map/map_geometry.h"
#include "rondo/map/map_summary.h"
#include "rondo/map/map_validation.h"
#include "rondo/map/map_yaml.h"

namespace rondo::map::fuzz {

[[noreturn]] inline void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz invariant broken: %s\n%s\n", what, detail.c_str());
  std::abort();
}

inline void check_parse_result(const Result<TopoMap>& result) {
  if (!result) {
    if (result.error().code != ErrorCode::kInvalidInput) fail("error is not kInvalidInput", result.error().message);
    if (result.error().message.empty()) fail("error without a message", "");
    return;
  }
  const TopoMap& map = *result;
  if (map.node_count() == 0) fail("a loaded map has no nodes", "");
  const MapSummary summary = summarize(map);
  (void)to_json(summary).dump(-1, ' ', false, Json::error_handler_t::replace);
  for (EdgeIndex e = 0; e < map.edge_count(); ++e) {
    if (nominal_travel_time(map, e).count() < 0) fail("negative travel time", map.edge(e).id);
  }
  const std::string text = write_map_yaml(map);
  auto again = parse_map_yaml(text, "roundtrip.yaml");
  if (!again) fail("written map does not read back", again.error().message + "\n" + text);
  if (!(*again == map)) fail("written map reads back different", text);
}

}  // namespace rondo::map::fuzz
