// `rondo learn`: fit the navigation models of every edge from the traversal log and save them.
#include <fmt/format.h>

#include <memory>
#include <set>

#include "commands.h"
#include "rondo/learn/edge_models.h"
#include "rondo/store/store.h"
#include "rondo/store/traversal_log.h"

namespace rondo::app {
namespace {

struct LearnArgs {
  std::string db;
  std::string map;
  std::string output;
  bool json = false;
};

void run_learn(const LearnArgs& args, CommandContext& ctx) {
  if (!args.map.empty()) {
    // The edge list and distance priors will come from rondo::map once it lands; until then the
    // edges are the ones the log names, without a distance prior.
    return (void)fail(ctx, Error{ErrorCode::kUnsupported,
                                 "--map: reading edges from a map is not wired in yet; "
                                 "run without --map to learn the edges the log names"});
  }
  auto db = store::Store::open(args.db, {.mode = store::OpenMode::kMustExist});
  if (!db) return (void)fail(ctx, db.error());
  auto log = store::find_traversals(*db);
  if (!log) return (void)fail(ctx, log.error());
  std::set<std::string> ids;
  for (const auto& t : *log) ids.insert(t.edge_id);
  std::vector<learn::EdgeSpec> edges;
  for (const auto& id : ids) edges.push_back({id, 0.0});
  auto models = learn::EdgeModels::fit(edges, *log);
  if (!models) return (void)fail(ctx, models.error());
  if (auto saved = (*models)->save(args.output); !saved) return (void)fail(ctx, saved.error());
  std::size_t own = 0;
  for (std::size_t e = 0; e < (*models)->size(); ++e)
    if ((*models)->has_own_model(e)) ++own;
  if (args.json) {
    ctx.out << Json{{"edges", (*models)->size()},
                    {"edges_with_own_model", own},
                    {"traversals", log->size()},
                    {"output", args.output}}
                   .dump(2)
            << '\n';
  } else {
    ctx.out << fmt::format("fitted {} edges ({} with enough data of their own) from {} traversals: {}\n",
                           (*models)->size(), own, log->size(), args.output);
  }
}

}  // namespace

void add_learn_commands(CLI::App& root, CommandContext& ctx) {
  auto args = std::make_shared<LearnArgs>();
  auto* learn = root.add_subcommand("learn", "Fit the edge success and travel-time models from the traversal log");
  learn->add_option("--db", args->db, "The SQLite database file")->required();
  learn->add_option("--map", args->map, "The map whose edges to model (not wired in yet)");
  learn->add_option("-o,--output", args->output, "Where to write the models (JSON)")->required();
  learn->add_flag("--json", args->json, "Print the summary as JSON");
  learn->callback([args, &ctx] { run_learn(*args, ctx); });
}

}  // namespace rondo::app
