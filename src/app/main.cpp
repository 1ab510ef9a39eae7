// The `rondo` binary: all of it lives in cli.cpp and the libraries.
#include <iostream>
#include <string>
#include <vector>

#include "cli.h"

int main(int argc, char** argv) {
  rondo::app::install_terminate_handler();
  std::vector<std::string> args(argv + 1, argv + argc);
  return rondo::app::run(args, std::cout, std::cerr);
}
