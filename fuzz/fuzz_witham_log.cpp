// libFuzzer target: one Witham Wharf edge log (src/core/witham_log.cpp), from a scratch file.
#include "fuzz_support.h"
#include "rondo/core/traversal.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = rondo::fuzz::scratch_file("WayPoint1_WayPoint2.data", data, size);
  auto log = rondo::read_witham_edge_log(file);
  if (!log) rondo::fuzz::check_error(log.error());
  return 0;
}
