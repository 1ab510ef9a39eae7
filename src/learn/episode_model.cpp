#include "rondo/learn/episode_model.h"

#include <algorithm>
#include <cmath>

#include "histogram_family.h"
#include "offline_durations.h"

namespace rondo::learn {
namespace {

constexpr std::int64_t kDayMs = 86'400'000;

std::size_t idx(int i) {
  return static_cast<std::size_t>(i);
}

// The q-quantile of the mixture "weight_a of `a`, the rest of `b`": every knot of each table is a
// point mass of its share; the two sorted knot lists are merged and read at cumulative weight q.
double mixture_quantile(const QuantileTable& a, double weight_a, const QuantileTable& b, double q) {
  const auto& va = a.values();
  const auto& vb = b.values();
  const double wa = std::clamp(weight_a, 0.0, 1.0) / static_cast<double>(va.size());
  const double wb = (1 - std::clamp(weight_a, 0.0, 1.0)) / static_cast<double>(vb.size());
  const double target = std::clamp(q, 0.0, 1.0);
  std::size_t i = 0, j = 0;
  double cumulative = 0, previous_mid = 0, previous_value = 0;
  bool first = true;
  while (i < va.size() || j < vb.size()) {
    const bool take_a = j >= vb.size() || (i < va.size() && va[i] <= vb[j]);
    const double value = take_a ? va[i++] : vb[j++];
    const double w = take_a ? wa : wb;
    if (w <= 0) continue;
    const double mid = cumulative + w / 2;
    cumulative += w;
    if (mid >= target) {
      if (first) return value;
      const double frac = mid > previous_mid ? (target - previous_mid) / (mid - previous_mid) : 1.0;
      return previous_value + frac * (value - previous_value);
    }
    previous_mid = mid;
    previous_value = value;
    first = false;
  }
  return previous_value;
}

double mean_of(const std::vector<double>& v) {
  if (v.empty()) return 0;
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

}  // namespace

namespace {
// Milliseconds since local midnight, in [0, kDayMs) (a 25-hour autumn day folds its last hour).
std::int64_t time_of_day_ms(Time t, const TimeZone& zone) {
  const std::int64_t ms = zone.time_of_day(t).count();
  return std::clamp<std::int64_t>(ms, 0, kDayMs - 1);
}
}  // namespace

int EpisodePriors::day_slot(Time t) const {
  return static_cast<int>(time_of_day_ms(t, options.zone) * kDaySlots / kDayMs);
}

SlotAttempt EpisodePriors::slot_attempt(Time t, bool success) const {
  // One zone lookup for the day, the day of the week and the time of day.
  const Time local = t + options.zone.utc_offset(t);
  const auto day = std::chrono::floor<std::chrono::days>(local);
  const std::int64_t ms = std::clamp<std::int64_t>((local - day).count(), 0, kDayMs - 1);
  const unsigned since_monday = (std::chrono::weekday{day}.iso_encoding() + 6) % 7;
  return {day.time_since_epoch().count(),
          static_cast<int>(since_monday) * kDaySlots + static_cast<int>(ms * kDaySlots / kDayMs), success};
}

int EpisodePriors::week_slot(Time t) const {
  return slot_attempt(t, false).week_slot;
}

int EpisodePriors::duration_bin(Time t) const {
  return static_cast<int>(time_of_day_ms(t, options.zone) * options.duration_bins / kDayMs);
}

int EpisodeStats::state_of(bool last_success, Duration gap) {
  const double gap_s = std::max(0.0, to_seconds(gap));
  const int bucket = std::min(kGapBuckets - 1, static_cast<int>(std::floor(std::log2(1.0 + gap_s / 4.0))));
  return (last_success ? kGapBuckets : 0) + bucket;
}

bool EpisodeStats::in_retry(Time t, const EpisodePriors& priors) const {
  return has_last && !last_success && t - last_end < priors.options.retry_gap;
}

void EpisodeStats::add(const Attempt& a, const EpisodePriors& priors) {
  const bool retry = in_retry(a.start, priors);
  if (has_last) {
    const auto s = idx(state_of(last_success, a.start - last_end));
    state_attempts[s] += 1;
    state_successes[s] += a.success ? 1 : 0;
  }
  if (retry) {
    ++episode_length;
  } else {
    if (episode_length > 0 && episode_first_failed) {
      failed_episodes += 1;
      log_length_sum += std::log(static_cast<double>(episode_length));
    }
    const int week = priors.week_slot(a.start);
    const auto slot = idx(week % kDaySlots);
    first_attempts[slot] += 1;
    first_successes[slot] += a.success ? 1 : 0;
    week_attempts[idx(week)] += 1;
    week_successes[idx(week)] += a.success ? 1 : 0;
    episode_length = 1;
    episode_first_failed = !a.success;
  }
  has_last = true;
  last_success = a.success;
  last_end = a.end;
  last_seconds = a.seconds;
}

namespace {

// Calls f(q) for the first-attempt estimate of every shifted histogram at `t` (with the
// time-of-week term when `weekly`).
// `shift`: the live time-of-week term's, added to each histogram's q (clamped).
template <class F>
void for_each_histogram(Time t, const EpisodePriors& priors, const EpisodeStats& live, bool weekly, double shift,
                        F&& f) {
  const auto& o = priors.options;
  double successes = 0, attempts = 0;
  for (std::size_t b = 0; b < live.first_attempts.size(); ++b) {
    successes += live.first_successes[b];
    attempts += live.first_attempts[b];
  }
  const double edge = (successes + o.edge_prior * priors.first_success) / (attempts + o.edge_prior);
  const SlotCounts counts{live.first_successes.data(), live.first_attempts.data(), live.week_successes.data(),
                          live.week_attempts.data()};
  for_each_bin_estimate(priors.week_slot(t), counts, edge, o, weekly,
                        [&](double, double q) { f(shift == 0 ? q : std::clamp(q + shift, 0.0, 1.0)); });
}

}  // namespace

std::shared_ptr<const EpisodeEdgeModel> EpisodeEdgeModel::with_week_shift(WeeklyChoice choice,
                                                                          std::vector<double> shift) const {
  // The statistics' own term is off (histogram_weekly() is false while a shift is set).
  auto copy = std::make_shared<EpisodeEdgeModel>(priors_, stats_, durations_, choice);
  if (choice.weekly && shift.size() == static_cast<std::size_t>(kWeekSlots))
    copy->week_shift_ = std::make_shared<const std::vector<double>>(std::move(shift));
  copy->weekly_.weekly = copy->week_shift_ != nullptr;
  return copy;
}

double EpisodeEdgeModel::week_shift(Time t) const {
  return week_shift_ ? (*week_shift_)[idx(priors_->week_slot(t))] : 0.0;
}

double EpisodeEdgeModel::first_attempt_probability(Time t, const EpisodeStats& live) const {
  double sum = 0;
  int count = 0;
  for_each_histogram(t, *priors_, live, histogram_weekly(), week_shift(t), [&](double q) {
    sum += q;
    ++count;
  });
  return count > 0 ? sum / count : priors_->first_success;
}

double EpisodeEdgeModel::retry_length(const EpisodeStats& live) const {
  const auto& o = priors_->options;
  const double log_length =
      (live.log_length_sum + o.length_prior * priors_->log_retry_length) / (live.failed_episodes + o.length_prior);
  return std::max(1.0, std::exp(log_length));
}

double EpisodeEdgeModel::offline_probability(Time t, const EpisodeStats& live) const {
  const double length = retry_length(live);
  double sum = 0;
  int count = 0;
  for_each_histogram(t, *priors_, live, histogram_weekly(), week_shift(t), [&](double q) {
    sum += q / (q + (1 - q) * length);
    ++count;
  });
  return count > 0 ? sum / count : priors_->first_success;
}

std::vector<double> EpisodeEdgeModel::slot_probabilities(const EpisodeStats& live, bool first_attempt) const {
  const auto& o = priors_->options;
  const bool weekly = histogram_weekly();
  // The edge's rate, as for_each_histogram sums it.
  double successes = 0, attempts = 0;
  for (std::size_t b = 0; b < live.first_attempts.size(); ++b) {
    successes += live.first_successes[b];
    attempts += live.first_attempts[b];
  }
  const double edge = (successes + o.edge_prior * priors_->first_success) / (attempts + o.edge_prior);
  const double length = first_attempt ? 1.0 : retry_length(live);
  std::vector<double> sum(kWeekSlots, 0.0);
  int count = 0;
  std::vector<double> day_q(kDaySlots), week_q(kWeekSlots);
  // One histogram at a time, in for_each_bin_estimate's order: each bin's estimate once, computed
  // as there (the same loop from the bin's first slot), then added to every slot in the bin.
  for_each_shifted_histogram(o.day_resolutions, [&](int width, int offset) {
    std::vector<double> day_s(kDaySlots), day_n(kDaySlots);
    for (int d = 0; d < kDaySlots; ++d) {
      const int back = (((d - offset) % width) + width) % width;
      if (back != 0 && d != 0) {
        day_q[static_cast<std::size_t>(d)] = day_q[static_cast<std::size_t>(d - 1)];
        day_s[static_cast<std::size_t>(d)] = day_s[static_cast<std::size_t>(d - 1)];
        day_n[static_cast<std::size_t>(d)] = day_n[static_cast<std::size_t>(d - 1)];
        continue;
      }
      double bs = 0, bn = 0;
      for (int k = 0; k < width; ++k) {
        const auto i = static_cast<std::size_t>((d - back + k + kDaySlots) % kDaySlots);
        bs += live.first_successes[i];
        bn += live.first_attempts[i];
      }
      day_s[static_cast<std::size_t>(d)] = bs;
      day_n[static_cast<std::size_t>(d)] = bn;
      day_q[static_cast<std::size_t>(d)] = (bs + o.bin_prior * edge) / (bn + o.bin_prior);
    }
    for (int w = 0; w < kWeekSlots; ++w) {
      const auto d = static_cast<std::size_t>(w % kDaySlots);
      double q = day_q[d];
      if (weekly) {
        const int back = (((static_cast<int>(d) - offset) % width) + width) % width;
        if (back != 0 && d != 0) {
          q = week_q[static_cast<std::size_t>(w - 1)];
        } else {
          double sw = 0, nw = 0;
          for (int k = 0; k < width; ++k) {
            const auto i = static_cast<std::size_t>((w - back + k + kWeekSlots) % kWeekSlots);
            sw += live.week_successes[i];
            nw += live.week_attempts[i];
          }
          if (nw > 0) {
            const double correction = nw / (nw + o.weekly_prior) * (sw / nw - day_s[d] / day_n[d]);
            q = std::clamp(q + correction, 0.0, 1.0);
          }
        }
        week_q[static_cast<std::size_t>(w)] = q;
      }
      if (week_shift_) q = std::clamp(q + (*week_shift_)[static_cast<std::size_t>(w)], 0.0, 1.0);
      sum[static_cast<std::size_t>(w)] += first_attempt ? q : q / (q + (1 - q) * length);
    }
    ++count;
  });
  for (double& v : sum) v = count > 0 ? v / count : priors_->first_success;
  return sum;
}

double EpisodeEdgeModel::probability_from(Time t, const EpisodeStats& live, double slot_value) const {
  if (!live.has_last) return slot_value;
  const double q = slot_value;
  const auto& o = priors_->options;
  const auto s = idx(EpisodeStats::state_of(live.last_success, t - live.last_end));
  const double pooled =
      (priors_->state_successes[s] + o.pooled_state_prior * q) / (priors_->state_attempts[s] + o.pooled_state_prior);
  return std::clamp((live.state_successes[s] + o.state_prior * pooled) / (live.state_attempts[s] + o.state_prior) +
                        week_shift(t),
                    0.0, 1.0);
}

double EpisodeEdgeModel::expected_seconds_from(Time t, const EpisodeStats& live, double slot_value) const {
  if (live.in_retry(t, *priors_)) {
    return std::max(0.0, priors_->retry_intercept + priors_->retry_slope * live.last_seconds);
  }
  const auto bin = idx(priors_->duration_bin(t));
  const double p = probability_from(t, live, slot_value);
  return p * durations_.success_mean[bin] + (1 - p) * durations_.failure_mean[bin];
}

double EpisodeEdgeModel::probability(Time t, const EpisodeStats& live, bool use_state) const {
  if (!use_state || !live.has_last) return offline_probability(t, live);
  return probability_from(t, live, first_attempt_probability(t, live));
}

double EpisodeEdgeModel::expected_seconds(Time t, const EpisodeStats& live, bool use_state) const {
  if (use_state && live.in_retry(t, *priors_)) {
    return std::max(0.0, priors_->retry_intercept + priors_->retry_slope * live.last_seconds);
  }
  const auto bin = idx(priors_->duration_bin(t));
  const double p = probability(t, live, use_state);
  return p * durations_.success_mean[bin] + (1 - p) * durations_.failure_mean[bin];
}

const std::vector<QuantileTable>& EpisodeEdgeModel::offline_tables() const {
  return durations_.offline->of_edge(durations_.offline_edge);
}

double EpisodeEdgeModel::quantile_seconds(Time t, double q, const EpisodeStats& live, bool use_state) const {
  if (use_state && live.in_retry(t, *priors_)) return live.last_seconds * priors_->retry_ratio.at(q);
  if (!use_state || !live.has_last) return offline_tables()[idx(priors_->day_slot(t))].at(q);
  const auto bin = idx(priors_->duration_bin(t));
  return mixture_quantile(durations_.success[bin], probability(t, live, use_state), durations_.failure[bin], q);
}

namespace {

struct PooledSums {
  double first_successes = 0, first_attempts = 0, failed_episodes = 0, log_length_sum = 0;
  std::array<double, kStates> state_successes{}, state_attempts{};
  std::vector<double> retry_ratios;
  std::array<std::vector<double>, 2> durations;    // of failed and of successful attempts
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;  // retry duration (y) on the previous one (x)
};

// The statistics of every edge under `priors` (only its options are read), and their pooled sums.
// `firsts` gets each edge's attempts where they fall in the week, in order (what chooses the
// structure of its q(t)).
std::vector<EpisodeStats> collect(const std::vector<std::vector<Attempt>>& edges, const EpisodePriors& priors,
                                  PooledSums& pooled, std::vector<std::vector<SlotAttempt>>& firsts) {
  std::vector<EpisodeStats> out;
  out.reserve(edges.size());
  firsts.assign(edges.size(), {});
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto& attempts = edges[e];
    EpisodeStats stats;
    for (const Attempt& a : attempts) {
      pooled.durations[a.success ? 1 : 0].push_back(a.seconds);
      if (stats.in_retry(a.start, priors)) {
        if (stats.last_seconds > 0) pooled.retry_ratios.push_back(a.seconds / stats.last_seconds);
        pooled.n += 1;
        pooled.sx += stats.last_seconds;
        pooled.sy += a.seconds;
        pooled.sxx += stats.last_seconds * stats.last_seconds;
        pooled.sxy += stats.last_seconds * a.seconds;
      }
      if (priors.options.weekly == WeeklyTerm::kAuto) {
        firsts[e].push_back(priors.slot_attempt(a.start, a.success));
        firsts[e].back().first = !stats.in_retry(a.start, priors);
      }
      stats.add(a, priors);
    }
    for (std::size_t b = 0; b < stats.first_attempts.size(); ++b) {
      pooled.first_successes += stats.first_successes[b];
      pooled.first_attempts += stats.first_attempts[b];
    }
    pooled.failed_episodes += stats.failed_episodes;
    pooled.log_length_sum += stats.log_length_sum;
    for (std::size_t s = 0; s < idx(kStates); ++s) {
      pooled.state_successes[s] += stats.state_successes[s];
      pooled.state_attempts[s] += stats.state_attempts[s];
    }
    out.push_back(std::move(stats));
  }
  return out;
}

std::shared_ptr<EpisodePriors> pooled_priors(const EpisodeOptions& options, const PooledSums& sums) {
  auto priors = std::make_shared<EpisodePriors>();
  priors->options = options;
  // With no attempt at all, assume what the map's distance prior assumes (plan::DistancePrior):
  // edges can be crossed. Every model family then agrees when it has seen nothing.
  priors->first_success = sums.first_attempts > 0 ? sums.first_successes / sums.first_attempts : 1.0;
  priors->log_retry_length = sums.failed_episodes > 0 ? sums.log_length_sum / sums.failed_episodes : 0.0;
  priors->state_successes = sums.state_successes;
  priors->state_attempts = sums.state_attempts;
  // Without any retry seen, a retry is expected to take as long as the attempt before it.
  priors->retry_ratio =
      QuantileTable::from_samples(sums.retry_ratios.empty() ? std::vector<double>{1.0} : sums.retry_ratios);
  const double var = sums.n * sums.sxx - sums.sx * sums.sx;
  if (sums.n >= 2 && var > 0) {
    priors->retry_slope = (sums.n * sums.sxy - sums.sx * sums.sy) / var;
    priors->retry_intercept = (sums.sy - priors->retry_slope * sums.sx) / sums.n;
  }
  return priors;
}

// The durations of every edge's failed ([0]) and successful ([1]) attempts, pooled: the prior of
// each edge's tables. Computed once per fit (sorting 30k samples per edge was most of a fit).
struct PooledDurations {
  std::array<QuantileTable, 2> table;
  std::array<double, 2> mean{};

