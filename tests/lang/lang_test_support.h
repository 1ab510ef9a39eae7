// The example office floor (examples/office) as the context of language tests: its map, its
// places file, London time, and "now" at Monday 2026-11-23 10:00 (GMT, so local = UTC).
#pragma once

#include <string>

#include <fmt/format.h>

#include "rondo/lang/command.h"
#include "rondo/map/map_loader.h"

namespace rondo::lang::test {

struct Office {
  map::TopoMap map;
  Places places;
  CommandContext ctx;
};

inline const Office& office() {
  static const Office o = [] {
    auto m = map::load_map("examples/office/map.yaml");
    if (!m) throw std::runtime_error(m.error().message);
    auto p = Places::load("examples/office/places.yaml", *m);
    if (!p) throw std::runtime_error(p.error().message);
    return Office{*m, *p, {}};
  }();
  return o;
}

inline CommandContext office_context() {
  return {&office().places, *TimeZone::named("Europe/London"), *parse_time("2026-11-23T10:00:00Z")};
}

}  // namespace rondo::lang::test
