// The episode model: rondo's own model of an edge's success and traversal time, built on what the
// logs of real robots show. Attempts come in episodes: a first attempt, and after a failure quick
// retries of the same edge that mostly fail again (a closed door stays closed) until one succeeds
// or the robot gives up. So:
//   - q(t), the success probability of an episode's first attempt, follows the building's daily
//     rhythm: per-edge time-of-day histograms, each bin shrunk towards the edge's mean (itself
//     shrunk towards the pooled mean), averaged over several bin widths and shifted bin edges
//     (averaged shifted histograms: smooth, and no bin width to pick);
//   - L, the typical number of attempts in a failed episode, is heavy-tailed: the edge's geometric
//     mean, shrunk towards the pooled one;
//   - offline, an attempt at t succeeds with q / (q + (1 − q) L) (successes among the attempts an
//     episode produces); online, the probability is conditioned on the edge's state: the outcome of
//     its last attempt and the time since it ended (a table per state, shrunk towards the pooled
//     table, which is itself shrunk towards q(t));
//   - durations, offline: per local time of day, quantiles of attempt durations in which a failed
//     episode's retries share the weight of a typical episode's and older attempts weigh less
//     (offline_durations.h); online: quantile tables of successful and of failed attempts mixed
//     with the state-conditioned success probability, and during a retry burst the last duration
//     times the pooled distribution of retry-to-retry ratios.
//
// Time of day is local time in `EpisodeOptions::zone` (IANA, daylight saving included).
//
// The week: q(t) may also carry a time-of-week term: each time-of-day bin's estimate is corrected
// by how the same bin on the same day of the week differs from it, that difference shrunk towards
// none (`weekly_prior` pseudo-observations). Whether an edge (or a
// binary series) gets it is chosen per edge from its own training data (WeeklyChoice): both
// structures predict every first attempt from the attempts before it (prequential, so every score
// is on data the counts have not seen), and the weekly term is kept only when its Brier score is
// lower by at least `weekly_evidence` standard errors of the paired differences.
//
//   std::vector<std::vector<Attempt>> per_edge = ...;    // training attempts, each in start order
//   auto fitted = fit_episode_models(per_edge, {});
//   double p = fitted.edges[3]->probability(t);                       // offline
//   EpisodePredictor live(fitted.edges[3]);                            // online, O(1) updates
//   live.observe(attempt);  double p_now = live.probability(t);
//
// Nothing here is tuned to one building: the histogram family is fixed, the other constants are
// weak priors (a few pseudo-observations).
#pragma once

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/timezone.h"
#include "rondo/learn/edge_predictor.h"
#include "rondo/learn/quantile_table.h"
#include "rondo/learn/temporal_model.h"

