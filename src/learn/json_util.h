// Small readers for the model JSON documents: each error names the member that is wrong.
#pragma once

#include <string>

#include "rondo/core/document.h"
#include "rondo/core/result.h"

namespace rondo::learn {

// The finite number `j[key]`; an invalid-input error naming `key` otherwise.
Result<double> json_number(const Json& j, const char* key);
// The array of finite numbers `j[key]`.
Result<std::vector<double>> json_numbers(const Json& j, const char* key);

}  // namespace rondo::learn
