// libFuzzer target: parse_strands_json on arbitrary bytes. See map_fuzz_checks.h for what is checked.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "map_fuzz_checks.h"
#include "rondo/map/strands_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);  // NOLINT
  rondo::map::fuzz::check_parse_result(rondo::map::parse_strands_json(text, "fuzz-input"));
  return 0;
}