namespace rondo::learn {

// Whether q(t) has a time-of-week term: never, chosen per edge on its training data, always.
enum class WeeklyTerm { kOff, kAuto, kOn };

struct EpisodeOptions {
  // An attempt that starts less than this after a failed attempt on the same edge ended is a retry.
  Duration retry_gap = seconds(60);
  // The time-of-day histograms averaged for q(t): bins per day. Each must divide 24 (so every
  // shifted bin edge falls on the 15-minute grid the counts are kept on); others are ignored.
  std::vector<int> day_resolutions = {1, 2, 3, 4, 6, 8, 12};
  // Time-of-day bins of the duration tables (clamped to 1..1440).
  int duration_bins = 6;
  // The deployment's time zone: time-of-day bins are local time, so they follow daylight saving.
  TimeZone zone = TimeZone::utc();
  // Offline duration quantiles: an attempt's weight halves every this long before the newest
  // attempt of the fit; zero or less: no decay.
  Duration duration_half_life = std::chrono::days(7);
  // Offline duration quantiles: how the tables are shrunk (a bin towards the edge, the edge towards
  // the pooled table) and how the shifted histograms are averaged. true: mixtures of the
  // distributions (the posterior predictive of a Dirichlet process whose base measure is the prior
  // table, and averaged shifted histograms proper); false: quantile averaging (Vincentisation),
  // which invents durations between modes and makes a fit about 3x faster (Witham: 36 against
  // 105 ms). Mixtures scored better on time-ordered validation periods before the default split
  // (docs/learning.md).
  bool duration_mixture = true;
  // The time-of-week term of q(t) and how it is chosen (see the top of this file).
  WeeklyTerm weekly = WeeklyTerm::kAuto;
  // kAuto keeps the term when z = −Σd / sqrt(Σd²) >= this, d the paired differences of the
  // prequential Brier scores (week − day) of the first attempts, and Σd < 0 in two weeks or more. Calibrated on series
  // without any weekly structure (docs/learning.md), not on a data set.
  double weekly_evidence = 2;
  // Prior strengths, in pseudo-observations.
  double bin_prior = 10;          // a time-of-day bin towards the edge's first-attempt rate
  double weekly_prior = 10;       // a time-of-week bin's deviation from its time-of-day bin towards 0
  double edge_prior = 2;          // an edge's first-attempt rate towards the pooled rate
  double length_prior = 5;        // an edge's log retry length towards the pooled one
  double state_prior = 10;        // an edge's state table towards the pooled state table
  double pooled_state_prior = 5;  // the pooled state table towards q(t)
  double duration_prior = 10;     // a bin's duration quantiles towards the edge's
};

// The edge's state for the online model: outcome of the last attempt and time since it ended.
// 13 gap buckets per outcome: floor(log2(1 + gap / 4 s)), the last one open-ended (> ~4.5 h).
inline constexpr int kGapBuckets = 13;
inline constexpr int kStates = 2 * kGapBuckets;

// Counts of first attempts are kept per 15 minutes of the day and of the week (Monday first).
inline constexpr int kDaySlots = 96;
inline constexpr int kWeekSlots = 7 * kDaySlots;
// Each histogram is averaged over this many shifts of its bin edges (by a quarter bin).
inline constexpr int kHistogramShifts = 4;

// One attempt where it falls in the local week, for choosing the structure of q(t).
struct SlotAttempt {
  std::int64_t day = 0;  // local days since 1970-01-01
  int week_slot = 0;
  bool success = false;
  bool first = true;  // starts an episode (only first attempts are counted in q's bins)
};

// What is pooled over all edges of a fit. Immutable once fitted.
struct EpisodePriors {
  EpisodeOptions options;
  double first_success = 0.5;                     // pooled first-attempt success rate
  double log_retry_length = 0;                    // pooled mean of log(attempts per failed episode)
  std::array<double, kStates> state_successes{};  // pooled counts per state
  std::array<double, kStates> state_attempts{};
  QuantileTable retry_ratio;  // quantiles of (retry duration / previous duration), pooled
  // Least-squares line of a retry's duration on the previous attempt's: the expected value.
  double retry_intercept = 0, retry_slope = 1;

  int day_slot(Time t) const;   // 0..kDaySlots-1, local time in options.zone
  int week_slot(Time t) const;  // 0..kWeekSlots-1 from local Monday 00:00; day_slot = week_slot % kDaySlots
  SlotAttempt slot_attempt(Time t, bool success) const;  // with the local day number
  int duration_bin(Time t) const;                        // 0..options.duration_bins-1, local time in options.zone
  Json to_json() const;
  static Result<EpisodePriors> from_json(const Json& j);
};

// Sufficient statistics of one edge, cheap to update: counts per time-of-day bin and per state,
// failed-episode lengths, and the recency state. add() takes attempts in order of their end.
struct EpisodeStats {
  std::vector<double> first_successes, first_attempts;  // per 15-minute slot of the day
  std::vector<double> week_successes, week_attempts;    // per 15-minute slot of the week
  double failed_episodes = 0, log_length_sum = 0;
  std::array<double, kStates> state_successes{}, state_attempts{};
  // Recency: the last attempt seen, and the failed episode in progress.
  bool has_last = false;
  bool last_success = false;
  Time last_end{};
  double last_seconds = 0;
  int episode_length = 0;  // attempts in the current episode so far
  bool episode_first_failed = false;

