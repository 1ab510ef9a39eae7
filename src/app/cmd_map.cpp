// `rondo map info|check|convert`: inspect, validate and convert topological maps.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>

#include "commands.h"
#include "rondo/core/utf8.h"
#include "rondo/map/map_loader.h"
#include "rondo/map/map_summary.h"
#include "rondo/map/map_validation.h"
#include "rondo/map/map_yaml.h"

namespace rondo::app {
namespace {

// Map files may carry names that are not UTF-8 (old .tmap files): replace such bytes, never throw.
std::string dump_json(const Json& j) {
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

void print_warnings(CommandContext& ctx, const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) ctx.err << "rondo: warning: " << w << '\n';
}

// Node capacities and narrow edges: "2 nodes hold more than one robot (up to 3); 4 narrow edges (2
// single, 2 one-way)".
std::string traffic_text(const map::MapSummary& s) {
  std::string text = s.nodes_with_capacity == 0
                         ? std::string("every node holds one robot")
                         : fmt::format("{} node{} hold{} more than one robot (up to {})", s.nodes_with_capacity,
                                       s.nodes_with_capacity == 1 ? "" : "s", s.nodes_with_capacity == 1 ? "s" : "",
                                       s.largest_capacity);
  const std::size_t narrow = s.narrow_single + s.narrow_one_way;
  if (narrow == 0) return text + "; no narrow edges";
  return text + fmt::format("; {} narrow edge{} ({} single, {} one-way)", narrow, narrow == 1 ? "" : "s",
                            s.narrow_single, s.narrow_one_way);
}

void print_table(CommandContext& ctx, const std::string& file, const map::LoadedMap& loaded, const map::MapSummary& s) {
  auto row = [&](std::string_view label, const std::string& value) {
    ctx.out << fmt::format("{:<11}{}\n", label, value);
  };
  row("map", fmt::format("{} ({}, {})", s.name.empty() ? "(no name)" : s.name, to_string(loaded.format), file));
  row("nodes", fmt::format("{} ({} with an influence polygon)", s.nodes, s.nodes_with_influence));
  std::string edges =
      fmt::format("{} ({} with a top speed), {:.1f} m in total", s.edges, s.edges_with_top_speed, s.total_edge_length);
  if (!s.longest_edge.empty()) edges += fmt::format(", longest {} ({:.1f} m)", s.longest_edge, s.longest_edge_length);
  row("edges", edges);
  if (s.bounding_box) {
    const auto& b = *s.bounding_box;
    row("extent", fmt::format("x {:.2f} .. {:.2f} m, y {:.2f} .. {:.2f} m ({:.1f} x {:.1f} m)", b.min_x, b.max_x,
                              b.min_y, b.max_y, b.max_x - b.min_x, b.max_y - b.min_y));
  }
  row("traffic", traffic_text(s));
  row("travel",
      fmt::format("{:.0f} s to cross every edge once at the no-data speed prior", s.nominal_travel_time_total));
  row("connected", s.strongly_connected_components <= 1
                       ? std::string("yes: every node can reach every other")
                       : fmt::format("no: {} strongly connected groups", s.strongly_connected_components));
  std::size_t width = 0;
  for (const auto& [action, count] : s.actions) width = std::max(width, action.size());
  bool first = true;
  for (const auto& [action, count] : s.actions) {
    row(first ? "actions" : "", fmt::format("{:<{}}  {}", action, width, count));
    first = false;
  }
  if (s.doors.empty()) row("doors", "none");
  first = true;
  for (const auto& door : s.doors) {
    row(first ? "doors" : "", fmt::format("{} ({})", door.id, fmt::join(door.edges, ", ")));
    first = false;
  }
  std::vector<std::string> warnings = loaded.import_warnings;
  warnings.insert(warnings.end(), s.warnings.begin(), s.warnings.end());
  if (warnings.empty()) row("warnings", "none");
  first = true;
  for (const auto& w : warnings) {
    row(first ? "warnings" : "", w);
    first = false;
  }
}

void add_info(CLI::App& group, CommandContext& ctx) {
  struct Options {
    std::string file;
    bool json = false;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = group.add_subcommand("info", "Summarise a map: sizes, actions, doors, extent, connectivity");
  cmd->add_option("file", opts->file, "Map file: rondo .yaml, LCAS .tmap2, STRANDS .tmap, .yaml or .json")->required();
  cmd->add_flag("--json", opts->json, "Print JSON instead of a table");
  cmd->callback([&ctx, opts] {
    auto loaded = map::load_map_file(opts->file);
    if (!loaded) {
      fail(ctx, loaded.error());
      return;
    }
    const map::MapSummary summary = map::summarize(loaded->map);
    if (opts->json) {
      Json j = Json::object();
      j["file"] = opts->file;
      j["format"] = to_string(loaded->format);
      const Json fields = map::to_json(summary);
      for (auto it = fields.begin(); it != fields.end(); ++it) j[it.key()] = it.value();
      j["import_warnings"] = loaded->import_warnings;
      ctx.out << dump_json(j);
    } else {
      print_table(ctx, opts->file, *loaded, summary);
    }
  });
}

void add_check(CLI::App& group, CommandContext& ctx) {
  auto file = std::make_shared<std::string>();
  CLI::App* cmd = group.add_subcommand(
      "check", "Validate a map; prints warnings (such as unreachable nodes). Exit 0 if valid, 2 if not");
  cmd->add_option("file", *file, "Map file: rondo .yaml, LCAS .tmap2, STRANDS .tmap, .yaml or .json")->required();
  cmd->callback([&ctx, file] {
    auto loaded = map::load_map_file(*file);
    if (!loaded) {
      fail(ctx, loaded.error());
      return;
    }
    auto warnings = loaded->import_warnings;
    for (std::string& w : map::map_warnings(loaded->map)) warnings.push_back(std::move(w));
    print_warnings(ctx, warnings);
    ctx.out << fmt::format("{}: valid {} map, {} nodes, {} edges, {} warning{}\n", *file, to_string(loaded->format),
                           loaded->map.node_count(), loaded->map.edge_count(), warnings.size(),
                           warnings.size() == 1 ? "" : "s");
  });
}

void add_convert(CLI::App& group, CommandContext& ctx) {
  struct Options {
    std::string file;
    std::string output;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = group.add_subcommand("convert", "Convert a map to rondo's YAML format (docs/map-format.md)");
  cmd->add_option("file", opts->file, "Map file: rondo .yaml, LCAS .tmap2, STRANDS .tmap, .yaml or .json")->required();
  cmd->add_option("-o,--output", opts->output, "Where to write the rondo .yaml ('-' for standard output)")->required();
  cmd->callback([&ctx, opts] {
    // The output name says the format; rondo writes only its own, so refuse any other name
    // before reading anything (a .json or .tmap name would otherwise get YAML inside).
    const std::string ext = std::filesystem::path(opts->output).extension().string();
    if (opts->output != "-" && ext != ".yaml" && ext != ".yml") {
      fail(ctx, Error::invalid(fmt::format(
                    "-o {}: map convert writes rondo's YAML map format only: give a .yaml or .yml name, or '-'",
                    printable_path(opts->output))));
      return;
    }
    auto loaded = map::load_map_file(opts->file);
    if (!loaded) {
      fail(ctx, loaded.error());
      return;
    }
    print_warnings(ctx, loaded->import_warnings);
    print_warnings(ctx, map::map_warnings(loaded->map));
    const std::string text = map::write_map_yaml(loaded->map);
    // The written file must read back as the same map; anything else is a bug in the writer.
    auto again = map::parse_map_yaml(text, opts->output);
    if (!again || !(*again == loaded->map)) {
      fail(ctx, Error::internal(fmt::format("{}: the converted map does not read back the same{}", opts->file,
                                            again ? "" : ": " + again.error().message)));
      return;
    }
    if (opts->output == "-") {
      ctx.out << text;
      return;
    }
    if (auto s = map::save_map(loaded->map, opts->output); !s) {
      fail(ctx, s.error());
      return;
    }
    ctx.out << fmt::format("wrote {}: {} nodes, {} edges (from {} {})\n", opts->output, loaded->map.node_count(),
                           loaded->map.edge_count(), to_string(loaded->format), opts->file);
  });
}

}  // namespace

void add_map_commands(CLI::App& root, CommandContext& ctx) {
  CLI::App* group = root.add_subcommand(
      "map", "Topological maps: inspect, check and convert (rondo YAML; LCAS tmap2; STRANDS .tmap, YAML and JSON)");
  group->require_subcommand(1);
  add_info(*group, ctx);
  add_check(*group, ctx);
  add_convert(*group, ctx);
}

}  // namespace rondo::app
