// Builds a Document's tree from JSON text with nlohmann's parser, checking as it reads what that
// parser lets through on its own: nesting deeper than Document::kMaxDepth, more than
// Document::kMaxValues values, and a key given twice in one object (nlohmann keeps the last value
// without a word; YAML's reader refuses a duplicate key, and this refuses it the same way).
#pragma once

#include <string>
#include <string_view>

#include "rondo/core/document.h"

namespace rondo::detail {

// The JSON value of `text`. Errors are kInvalidInput and start with "source: ", or for a duplicate
// key with "source:line: path: " (the line of the second occurrence).
Result<Json> json_to_tree(std::string_view text, const std::string& source);

}  // namespace rondo::detail
