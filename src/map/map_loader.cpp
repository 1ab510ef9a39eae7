#include "rondo/map/map_loader.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "rondo/core/atomic_file.h"
#include "rondo/core/document.h"
#include "rondo/map/map_yaml.h"
#include "rondo/map/strands_import.h"
#include "rondo/map/tmap2_import.h"

namespace rondo::map {

namespace {

// What an imported map cannot say: its format has no field for traffic (tmap2's restrictions choose
// robots and tasks, not how many at once).
std::string no_traffic_warning(MapFormat format) {
  return fmt::format(
      "{} maps have no node capacity and no narrow edges: every node holds one robot and robots pass each other on "
      "every edge (a converted map may add capacity and narrow: docs/map-format.md)",
      format == MapFormat::kTmap2 ? "tmap2" : "STRANDS");
}

}  // namespace

const char* to_string(MapFormat format) {
  switch (format) {
    case MapFormat::kRondo:
      return "rondo";
    case MapFormat::kStrandsTmap:
      return "strands-tmap";
    case MapFormat::kStrandsYaml:
      return "strands-yaml";
    case MapFormat::kStrandsJson:
      return "strands-json";
    case MapFormat::kTmap2:
      return "tmap2";
  }
  return "unknown";
}

Result<LoadedMap> load_map_file(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  const bool is_tmap = ext == ".tmap";
  const bool is_json = ext == ".json";
  const bool is_yaml = ext == ".yaml" || ext == ".yml" || ext == ".tmap2";
  if (!is_tmap && !is_json && !is_yaml) {
    return Error::invalid(fmt::format(
        "{}: unknown map file type '{}': expected .yaml, .yml or .tmap2 (rondo, LCAS tmap2 or STRANDS YAML), "
        ".tmap or .json (STRANDS)",
        file.string(), ext));
  }
  auto text = read_text_file(file, Document::kMaxBytes);
  if (!text) return text.error();
  if (is_tmap) {
    auto map = parse_strands_tmap(*text, file.string());
    if (!map) return map.error();
    return LoadedMap{std::move(*map), MapFormat::kStrandsTmap, {no_traffic_warning(MapFormat::kStrandsTmap)}};
  }
  auto doc = Document::parse(*text, is_json ? DocumentFormat::kJson : DocumentFormat::kYaml, file.string());
  if (!doc) return doc.error();
  // A .tmap2 file that is no other form either is judged as the tmap2 it claims to be.
  const bool claims_tmap2 = ext == ".tmap2" && !doc->root().is_array() && !is_rondo_map_document(*doc);
  if (claims_tmap2 || is_tmap2_document(*doc)) {
    auto in = tmap2_map_from_document(*doc);
    if (!in) return in.error();
    in->warnings.push_back(no_traffic_warning(MapFormat::kTmap2));
    return LoadedMap{std::move(in->map), MapFormat::kTmap2, std::move(in->warnings)};
  }
  if (is_rondo_map_document(*doc)) {
    auto map = map_from_document(*doc);
    if (!map) return map.error();
    return LoadedMap{std::move(*map), MapFormat::kRondo};
  }
  auto map = strands_map_from_document(*doc);
  if (!map) return map.error();
  const MapFormat format = is_json ? MapFormat::kStrandsJson : MapFormat::kStrandsYaml;
  return LoadedMap{std::move(*map), format, {no_traffic_warning(format)}};
}

Result<TopoMap> load_map(const std::filesystem::path& file) {
  auto loaded = load_map_file(file);
  if (!loaded) return loaded.error();
  return std::move(loaded->map);
}

Status save_map(const TopoMap& map, const std::filesystem::path& file) {
  return write_file_atomically(file, write_map_yaml(map));
}

}  // namespace rondo::map
