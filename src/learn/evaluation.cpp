#include "rondo/learn/evaluation.h"

#include <algorithm>
#include <charconv>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "contenders.h"
#include "rondo/core/document.h"
#include "rondo/core/utf8.h"
#include "rondo/learn/metrics.h"

namespace rondo::learn {
namespace {

struct ScoredEdge {
  EdgeHistory history;
  std::vector<Attempt> test;
};

Attempt to_attempt(const Traversal& t) {
  return Attempt{t.start, t.start + t.duration, to_seconds(t.duration), t.success};
}

struct Scores {
  BinaryScore binary;
  DurationScore duration;
};

// Offline: predict every test attempt from the fitted state. Online: before each test attempt,
// observe the test attempts of the same edge that ended before it started (to `resolution`).
void score_edge(EdgePredictor& predictor, const std::vector<Attempt>& test, bool online, Duration resolution,
                Scores& scores) {
  std::vector<const Attempt*> pending;  // started, outcome not yet observed, in end order
  std::size_t next_pending = 0;
  for (const Attempt& a : test) {
    if (online) {
      while (next_pending < pending.size() && pending[next_pending]->end < a.start + resolution) {
        predictor.observe(*pending[next_pending]);
        ++next_pending;
      }
    }
    scores.binary.add(predictor.probability(a.start), a.success);
    scores.duration.add({.expected = predictor.expected_seconds(a.start),
                         .median = predictor.quantile_seconds(a.start, 0.5),
                         .q90 = predictor.quantile_seconds(a.start, DurationScore::kLevel)},
                        a.seconds);
    if (online) {
      // Keep `pending` ordered by end time (attempts on one edge rarely overlap).
      auto it = std::upper_bound(pending.begin() + static_cast<std::ptrdiff_t>(next_pending), pending.end(), &a,
                                 [](const Attempt* x, const Attempt* y) { return x->end < y->end; });
      const auto offset = it - pending.begin();
      pending.insert(pending.begin() + offset, &a);
    }
  }
}

ModelScoreRow make_row(const Contender& c, bool online, const Scores& s, bool with_durations) {
  ModelScoreRow row;
  row.name = c.name();
  row.protocol = online ? "online" : "offline";
  row.train_dedup = c.train_dedup();
  row.brier = s.binary.brier();
  row.binary_error = s.binary.error_rate();
  if (with_durations) {
    row.duration_mae = s.duration.mae();
    row.duration_mae_of_mean = s.duration.mae_of_mean();
    row.duration_rmse = s.duration.rmse();
    row.duration_pinball_90 = s.duration.pinball();
  }
  return row;
}

Json row_json(const ModelScoreRow& r, bool binary_series) {
  Json j{{"name", r.name}, {"protocol", r.protocol}, {"train_dedup", r.train_dedup}};
  if (binary_series) j["rmse"] = std::sqrt(r.brier);
  j["brier"] = r.brier;
  j["binary_error"] = r.binary_error;
  if (r.duration_mae) {
    j["duration_mae"] = *r.duration_mae;
    j["duration_mae_of_mean"] = *r.duration_mae_of_mean;
    j["duration_rmse"] = *r.duration_rmse;
    j["duration_pinball_90"] = *r.duration_pinball_90;
  }
  return j;
}

}  // namespace

Result<EdgeEvaluation> evaluate_edges(const std::vector<Traversal>& log, const EdgeEvalOptions& options) {
  std::map<std::string, ScoredEdge> by_edge;
  for (const Traversal& t : log) {
    if (options.until && t.start >= *options.until) continue;
    auto& e = by_edge[t.edge_id];
    e.history.id = t.edge_id;
    (t.start < options.split ? e.history.train : e.test).push_back(to_attempt(t));
  }
  std::vector<EdgeHistory> histories;
  std::vector<std::vector<Attempt>> tests;
  EdgeEvaluation result;
  for (auto& [id, e] : by_edge) {
    if (static_cast<int>(e.history.train.size()) < options.min_train_attempts ||
        static_cast<int>(e.test.size()) < options.min_test_attempts) {
      continue;
    }
    auto by_start = [](const Attempt& a, const Attempt& b) { return a.start < b.start; };
    std::stable_sort(e.history.train.begin(), e.history.train.end(), by_start);
    std::stable_sort(e.test.begin(), e.test.end(), by_start);
    result.edge_ids.push_back(id);
    result.test_attempts += static_cast<int>(e.test.size());
    histories.push_back(std::move(e.history));
    tests.push_back(std::move(e.test));
  }
  result.edges = static_cast<int>(histories.size());
  if (histories.empty()) {
    return Error::invalid(fmt::format("no edge has at least {} attempts before the split and {} after it",
                                      options.min_train_attempts, options.min_test_attempts));
  }
  for (const auto& contender : all_contenders(options.episode)) {
    for (bool online : {false, true}) {
      auto predictors = contender->fit(histories, online);
      Scores scores;
      for (std::size_t i = 0; i < predictors.size(); ++i) {
        score_edge(*predictors[i], tests[i], online, options.start_resolution, scores);
      }
      result.models.push_back(make_row(*contender, online, scores, true));
    }
  }
  return result;
}

Result<BinaryEvaluation> evaluate_binary_series(const std::vector<BinarySample>& train,
                                                const std::vector<BinarySample>& test) {
  return evaluate_binary_series(train, test, EpisodeOptions{});
}

Result<BinaryEvaluation> evaluate_binary_series(const std::vector<BinarySample>& train,
                                                const std::vector<BinarySample>& test, const EpisodeOptions& episode) {
  if (train.empty()) return Error::invalid("the training series is empty");
  if (test.empty()) return Error::invalid("the test series is empty");
  std::vector<EdgeHistory> histories(1);
  histories[0].id = "series";
  for (const auto& s : train) histories[0].train.push_back({s.time, s.time, 0.0, s.value});
  std::vector<Attempt> test_attempts;
  for (const auto& s : test) test_attempts.push_back({s.time, s.time, 0.0, s.value});
  BinaryEvaluation result;
  result.train_samples = static_cast<int>(train.size());
  result.test_samples = static_cast<int>(test.size());
  for (const auto& contender : all_contenders(episode)) {
    for (bool online : {false, true}) {
      auto predictors = contender->fit(histories, online);
      Scores scores;
      // A sample is known once it has been predicted: resolution 1 ms reveals it to the next one.
      score_edge(*predictors[0], test_attempts, online, milliseconds(1), scores);
      result.models.push_back(make_row(*contender, online, scores, false));
    }
  }
  return result;
}

Json evaluation_to_json(const EdgeEvaluation& e) {
  Json models = Json::array();
  for (const auto& r : e.models) models.push_back(row_json(r, false));
  return Json{{"edges", e.edges}, {"test_attempts", e.test_attempts}, {"edge_ids", e.edge_ids}, {"models", models}};
}

Json evaluation_to_json(const BinaryEvaluation& e) {
  Json models = Json::array();
  for (const auto& r : e.models) models.push_back(row_json(r, true));
  return Json{{"train_samples", e.train_samples}, {"test_samples", e.test_samples}, {"models", models}};
}

std::string evaluation_to_table(const EdgeEvaluation& e) {
  std::string out = fmt::format("{} edges, {} test attempts\n", e.edges, e.test_attempts);
  out += fmt::format("{:<14} {:<8} {:<6} {:>8} {:>8} {:>9} {:>9} {:>9} {:>11}\n", "model", "protocol", "dedup", "brier",
                     "error", "dur_mae", "mae_mean", "dur_rmse", "pinball_90");
  for (const auto& r : e.models) {
    out +=
        fmt::format("{:<14} {:<8} {:<6} {:>8.4f} {:>8.4f} {:>9.3f} {:>9.3f} {:>9.3f} {:>11.3f}\n", r.name, r.protocol,
                    r.train_dedup ? "yes" : "no", r.brier, r.binary_error, r.duration_mae.value_or(0),
                    r.duration_mae_of_mean.value_or(0), r.duration_rmse.value_or(0), r.duration_pinball_90.value_or(0));
  }
  return out;
}

std::string evaluation_to_table(const BinaryEvaluation& e) {
  std::string out = fmt::format("{} training samples, {} test samples\n", e.train_samples, e.test_samples);
  out += fmt::format("{:<14} {:<8} {:<6} {:>8} {:>8} {:>8}\n", "model", "protocol", "dedup", "rmse", "brier", "error");
  for (const auto& r : e.models) {
    out += fmt::format("{:<14} {:<8} {:<6} {:>8.4f} {:>8.4f} {:>8.4f}\n", r.name, r.protocol,
                       r.train_dedup ? "yes" : "no", std::sqrt(r.brier), r.brier, r.binary_error);
  }
  return out;
}

Result<std::vector<BinarySample>> read_binary_series(const std::filesystem::path& file) {
  auto text = read_text_file(file, Document::kMaxBytes * 4);
  if (!text) return text.error();
  std::vector<BinarySample> out;
  std::istringstream lines(*text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::string t, s, extra;
    if (!(words >> t)) continue;
    words >> s;
    const auto where = fmt::format("{}:{}: ", printable_path(file), number);
    if (s.empty() || (words >> extra))
      return Error::invalid(where + "expected 'unix_time state', found '" + quote_for_message(line) + "'");
    double seconds_since_epoch = 0;
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), seconds_since_epoch);
    if (ec != std::errc{} || p != t.data() + t.size() || !(seconds_since_epoch >= 0 && seconds_since_epoch < 1e11)) {
      return Error::invalid(where + "time '" + quote_for_message(t) + "' is not a unix time in seconds");
    }
    if (s != "0" && s != "1") return Error::invalid(where + "state '" + quote_for_message(s) + "' must be 0 or 1");
    out.push_back({from_unix_seconds(seconds_since_epoch), s == "1"});
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
  return out;
}

}  // namespace rondo::learn
