// libFuzzer target: simulated-world files (src/sim/world_decode.cpp) against the G4S example map.
// Relative paths (replay logs) resolve in a folder that does not exist.
#include <cstdlib>

#include "fuzz_support.h"
#include "rondo/core/document.h"
#include "rondo/core/timezone.h"
#include "rondo/map/map_loader.h"
#include "rondo/sim/sim_world.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const rondo::map::TopoMap map = [] {
    auto m = rondo::map::load_map(RONDO_SOURCE_DIR "/examples/g4s/map.yaml");
    if (!m) rondo::fuzz::broken("cannot load the example map", m.error().message);
    return *m;
  }();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto doc = rondo::Document::parse(text, rondo::DocumentFormat::kYaml, "world.yaml");
  if (!doc) return rondo::fuzz::check_error(doc.error()), 0;
  auto world = rondo::sim::decode_world(*doc, "/nonexistent-rondo-fuzz", map, rondo::TimeZone::utc());
  if (!world) rondo::fuzz::check_error(world.error());
  return 0;
}
