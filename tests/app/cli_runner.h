// Runs the `rondo` command line in-process and captures what it prints.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "cli.h"

namespace rondo::test {

struct CliResult {
  int exit_code;
  std::string out;
  std::string err;
};

inline CliResult run_cli(const std::vector<std::string>& args) {
  std::ostringstream out;
  std::ostringstream err;
  const int code = rondo::app::run(args, out, err);
  return {code, out.str(), err.str()};
}

}  // namespace rondo::test
