#include "commands.h"

namespace rondo::app {

void add_map_commands(CLI::App& root, CommandContext& ctx) {
  (void)root;
  (void)ctx;
}

}  // namespace rondo::app