  EpisodeStats()
      : first_successes(kDaySlots, 0.0),
        first_attempts(kDaySlots, 0.0),
        week_successes(kWeekSlots, 0.0),
        week_attempts(kWeekSlots, 0.0) {}
  void add(const Attempt& a, const EpisodePriors& priors);
  // True when an attempt starting at t would be a retry of a failure.
  bool in_retry(Time t, const EpisodePriors& priors) const;
  static int state_of(bool last_success, Duration gap);
  Json to_json() const;
  static Result<EpisodeStats> from_json(const Json& j);
};

// The structure chosen for one edge's q(t), and the evidence: the prequential Brier scores of its
// first attempts under time of day alone and with the time-of-week term (0 when not scored).
struct WeeklyChoice {
  bool weekly = false;
  double evidence = 0;  // z (see EpisodeOptions::weekly_evidence)
  int scored = 0;       // first attempts the two structures predicted differently
  int weeks_won = 0;    // 7-day blocks after the first in which the term lowered the score
  double day_brier = 0, week_brier = 0;  // means over all first attempts
  Json to_json() const;
  static Result<WeeklyChoice> from_json(const Json& j);
};

// Chooses the structure of q(t) from one edge's attempts (in time order; only first attempts are
// used: retries of one failure are one observation of q, not hundreds). Each first attempt of a
// day is predicted from those of the days before it only (day-ahead, as the nightly fit is used:
// otherwise a state that persists for hours would make the finer bins look prescient). The weekly
// term is kept when z >= options.weekly_evidence and it lowered the Brier score in at least two
// different weeks (a weekly pattern recurs; one odd day remembered a week later does not).
// `pooled_rate` is what an edge's rate is shrunk towards. Deterministic.
WeeklyChoice choose_weekly(std::span<const SlotAttempt> attempts, double pooled_rate, const EpisodeOptions& options);

// The offline duration tables of the edges of one fit (offline_durations.h), computed when first
// read.
class OfflineDurations;

// One edge's fitted model: shared priors, the edge's statistics and duration tables. Immutable.
class EpisodeEdgeModel {
 public:
  struct DurationTables {
    // Per time-of-day bin, durations of successful and of failed attempts.
    std::vector<QuantileTable> success, failure;
    std::vector<double> success_mean, failure_mean;
    // Offline: per 15-minute slot of the local day, all attempts: the tables of edge
    // `offline_edge` of the fit's OfflineDurations, shared by its edges.
    std::shared_ptr<const OfflineDurations> offline;
    std::size_t offline_edge = 0;
  };
  EpisodeEdgeModel(std::shared_ptr<const EpisodePriors> priors, EpisodeStats stats, DurationTables durations,
                   WeeklyChoice weekly = {})
      : priors_(std::move(priors)), stats_(std::move(stats)), durations_(std::move(durations)), weekly_(weekly) {}

  // Offline: success probability of an attempt starting at t, not knowing recent outcomes.
  double probability(Time t) const { return probability(t, stats_, false); }
  // With `live` statistics: online when `use_state` (conditioned on live's recency state).
  double probability(Time t, const EpisodeStats& live, bool use_state) const;
  // The first-attempt success probability q(t) from `live` counts (the histogram average).
  double first_attempt_probability(Time t, const EpisodeStats& live) const;
  // Offline attempt success q / (q + (1 − q) L), averaged over the histograms.
  double offline_probability(Time t, const EpisodeStats& live) const;
  // Typical attempts per failed episode, >= 1.
  double retry_length(const EpisodeStats& live) const;
  // For every 15-minute slot of the local week (kWeekSlots, Monday 00:00 first): q(t) from `live`
  // counts when `first_attempt`, else offline_probability(t, live), at any t in that slot. The
  // same sums in the same order as those functions, so equal to them, at the cost of a few calls.
  std::vector<double> slot_probabilities(const EpisodeStats& live, bool first_attempt) const;
  // probability(t, live, true) and expected_seconds(t, live, true) given slot_probabilities(live,
  // live.has_last)'s value for t's slot: what LiveEdgeModels reads many times between updates.
  double probability_from(Time t, const EpisodeStats& live, double slot_value) const;
  double expected_seconds_from(Time t, const EpisodeStats& live, double slot_value) const;

