// libFuzzer target: request files (src/sim/request_decode.cpp) against the G4S example map; what
// decodes must also generate a day of requests.
#include "fuzz_support.h"
#include "rondo/core/document.h"
#include "rondo/core/timezone.h"
#include "rondo/map/map_loader.h"
#include "rondo/sim/request_generator.h"
#include "rondo/sim/rng.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const rondo::map::TopoMap map = [] {
    auto m = rondo::map::load_map(RONDO_SOURCE_DIR "/examples/g4s/map.yaml");
    if (!m) rondo::fuzz::broken("cannot load the example map", m.error().message);
    return *m;
  }();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto doc = rondo::Document::parse(text, rondo::DocumentFormat::kYaml, "requests.yaml");
  if (!doc) return rondo::fuzz::check_error(doc.error()), 0;
  auto gen = rondo::sim::RequestGenerator::decode(*doc, map, rondo::TimeZone::utc());
  if (!gen) return rondo::fuzz::check_error(gen.error()), 0;
  rondo::sim::Rng rng(1);
  const rondo::Time day = rondo::Time{} + std::chrono::hours(24 * 20000);
  (void)gen->between(day, day + std::chrono::hours(24), rng);
  return 0;
}
