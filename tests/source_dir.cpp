#include "source_dir.h"

namespace rondo::testing {

const std::filesystem::path& source_dir() {
  static const std::filesystem::path dir(RONDO_SOURCE_DIR);
  return dir;
}

}  // namespace rondo::testing
