// libFuzzer target: the TSPTW instance reader (src/schedule/tsptw.cpp). A parsed instance must
// validate; the reader must never allocate more than the text can fill.
#include "fuzz_support.h"
#include "rondo/schedule/problem.h"
#include "rondo/schedule/tsptw.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto p = rondo::schedule::parse_tsptw(text, "fuzz.tsptw");
  if (!p) return rondo::fuzz::check_error(p.error()), 0;
  if (auto ok = rondo::schedule::validate(*p); !ok)
    rondo::fuzz::broken("a parsed instance fails validate", ok.error().message);
  return 0;
}
