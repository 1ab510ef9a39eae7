// libFuzzer target: deployment files (src/app/deployment.cpp), read from a scratch file.
#include "deployment.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = rondo::fuzz::scratch_file("deployment.yaml", data, size);
  auto d = rondo::app::load_deployment(file);
  if (!d) rondo::fuzz::check_error(d.error());
  return 0;
}
