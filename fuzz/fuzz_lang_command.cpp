// libFuzzer target: commands in words (rondo::lang::parse_command) on the example office floor.
// Any input gives a Command or an Error, never a crash or a hang; what it accepts passes core's
// checks, names only nodes of the map, and survives encode -> JSON -> decode unchanged.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "rondo/core/task_codec.h"
#include "rondo/lang/command.h"
#include "rondo/map/map_loader.h"

namespace {

struct Floor {
  rondo::map::TopoMap map;
  rondo::lang::Places places;
};

const Floor& floor_plan() {
  static const Floor f = [] {
    auto m = rondo::map::load_map(RONDO_SOURCE_DIR "/examples/office/map.yaml");
    if (!m) std::abort();
    auto p = rondo::lang::Places::load(RONDO_SOURCE_DIR "/examples/office/places.yaml", *m);
    if (!p) std::abort();
    return Floor{*m, *p};
  }();
  return f;
}

void check_node(const std::string& node) {
  if (!node.empty() && !floor_plan().map.find_node(node)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const rondo::lang::CommandContext ctx{&floor_plan().places, *rondo::TimeZone::named("Europe/London"),
                                        *rondo::parse_time("2026-03-29T00:30:00Z")};  // the spring change
  auto command = rondo::lang::parse_command(text, ctx);
  if (!command) {
    if (command.error().code != rondo::ErrorCode::kInvalidInput &&
        command.error().code != rondo::ErrorCode::kNotFound) {
      std::abort();  // bad words are bad input, never an internal error
    }
    return 0;
  }
  if (command->cancel) {
    if (!command->tasks.empty() || !command->routines.empty()) std::abort();
    for (const auto& n : command->cancel->nodes) check_node(n);
    return 0;
  }
  if (command->tasks.empty() == command->routines.empty()) std::abort();  // one or the other
  if (!rondo::validate(command->tasks)) std::abort();
  for (const auto& t : command->tasks) check_node(t.start_node);
  for (const auto& r : command->routines) {
    if (!rondo::validate(r)) std::abort();
    check_node(r.task.start_node);
  }
  rondo::TaskFile file{ctx.zone, command->tasks, command->routines};
  auto again = rondo::parse_task_file(rondo::encode(file).dump(), rondo::DocumentFormat::kJson, "again");
  if (!again || again->tasks != command->tasks || again->routines != command->routines) std::abort();
  return 0;
}
