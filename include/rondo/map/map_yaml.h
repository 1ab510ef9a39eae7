// rondo's own map file format (docs/map-format.md): read and write.
//
//   Result<TopoMap> map = parse_map_yaml(text, "office.yaml");
//   std::string text = write_map_yaml(*map);        // parse_map_yaml(text) == *map
//
// Reading is strict: unknown fields, wrong types and broken references are errors that name the
// file, the line and the field path ("office.yaml:14: edges[2].to: no node named 'Lab'").
#pragma once

#include <string>
#include <string_view>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/map/topo_map.h"

namespace rondo::map {

// The format version this build reads and writes (the `rondo_map` field).
inline constexpr int kMapFormatVersion = 1;

// Parses a map in rondo's format; `source` names the text in error messages (usually the path).
Result<TopoMap> parse_map_yaml(std::string_view text, const std::string& source);

// Decodes an already parsed document (YAML or JSON) in rondo's format.
Result<TopoMap> map_from_document(const Document& doc);

// Whether a parsed document looks like rondo's format: a mapping with `rondo_map` or `nodes`.
bool is_rondo_map_document(const Document& doc);

// The map as the JSON value of rondo's format (what write_map_yaml prints as YAML).
Json map_to_json(const TopoMap& map);

// The map in rondo's format, with a comment line naming the format. Round-trips exactly.
std::string write_map_yaml(const TopoMap& map);

}  // namespace rondo::map
