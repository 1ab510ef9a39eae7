// libFuzzer target: the 'unix_time state' series of `rondo eval binary` (src/learn/evaluation.cpp).
#include "fuzz_support.h"
#include "rondo/learn/evaluation.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = rondo::fuzz::scratch_file("series.txt", data, size);
  auto series = rondo::learn::read_binary_series(file);
  if (!series) rondo::fuzz::check_error(series.error());
  return 0;
}
