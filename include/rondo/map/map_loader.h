// One entry point to read a map file in any supported format, and to save one in rondo's format.
//
//   Result<TopoMap> map = load_map("../shared/data/maps/tsc_1605.yaml");
//   Result<LoadedMap> file = load_map_file("g4s_y2.tmap");   // also says which format it was
//   Result<TopoMap> lcas = load_map("riseholme.tmap2");          // LCAS topological_navigation
//   Status s = save_map(*map, "office.yaml");
//
// `.tmap` is STRANDS text. The other forms are told apart by content, not by name: a `.yaml`,
// `.yml`, `.tmap2` or `.json` file is an LCAS tmap2 map when is_tmap2_document() says so (`nodes`
// of `{meta, node}` entries, or tmap2's top-level keys), else rondo's format when the top level is
// a mapping with `rondo_map` or `nodes`, else STRANDS YAML (or JSON, for `.json`). A `.tmap2` file
// that is none of these is judged as tmap2, so that its error says what tmap2 needs. Any other
// extension is an error naming the supported ones.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/map/topo_map.h"

namespace rondo::map {

enum class MapFormat { kRondo, kStrandsTmap, kStrandsYaml, kStrandsJson, kTmap2 };

// "rondo", "strands-tmap", "strands-yaml", "strands-json", "tmap2".
const char* to_string(MapFormat format);

struct LoadedMap {
  TopoMap map;
  MapFormat format = MapFormat::kRondo;
  // What the file says that rondo reads but does not apply (tmap2 restrictions), and what its
  // format cannot say (node capacity, narrow edges: every tmap2 and STRANDS map), one sentence
  // each; the commands print them as warnings. Empty for rondo's format.
  std::vector<std::string> import_warnings{};
};

Result<LoadedMap> load_map_file(const std::filesystem::path& file);
Result<TopoMap> load_map(const std::filesystem::path& file);

// Writes the map in rondo's format (write_map_yaml). The file is written next to its final place
// and renamed over it, so a reader never sees half a map. kIo naming the file on failure.
Status save_map(const TopoMap& map, const std::filesystem::path& file);

}  // namespace rondo::map
