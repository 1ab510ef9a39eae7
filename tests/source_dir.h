// Where this project's sources are, for the tests that read its fixtures, examples and the shared
// data beside it. The path is compiled into tests/source_dir.cpp alone, so that every other test
// object is the same in any clone, and a compiler cache shared by clones at other paths (CI's
// fresh clone) hits on them.
#pragma once

#include <filesystem>

namespace rondo::testing {

const std::filesystem::path& source_dir();

}  // namespace rondo::testing