  explicit PooledDurations(const std::array<std::vector<double>, 2>& durations) {
    for (std::size_t outcome = 0; outcome < 2; ++outcome) {
      table[outcome] = QuantileTable::from_samples(durations[outcome]);
      mean[outcome] = mean_of(durations[outcome]);
    }
  }
};

// Duration tables of one edge per time-of-day bin, for successful and for failed attempts: each
// bin shrunk towards the edge's table, the edge's towards the pooled one.
EpisodeEdgeModel::DurationTables duration_tables(const std::vector<Attempt>& attempts, const EpisodePriors& priors,
                                                 const PooledDurations& pooled) {
  const auto bins = idx(priors.options.duration_bins);
  std::array<std::vector<std::vector<double>>, 2> by_bin{std::vector<std::vector<double>>(bins),
                                                         std::vector<std::vector<double>>(bins)};
  std::array<std::vector<double>, 2> edge;
  for (const Attempt& a : attempts) {
    const auto outcome = idx(a.success ? 1 : 0);
    by_bin[outcome][idx(priors.duration_bin(a.start))].push_back(a.seconds);
    edge[outcome].push_back(a.seconds);
  }
  const double k = priors.options.duration_prior;
  auto weight = [k](const std::vector<double>& v) {
    return static_cast<double>(v.size()) / (static_cast<double>(v.size()) + k);
  };
  EpisodeEdgeModel::DurationTables out;
  for (std::size_t outcome = 0; outcome < 2; ++outcome) {
    const double we = weight(edge[outcome]);
    const auto edge_table = QuantileTable::blend(QuantileTable::from_samples(edge[outcome]), pooled.table[outcome], we);
    const double edge_mean = we * mean_of(edge[outcome]) + (1 - we) * pooled.mean[outcome];
    auto& tables = outcome == 1 ? out.success : out.failure;
    auto& means = outcome == 1 ? out.success_mean : out.failure_mean;
    for (std::size_t b = 0; b < bins; ++b) {
      const double wb = weight(by_bin[outcome][b]);
      tables.push_back(QuantileTable::blend(QuantileTable::from_samples(by_bin[outcome][b]), edge_table, wb));
      means.push_back(wb * mean_of(by_bin[outcome][b]) + (1 - wb) * edge_mean);
    }
  }
  return out;
}

}  // namespace

EpisodeFit fit_episode_models(const std::vector<std::vector<Attempt>>& edges, const EpisodeOptions& given) {
  EpisodeOptions options = given;
  options.duration_bins = std::clamp(options.duration_bins, 1, 1440);
  EpisodePriors shape;
  shape.options = options;
  PooledSums sums;
  std::vector<std::vector<SlotAttempt>> firsts;
  auto stats = collect(edges, shape, sums, firsts);
  EpisodeFit fit;
  auto priors = pooled_priors(options, sums);
  fit.priors = priors;
  // Computed when first read (the executor's refit never reads them).
  const auto offline = std::make_shared<const OfflineDurations>(edges, priors);
  const PooledDurations pooled(sums.durations);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    auto tables = duration_tables(edges[e], *priors, pooled);
    tables.offline = offline;
    tables.offline_edge = e;
    WeeklyChoice weekly;
    if (options.weekly == WeeklyTerm::kOn) weekly.weekly = true;
    if (options.weekly == WeeklyTerm::kAuto) {
      weekly = choose_weekly(firsts[e], priors->first_success, options);
    }
    fit.edges.push_back(
        std::make_shared<const EpisodeEdgeModel>(priors, std::move(stats[e]), std::move(tables), weekly));
  }
  return fit;
}

std::shared_ptr<const EpisodeBinaryModel> fit_episode_binary(std::span<const BinarySample> samples,
                                                             const EpisodeOptions& options) {
  std::vector<std::vector<Attempt>> edges(1);
  for (const auto& s : samples) edges[0].push_back({s.time, s.time, 0.0, s.value});
  std::stable_sort(edges[0].begin(), edges[0].end(), [](const auto& a, const auto& b) { return a.start < b.start; });
  auto fit = fit_episode_models(edges, options);
  return std::make_shared<const EpisodeBinaryModel>(fit.edges[0]);
}

}  // namespace rondo::learn
