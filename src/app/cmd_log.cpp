#include "commands.h"

namespace rondo::app {

void add_log_commands(CLI::App& root, CommandContext& ctx) {
  (void)root;
  (void)ctx;
}

}  // namespace rondo::app
