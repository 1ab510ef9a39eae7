// libFuzzer target: task/routine files in JSON; see task_file_checks.h for what is checked.
#include "task_file_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rondo::fuzz::check_task_file(data, size, rondo::DocumentFormat::kJson);
  return 0;
}
