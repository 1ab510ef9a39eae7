// Offline and online comparison of edge models on a real traversal log (what `rondo eval edges`
// prints) and of binary models on any binary time series (`rondo eval binary`).
//
//   auto log = read_witham_logs("../shared/data/witham_wharf");
//   auto result = evaluate_edges(*log, {.split = *parse_time("2014-09-02T16:24:00Z")});
//   std::cout << evaluation_to_json(*result).dump(2);
//
// Protocols. offline: each model is fitted on the attempts that start before the split and
// predicts every later attempt without updates. online: the same models keep learning: before an
// attempt they have seen every attempt (on any edge) that ended before it started. Start times in
// the logs are whole seconds (truncated), so an attempt counts as ended before a start s when its
// end is earlier than s + 1 s.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/core/traversal.h"
#include "rondo/learn/episode_model.h"
#include "rondo/learn/temporal_model.h"

namespace rondo::learn {

struct EdgeEvalOptions {
  Time split;
  // Attempts that start at or after this are ignored (training and test): evaluates a validation
  // split inside a training period without looking past it.
  std::optional<Time> until = std::nullopt;
  int min_train_attempts = 20;  // an edge is scored only with this many attempts before the split
  int min_test_attempts = 5;    // ... and this many at or after it (and before `until`)
  Duration start_resolution = seconds(1);
  // Our models' options; among them the deployment's time zone (Witham Wharf: Europe/London).
  EpisodeOptions episode{};
};

struct ModelScoreRow {
  std::string name;      // "static", "fremen-2", "rhythm", ...
  std::string protocol;  // "offline" | "online"
  bool train_dedup = false;
  double brier = 0;
  double binary_error = 0;
  // Durations of all scored attempts (failed ones included: their time is spent too). MAE of the
  // median forecast (the point MAE rewards), RMSE of the expected value, pinball loss of the
  // 0.9-quantile; duration_mae_of_mean is the MAE of the expected value.
  std::optional<double> duration_mae, duration_mae_of_mean, duration_rmse, duration_pinball_90;
};

struct EdgeEvaluation {
  int edges = 0;
  int test_attempts = 0;
  std::vector<std::string> edge_ids;
  std::vector<ModelScoreRow> models;
};

// Scores every model on the edges that pass the filter. An error if no edge passes.
Result<EdgeEvaluation> evaluate_edges(const std::vector<Traversal>& log, const EdgeEvalOptions& options);

struct BinaryEvaluation {
  int train_samples = 0;
  int test_samples = 0;
  std::vector<ModelScoreRow> models;  // brier and binary_error; rmse = sqrt(brier)
};

// The same comparison for one binary series (door states, occupancy); samples in time order. The
// online protocol reveals each test sample right after it has been predicted.
Result<BinaryEvaluation> evaluate_binary_series(const std::vector<BinarySample>& train,
                                                const std::vector<BinarySample>& test);
// The same with our models fitted with `episode` (e.g. the series' time zone).
Result<BinaryEvaluation> evaluate_binary_series(const std::vector<BinarySample>& train,
                                                const std::vector<BinarySample>& test, const EpisodeOptions& episode);

Json evaluation_to_json(const EdgeEvaluation& e);
Json evaluation_to_json(const BinaryEvaluation& e);
// Human tables, one row per model and protocol.
std::string evaluation_to_table(const EdgeEvaluation& e);
std::string evaluation_to_table(const BinaryEvaluation& e);

// Reads `unix_time state` lines (state 0 or 1; '#' comments and blank lines skipped), sorted by
// time. An error names the file and the line.
Result<std::vector<BinarySample>> read_binary_series(const std::filesystem::path& file);

}  // namespace rondo::learn
