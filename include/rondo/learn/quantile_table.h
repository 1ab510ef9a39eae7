// A compact, monotone description of a distribution of durations: its quantiles at fixed levels,
// linearly interpolated between them. What the duration models store and serialise.
//
//   QuantileTable q = QuantileTable::from_samples({12.0, 9.5, 30.1, 11.0});
//   double p90 = q.at(0.9);          // non-decreasing in the level, >= 0
//   auto w = QuantileTable::from_weighted_samples({{12.0, 1.0}, {0.7, 0.25}});  // (value, weight)
//   auto shrunk = QuantileTable::blend(w, q, 0.8);       // 0.8 of w's quantile function, 0.2 of q's
//   auto mixed = QuantileTable::mixture(std::vector{w, q}, std::vector{0.8, 0.2});  // of the distributions
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"

namespace rondo::learn {

class QuantileTable {
 public:
  // Levels 0.02, 0.04, ..., 0.98 (49 knots): fine enough for pinball losses, small in JSON.
  static constexpr int kKnots = 49;
  static double level(int knot) { return 0.02 * (knot + 1); }

  QuantileTable() : values_(kKnots, 0.0) {}
  // Empirical quantiles (linear interpolation between order statistics) of `values`; all zero
  // when `values` is empty. Negative values are clamped to 0 unless `allow_negative` (residuals).
  static QuantileTable from_samples(std::vector<double> values, bool allow_negative = false);

  struct WeightedValue {
    double value = 0;
    double weight = 0;  // >= 0; non-positive and non-finite weights are dropped
  };
  // Quantiles of a weighted sample: each distinct value holds its share of the total weight (equal
  // values pool their weights), centred on the middle of its share (Hazen's plotting positions),
  // interpolated linearly between those centres and constant beyond the first and last. Negative
  // values are clamped to 0; all zero when no weight is positive. O(n) for samples already in
  // value order, O(n log n) otherwise.
  static QuantileTable from_weighted_samples(std::vector<WeightedValue> samples);
  // The effective number of observations of a weighted sample, (sum w)^2 / sum w^2 (Kish).
  static double effective_count(const std::vector<WeightedValue>& samples);

  // Quantile averaging (Vincentisation): `weight` of a's quantile function plus the rest of b's,
  // weight clamped to [0, 1]. Non-decreasing because both inputs are.
  static QuantileTable blend(const QuantileTable& a, const QuantileTable& b, double weight);
  // A table from its kKnots knot values (made non-decreasing and >= 0); empty or wrong-sized
  // input gives all zeros.
  static QuantileTable from_knots(const std::vector<double>& knots);
  // The knot-wise mean of `tables` (all zero for none): the quantile average with equal weights.
  static QuantileTable average(std::span<const QuantileTable> tables);
  // The mixture of distributions: `weights[i]` of tables[i]'s distribution (weights normalised;
  // non-positive and non-finite ones dropped; all zero for none). A table's distribution is the
  // one its knots describe: 0.02 at the first knot, its CDF linear between knots, 0.02 at the last
  // (knots equal to 1e-9 relative are an atom). The mixture's CDF is the weighted mean of the
  // CDFs, so a mixture of equal tables is that table, and each of its quantiles lies between the
  // smallest and the largest of the inputs' quantiles at the same level. Unlike blend(), mixing 10 s and 100 s
  // gives a table of 10 s and 100 s, not one of 55 s.
  static QuantileTable mixture(std::span<const QuantileTable> tables, std::span<const double> weights);
  // The same over tables held elsewhere (no copies).
  static QuantileTable mixture(std::span<const QuantileTable* const> tables, std::span<const double> weights);
  // The same table with every value rounded to `decimals` (0..9) decimal places, still
  // non-decreasing: short JSON numbers.
  QuantileTable rounded(int decimals) const;

  // The q-quantile, q clamped to [0.02, 0.98] (the table does not extrapolate the tails).
  // Non-decreasing in q.
  double at(double q) const;
  const std::vector<double>& values() const { return values_; }

  Json to_json() const;
  static Result<QuantileTable> from_json(const Json& j);

 private:
  friend class QuantileMixer;
  // One knot of one table in the sweep of a mixture.
  struct KnotEvent {
    double value = 0;
    std::uint32_t table = 0;
    std::uint32_t knot = 0;
  };
  // The mixture's CDF swept over `events` (in value, table, knot order): table t is tables[t],
  // with normalised weight share[t].
  static QuantileTable sweep(std::span<const KnotEvent> events, std::span<const QuantileTable* const> tables,
                             std::span<const double> share);

  std::vector<double> values_;  // non-decreasing, size kKnots
};

// Mixtures of tables from one family where each mixture changes only a few members of the one
// before: the time slots of a day, which share most of their bins. mix() gives exactly what
// QuantileTable::mixture gives for the same members in rank order, but keeps the members' knots
// sorted between calls, so that a call merges the knots of the members that changed instead of
// sorting all of them again.
//
//   QuantileMixer mixer;
//   for (slot ...) out[slot] = mixer.mix(members_of(slot));   // {table, weight, rank} each
class QuantileMixer {
 public:
  struct Member {
    const QuantileTable* table = nullptr;  // must outlive the mixer's use of it
    double weight = 0;                     // > 0 and finite; others are left out
    std::uint32_t rank = 0;                // the member's place in the order (ties of values)
  };
  // Members in strictly increasing rank (others: an empty table). A rank holding another table
  // than in the last call is a new member.
  QuantileTable mix(std::span<const Member> members);

 private:
  using KnotEvent = QuantileTable::KnotEvent;
  std::vector<KnotEvent> events_, fresh_, buffer_;
  std::vector<const QuantileTable*> table_of_rank_;  // the members of the last call, by rank
  std::vector<double> share_;
};

}  // namespace rondo::learn
