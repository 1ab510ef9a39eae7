// One entry point to read a map file in any supported format, and to save one in rondo's format.
//
//   Result<TopoMap> map = load_map("../shared/data/maps/tsc_1605.yaml");
//   Result<LoadedMap> file = load_map_file("g4s_y2.tmap");   // also says which format it was
//   Status s = save_map(*map, "office.yaml");
//
// The format comes from the extension: `.tmap` is STRANDS text, `.json` is STRANDS JSON (or rondo's
// format written as JSON, if it has rondo's top-level keys), `.yaml`/`.yml` is rondo's format when
// the top level is a mapping with `rondo_map` or `nodes`, else STRANDS YAML. Any other extension is
// an error naming the supported ones.
#pragma once

#include <filesystem>

#include "rondo/core/result.h"
#include "rondo/map/topo_map.h"

namespace rondo::map {

enum class MapFormat { kRondo, kStrandsTmap, kStrandsYaml, kStrandsJson };

// "rondo", "strands-tmap", "strands-yaml", "strands-json".
const char* to_string(MapFormat format);

struct LoadedMap {
  TopoMap map;
  MapFormat format = MapFormat::kRondo;
};

Result<LoadedMap> load_map_file(const std::filesystem::path& file);
Result<TopoMap> load_map(const std::filesystem::path& file);

// Writes the map in rondo's format (write_map_yaml). The file is written next to its final place
// and renamed over it, so a reader never sees half a map. kIo naming the file on failure.
Status save_map(const TopoMap& map, const std::filesystem::path& file);

}  // namespace rondo::map
