// libFuzzer target: task/routine files in YAML. Any input must give a value or an Error, never a
// crash or a hang; and what decodes must survive encode -> YAML -> decode unchanged.
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "rondo/core/task_codec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto file = rondo::parse_task_file(text, rondo::DocumentFormat::kYaml, "fuzz");
  if (!file) return 0;
  auto again = rondo::parse_task_file(rondo::to_yaml(rondo::encode(*file)), rondo::DocumentFormat::kYaml, "again");
  if (!again || again->tasks != file->tasks || again->routines != file->routines) std::abort();
  if (file->zone) {
    for (const auto& r : file->routines) {
      for (unsigned d = 0; d < 3; ++d) {
        const auto day = std::chrono::year{2026} / std::chrono::March / std::chrono::day{28 + d};
        for (const auto& t : rondo::instances_on(r, day, *file->zone)) {
          if (!rondo::validate(t)) std::abort();
        }
      }
    }
  }
  return 0;
}
