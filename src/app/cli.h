// The `rondo` command line as a library call, so tests can run it in-process.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace rondo::app {

// Runs `rondo <args...>` and returns its exit code. Never throws: an unexpected exception is
// reported on `err` as an internal error with exit code 1.
int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace rondo::app
