// Durations in the executor's reasons: "4 min 10 s", rounded to the second.
#pragma once

#include <chrono>
#include <string>

#include "rondo/core/time.h"

namespace rondo::exec {

inline std::string duration_text(Duration d) { return format_duration(std::chrono::round<std::chrono::seconds>(d)); }

}  // namespace rondo::exec
