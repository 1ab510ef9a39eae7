// The checks both task-file fuzz targets make: any input gives a value or an Error, never a crash
// or a hang; what decodes survives encode -> YAML -> decode unchanged; routine instances validate.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "rondo/core/task_codec.h"

namespace rondo::fuzz {

inline void check_task_file(const std::uint8_t* data, std::size_t size, DocumentFormat format) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto file = parse_task_file(text, format, "fuzz");
  if (!file) return;
  auto again = parse_task_file(to_yaml(encode(*file)), DocumentFormat::kYaml, "again");
  if (!again || again->tasks != file->tasks || again->routines != file->routines) std::abort();
  if (!file->zone) return;
  for (const auto& r : file->routines) {
    for (unsigned d = 0; d < 3; ++d) {  // across the spring daylight-saving change in Europe
      const auto day = std::chrono::year{2026} / std::chrono::March / std::chrono::day{28 + d};
      for (const auto& t : instances_on(r, day, *file->zone)) {
        if (!validate(t)) std::abort();
      }
    }
  }
}

}  // namespace rondo::fuzz
