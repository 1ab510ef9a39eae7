// Builds a Document's JSON tree straight from yaml-cpp's parse events, bounding the work before it
// is done: every value, including each one an alias repeats, is counted as it is added, so an
// alias bomb ("billion laughs") is refused after Document::kMaxValues values instead of expanding
// into gigabytes. Aliases are also bounded in number and in how deep they nest inside anchors.
#pragma once

#include <map>
#include <string>
#include <string_view>

#include "rondo/core/document.h"

namespace rondo::detail {

// The first document of `text` as JSON; `lines` gets the 1-based line of each value's path.
// Errors are kInvalidInput and start with "source:line: ".
Result<Json> yaml_to_json(std::string_view text, const std::string& source, std::map<std::string, int>& lines);

// YAML 1.2 core schema for plain (unquoted) scalars: null, booleans, integers, floats, else text.
Json plain_scalar(const std::string& s);

}  // namespace rondo::detail
