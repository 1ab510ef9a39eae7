// The `rondo` command line as a library call, so tests can run it in-process.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace rondo::app {

// Runs `rondo <args...>` and returns its exit code. Never throws: an unexpected exception is
// reported on `err` as an internal error with exit code 1.
// Out of memory (std::bad_alloc) is reported the same way.
int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// `run` without the guard: exceptions pass through.
int run_commands(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// Runs `body` and returns its exit code; any exception, std::bad_alloc included, is reported on
// `err` with exit code 1 instead of escaping.
int run_guarded(const std::function<int()>& body, std::ostream& err);

// Makes an exception that escapes any thread (or std::terminate for any other reason) print
// "rondo: internal error: ..." and exit with code 1, instead of aborting. main() calls it.
void install_terminate_handler();

}  // namespace rondo::app
