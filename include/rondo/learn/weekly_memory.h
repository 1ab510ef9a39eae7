// The week, learned live. The executor refits its edge models every night from a bounded window
// of the traversal log (14 days by default): too few weeks for a time-of-week term to earn its
// place (choose_weekly needs it to win in two weeks after the first). WeeklyMemory keeps what the
// term needs beside that window, at a fixed cost per day however long the robot lives:
//   - per edge, counts of first attempts (successes, attempts) by 15-minute slot of the local
//     week, every count forgotten exponentially (`half_life`);
//   - the same prequential, day-ahead evidence as choose_weekly: each first attempt of a new day is
//     predicted from the counts of the days before it, by time of day alone and with the weekly
//     term, and the paired differences of the Brier scores are summed (forgotten at the same rate)
//     and kept per 7-day block for the last `weeks_kept` blocks.
// The term is chosen per edge by the offline rule: z = −Σd / √Σd² >= `evidence` and the term
// won (Σd < 0) in at least two whole blocks after the edge's first (a block counts once its seventh
// day is in). Then `shift(edge)` is what it adds to
// q(t) and to the online probability, per slot of the week: the week bin's deviation from its day
// bin in the forgotten counts, shrunk towards none by `weekly_prior`, averaged over the shifted
// histograms (episode_model.h).
//
//   WeeklyMemory memory;                        // or WeeklyMemory::from_json(stored)
//   memory.add_day(day, that_days_traversals, priors);   // once per whole local day, in order
//   if (memory.choice("A_B", priors.options).weekly) std::vector<double> w = memory.shift("A_B", priors.options);
//
// Deterministic: the same days in the same order give the same memory, and its JSON round-trips
// exactly.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/traversal.h"
#include "rondo/learn/episode_model.h"

namespace rondo::learn {

struct WeeklyMemoryOptions {
  // A first attempt's weight halves in this many days (the prequential sums' too).
  double half_life_days = 28;
  // The blocks of 7 days whose evidence is kept: the term must have won in two of them.
  int weeks_kept = 6;
  // The term needs z >= this (EpisodeOptions::weekly_evidence is the offline choice's, made once):
  // the live choice is made again every night, and on a persistent series without any weekly
  // pattern z >= 2 came up on some night of eight weeks in 5 of 200 runs, z >= 2.5 in none
  // (tests/learn/gtest_weekly_memory.cpp).
  double evidence = 2.5;
};

class WeeklyMemory {
 public:
  explicit WeeklyMemory(WeeklyMemoryOptions options = {}) : options_(options) {}

  const WeeklyMemoryOptions& options() const { return options_; }
  // The first local day (days since 1970-01-01) not yet added; nothing before the first day.
  std::optional<std::int64_t> next_day() const;
  // Adds one whole local day: the traversals that started on local day `day` (in priors.options'
  // zone), in start order. Days must come in increasing order (a day already added is an error);
  // days skipped are days without traversals. Edges are known by id; new ids are added.
  Status add_day(std::int64_t day, std::span<const Traversal> traversals, const EpisodePriors& priors);

  // The choice for an edge by options.weekly and this memory's `evidence` (no weekly term for an
  // unknown edge). `scored` is the forgotten count of its first attempts, rounded.
  WeeklyChoice choice(const std::string& edge_id, const EpisodeOptions& options) const;
  // What the term adds to q(t) at each slot of the week (kWeekSlots values); empty for an unknown
  // edge. Computed from the counts whether or not the term is chosen.
  std::vector<double> shift(const std::string& edge_id, const EpisodeOptions& options) const;
  std::size_t edges() const { return edges_.size(); }

  Json to_json() const;
  static Result<WeeklyMemory> from_json(const Json& j);

 private:
  struct Edge {
    std::vector<double> successes = std::vector<double>(kWeekSlots, 0.0);
    std::vector<double> attempts = std::vector<double>(kWeekSlots, 0.0);
    double sum_d = 0, sum_dd = 0;
    std::int64_t first_block = -1;                 // the block of its first scored attempt
    std::map<std::int64_t, double> block_sums;     // Σd per 7-day block, the last weeks_kept
    bool has_last = false, last_success = false;   // for telling retries from first attempts
    Time last_end{};
  };
  void forget(double factor);
  void score_and_add(Edge& e, std::int64_t block, std::span<const SlotAttempt> firsts, const EpisodePriors& priors);
  static Json edge_json(const Edge& e);
  static Result<Edge> edge_from_json(const Json& j);

  WeeklyMemoryOptions options_;
  std::optional<std::int64_t> first_day_, next_day_;
  std::map<std::string, Edge> edges_;
};

}  // namespace rondo::learn
