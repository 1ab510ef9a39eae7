// `rondo learn`: fit the navigation models of every edge from the traversal log and save them.
// With --map, the edges are the map's, each with its distance-based prior time (so an edge the log
// never names still gets a sane model); without it, the edges the log names, without a prior.
#include <fmt/format.h>

#include <memory>
#include <optional>
#include <set>

#include "commands.h"
#include "rondo/core/timezone.h"
#include "rondo/core/utf8.h"
#include "rondo/learn/edge_models.h"
#include "rondo/map/map_loader.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/store/store.h"
#include "rondo/store/traversal_log.h"

namespace rondo::app {
namespace {

struct LearnArgs {
  std::string db;
  std::string map;
  std::string zone = "UTC";
  std::string output;
  bool json = false;
};

// The map's edges (id + map::nominal_travel_time), or nothing without --map.
Result<std::optional<std::vector<learn::EdgeSpec>>> map_edges(const LearnArgs& args) {
  if (args.map.empty()) return std::optional<std::vector<learn::EdgeSpec>>{};
  auto map = map::load_map(args.map);
  if (!map) return map.error().with_context("--map");
  return std::optional<std::vector<learn::EdgeSpec>>{plan::edge_specs(*map)};
}

// Without a map: the edge ids the log names, without a prior.
std::vector<learn::EdgeSpec> logged_edges(const std::vector<Traversal>& log) {
  std::set<std::string> ids;
  for (const auto& t : log) ids.insert(t.edge_id);
  std::vector<learn::EdgeSpec> edges;
  for (const auto& id : ids) edges.push_back({id, 0.0});
  return edges;
}

void print_summary(const LearnArgs& args, const learn::EdgeModels& models, std::size_t traversals,
                   std::size_t unmatched, CommandContext& ctx) {
  std::size_t own = 0;
  for (std::size_t e = 0; e < models.size(); ++e)
    if (models.has_own_model(e)) ++own;
  if (args.json) {
    ctx.out << Json{{"edges", models.size()},   {"edges_with_own_model", own},
                    {"traversals", traversals}, {"traversals_of_unknown_edges", unmatched},
                    {"time_zone", args.zone},   {"output", printable_path(args.output)}}
                   .dump(2)
            << '\n';
    return;
  }
  ctx.out << fmt::format("fitted {} edges ({} with enough data of their own) from {} traversals: {}\n", models.size(),
                         own, traversals - unmatched, args.output);
  if (unmatched > 0) ctx.out << fmt::format("ignored {} traversals of edges the map does not have\n", unmatched);
}

void run_learn(const LearnArgs& args, CommandContext& ctx) {
  auto zone = TimeZone::named(args.zone);
  if (!zone) return (void)fail(ctx, zone.error().with_context("--zone"));
  auto from_map = map_edges(args);
  if (!from_map) return (void)fail(ctx, from_map.error());
  auto db = store::Store::open_named(args.db, {.mode = store::OpenMode::kReadOnly});
  if (!db) return (void)fail(ctx, db.error());
  auto log = store::find_traversals(*db);
  if (!log) return (void)fail(ctx, log.error());
  const auto edges = from_map->has_value() ? **from_map : logged_edges(*log);
  learn::EdgeModelsOptions options;
  options.episode.zone = *zone;
  auto models = learn::EdgeModels::fit(edges, *log, options);
  if (!models) return (void)fail(ctx, models.error());
  if (auto saved = (*models)->save(args.output); !saved) return (void)fail(ctx, saved.error());
  std::size_t unmatched = 0;
  for (const auto& t : *log)
    if (!(*models)->index_of(t.edge_id)) ++unmatched;
  print_summary(args, **models, log->size(), unmatched, ctx);
}

}  // namespace

void add_learn_commands(CLI::App& root, CommandContext& ctx) {
  auto args = std::make_shared<LearnArgs>();
  auto* learn = root.add_subcommand("learn", "Fit the edge success and travel-time models from the traversal log");
  learn->add_option("--db", args->db, "The store: an SQLite file or a postgresql:// URL")->required();
  learn->add_option("--map", args->map,
                    "The map whose edges to model (with distance priors); default: the edges the log names");
  learn->add_option("--zone", args->zone, "IANA time zone of the deployment (time-of-day bins)")->capture_default_str();
  learn->add_option("-o,--output", args->output, "Where to write the models (JSON)")->required();
  learn->add_flag("--json", args->json, "Print the summary as JSON");
  learn->callback([args, &ctx] { run_learn(*args, ctx); });
}

}  // namespace rondo::app
