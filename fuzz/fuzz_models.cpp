// libFuzzer target: the models file that `rondo learn` writes (src/learn/edge_models.cpp); what
// loads must be written again as JSON text.
#include "fuzz_support.h"
#include "rondo/learn/edge_models.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = rondo::fuzz::scratch_file("models.json", data, size);
  auto models = rondo::learn::EdgeModels::load(file);
  if (!models) return rondo::fuzz::check_error(models.error()), 0;
  (void)(*models)->to_json().dump();
  return 0;
}
