// libFuzzer target: parse_tmap2 (LCAS topological_navigation) on arbitrary bytes. Beyond
// map_fuzz_checks.h, every import warning is a non-empty sentence of bounded length.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "map_fuzz_checks.h"
#include "rondo/map/tmap2_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);  // NOLINT
  auto in = rondo::map::parse_tmap2(text, "fuzz-input");
  if (!in) {
    rondo::map::fuzz::check_parse_result(in.error());
    return 0;
  }
  if (in->warnings.size() > 11) rondo::map::fuzz::fail("more than 11 import warnings", "");
  for (const std::string& w : in->warnings) {
    if (w.empty() || w.size() > 400) rondo::map::fuzz::fail("import warning empty or unbounded", w);
  }
  rondo::map::fuzz::check_parse_result(std::move(in->map));
  return 0;
}