  double expected_seconds(Time t) const { return expected_seconds(t, stats_, false); }
  double quantile_seconds(Time t, double q) const { return quantile_seconds(t, q, stats_, false); }
  double expected_seconds(Time t, const EpisodeStats& live, bool use_state) const;
  double quantile_seconds(Time t, double q, const EpisodeStats& live, bool use_state) const;

  const EpisodeStats& stats() const { return stats_; }
  // The per-bin duration tables of successful and failed attempts (bin: priors()->duration_bin).
  const DurationTables& durations() const { return durations_; }
  const std::shared_ptr<const EpisodePriors>& priors() const { return priors_; }
  // Whether q(t) has the time-of-week term, and why.
  const WeeklyChoice& weekly() const { return weekly_; }
  // A copy with a live time-of-week term (WeeklyMemory, weekly_memory.h): `shift` (kWeekSlots
  // values, one per slot of the local week) is added to each histogram's q(t) before the average
  // and the offline probability, and to the online probability, each clamped to [0, 1]. The
  // copy's term from its own statistics is off; `choice` says why the shift is there.
  std::shared_ptr<const EpisodeEdgeModel> with_week_shift(WeeklyChoice choice, std::vector<double> shift) const;
  // The live time-of-week shift at t (0 without one).
  double week_shift(Time t) const;
  // The edge's part only (statistics and duration tables); the priors are saved once per set.
  Json to_json() const;
  static Result<EpisodeEdgeModel> from_json(const Json& j, std::shared_ptr<const EpisodePriors> priors);

 private:
  // The offline duration tables (kDaySlots), computed on the first call for the whole fit.
  const std::vector<QuantileTable>& offline_tables() const;
  // Whether the histograms carry the weekly term from the statistics' week counts.
  bool histogram_weekly() const { return weekly_.weekly && !week_shift_; }

  std::shared_ptr<const EpisodePriors> priors_;
  EpisodeStats stats_;
  DurationTables durations_;
  WeeklyChoice weekly_;
  std::shared_ptr<const std::vector<double>> week_shift_;  // null: none
};

struct EpisodeFit {
  std::shared_ptr<const EpisodePriors> priors;
  std::vector<std::shared_ptr<const EpisodeEdgeModel>> edges;  // same order as the input
};

// Fits every edge, pooling across them. Each inner vector: one edge's attempts in start order.
EpisodeFit fit_episode_models(const std::vector<std::vector<Attempt>>& edges, const EpisodeOptions& options = {});

// The online form: the fitted edge plus live statistics. observe() is O(1).
class EpisodePredictor final : public EdgePredictor {
 public:
  explicit EpisodePredictor(std::shared_ptr<const EpisodeEdgeModel> model)
      : model_(std::move(model)), live_(model_->stats()) {}
  void observe(const Attempt& a) override { live_.add(a, *model_->priors()); }
  double probability(Time t) const override { return model_->probability(t, live_, true); }
  double expected_seconds(Time t) const override { return model_->expected_seconds(t, live_, true); }
  double quantile_seconds(Time t, double q) const override { return model_->quantile_seconds(t, q, live_, true); }
  const EpisodeStats& live() const { return live_; }

 private:
  std::shared_ptr<const EpisodeEdgeModel> model_;
  EpisodeStats live_;
};

// A single binary series through the same model (the series is one "edge" whose attempts take no
// time): the BinaryModel for `rondo eval binary` and for door-open facts.
class EpisodeBinaryModel final : public BinaryModel {
 public:
  explicit EpisodeBinaryModel(std::shared_ptr<const EpisodeEdgeModel> model) : model_(std::move(model)) {}
  double probability(Time t) const override { return model_->probability(t); }
  Json to_json() const override;
  const EpisodeEdgeModel& model() const { return *model_; }

 private:
  std::shared_ptr<const EpisodeEdgeModel> model_;
};

std::shared_ptr<const EpisodeBinaryModel> fit_episode_binary(std::span<const BinarySample> samples,
                                                             const EpisodeOptions& options = {});

}  // namespace rondo::learn
