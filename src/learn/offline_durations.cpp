#include "offline_durations.h"

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <map>

#include "histogram_family.h"

namespace rondo::learn {
namespace {

using Sample = QuantileTable::WeightedValue;

struct SlotSample {
  int slot = 0;
  Sample sample;
};

// The edge's attempts with their episode and recency weights, and the slot each started in.
std::vector<SlotSample> weighted_attempts(const std::vector<Attempt>& attempts, const EpisodePriors& priors,
                                          Time newest) {
  const auto& o = priors.options;
  // Episodes: index of each attempt's episode, retries per episode, failed episodes.
  std::vector<std::size_t> episode_of(attempts.size());
  std::vector<int> retries;
  std::vector<bool> first_failed;
  double log_length_sum = 0;
  for (std::size_t i = 0; i < attempts.size(); ++i) {
    const Attempt& a = attempts[i];
    const bool retry = i > 0 && !attempts[i - 1].success && a.start - attempts[i - 1].end < o.retry_gap;
    if (!retry) {
      if (!retries.empty() && first_failed.back()) log_length_sum += std::log(1.0 + retries.back());
      retries.push_back(0);
      first_failed.push_back(!a.success);
    } else {
      ++retries.back();
    }
    episode_of[i] = retries.size() - 1;
  }
  if (!retries.empty() && first_failed.back()) log_length_sum += std::log(1.0 + retries.back());
  double failed = 0, with_retries = 0;
  for (std::size_t e = 0; e < retries.size(); ++e) {
    failed += first_failed[e] ? 1 : 0;
    with_retries += retries[e] > 0 ? 1 : 0;
  }
  // The same shrunk geometric mean as EpisodeEdgeModel::retry_length.
  const double length =
      std::max(1.0, std::exp((log_length_sum + o.length_prior * priors.log_retry_length) / (failed + o.length_prior)));
  const double retry_mass = with_retries > 0 ? failed * (length - 1) / with_retries : 0.0;
  const double half_life_s = to_seconds(o.duration_half_life);
  std::vector<SlotSample> out;
  out.reserve(attempts.size());
  for (std::size_t i = 0; i < attempts.size(); ++i) {
    const Attempt& a = attempts[i];
    const int n_retries = retries[episode_of[i]];
    const bool first = i == 0 || episode_of[i] != episode_of[i - 1];
    double w = first ? 1.0 : retry_mass / n_retries;
    if (half_life_s > 0) w *= std::exp2(-to_seconds(newest - a.start) / half_life_s);
    out.push_back({priors.day_slot(a.start), {a.seconds, w}});
  }
  return out;
}

std::vector<Sample> samples_of(const std::vector<SlotSample>& v) {
  std::vector<Sample> out;
  out.reserve(v.size());
  for (const auto& s : v) out.push_back(s.sample);
  return out;
}

// `samples` shrunk towards `prior` by their effective count n: n / (n + prior_strength) of the
// samples' table, the rest of the prior's, as a quantile average or (`mixture`) a mixture.
QuantileTable shrunk(const std::vector<Sample>& samples, const QuantileTable& prior, double prior_strength,
                     bool mixture) {
  const double n = QuantileTable::effective_count(samples);
  if (n <= 0) return prior;
  const double weight = n / (n + prior_strength);
  if (!mixture) return QuantileTable::blend(QuantileTable::from_weighted_samples(samples), prior, weight);
  const std::array<QuantileTable, 2> tables{QuantileTable::from_weighted_samples(samples), prior};
  const std::array<double, 2> weights{weight, 1 - weight};
  return QuantileTable::mixture(tables, weights);
}

// The bins of every shifted histogram of one edge: their samples, and for each 15-minute slot the
// bins (one per histogram) that hold it. `attempts` come in value order, and so does each bin's
// share of them, so that building a bin's table does not sort it again.
struct ShiftedBins {
  std::vector<std::vector<Sample>> members;       // per bin, over all histograms, by value
  std::vector<std::vector<std::size_t>> of_slot;  // per slot, its bins

  ShiftedBins(const std::vector<SlotSample>& attempts, const std::vector<int>& day_resolutions)
      : of_slot(static_cast<std::size_t>(kDaySlots)) {
    for_each_shifted_histogram(day_resolutions, [&](int width, int offset) {
      auto bin_of = [&](int slot) {
        return static_cast<std::size_t>(((slot - offset) % kDaySlots + kDaySlots) % kDaySlots / width);
      };
      const std::size_t first = members.size();
      members.resize(first + static_cast<std::size_t>(kDaySlots / width));
      for (const auto& a : attempts) members[first + bin_of(a.slot)].push_back(a.sample);
      for (int slot = 0; slot < kDaySlots; ++slot) {
        of_slot[static_cast<std::size_t>(slot)].push_back(first + bin_of(slot));
      }
    });
  }
};

// Quantile averaging: each bin's table shrunk towards the edge's (a quantile average), and each
// slot's table the equal-weight quantile average of its bins' tables.
std::vector<QuantileTable> averaged_day_tables(const ShiftedBins& bins, const QuantileTable& edge, double prior) {
  std::vector<QuantileTable> tables;
  tables.reserve(bins.members.size());
  for (const auto& m : bins.members) tables.push_back(shrunk(m, edge, prior, false));
  std::vector<QuantileTable> out(static_cast<std::size_t>(kDaySlots), edge);
  std::vector<QuantileTable> of_slot;
  for (std::size_t slot = 0; slot < out.size(); ++slot) {
    if (bins.of_slot[slot].empty()) continue;
    of_slot.clear();
    for (std::size_t b : bins.of_slot[slot]) of_slot.push_back(tables[b]);
    out[slot] = QuantileTable::average(of_slot);
  }
  return out;
}

// Mixtures: a bin with effective count n is n / (n + prior) of its own distribution and the rest
// the edge's, and a slot is the equal-weight mixture of its bins. A mixture of mixtures is one
// mixture, so each slot mixes its bins' own tables (weight n / (n + prior) each) with the edge's
// (the sum of the rest), once per distinct set of bins (neighbouring slots often share all).
std::vector<QuantileTable> mixed_day_tables(const ShiftedBins& bins, const QuantileTable& edge, double prior) {
  std::vector<QuantileTable> own;
  std::vector<double> own_weight;
  own.reserve(bins.members.size());
  for (const auto& m : bins.members) {
    const double n = QuantileTable::effective_count(m);
    own.push_back(n > 0 ? QuantileTable::from_weighted_samples(m) : QuantileTable{});
    own_weight.push_back(n > 0 ? n / (n + prior) : 0.0);
  }
  std::vector<QuantileTable> out(static_cast<std::size_t>(kDaySlots), edge);
  std::map<std::vector<std::size_t>, std::size_t> done;  // a slot's bins -> the first slot with them
  // Neighbouring slots share all but a few bins: the mixer keeps their knots sorted. A bin's rank
  // is its histogram's place in the slot's list, the edge's comes last (QuantileTable::mixture's
  // order of the same tables).
  QuantileMixer mixer;
  std::vector<QuantileMixer::Member> members;
  for (std::size_t slot = 0; slot < out.size(); ++slot) {
    const auto& of_slot = bins.of_slot[slot];
    if (of_slot.empty()) continue;
    if (auto [it, inserted] = done.try_emplace(of_slot, slot); !inserted) {
      out[slot] = out[it->second];
      continue;
    }
    members.clear();
    double edge_weight = 0;
    for (std::size_t h = 0; h < of_slot.size(); ++h) {
      const std::size_t b = of_slot[h];
      edge_weight += 1 - own_weight[b];
      if (own_weight[b] <= 0) continue;
      members.push_back({.table = &own[b], .weight = own_weight[b], .rank = static_cast<std::uint32_t>(h)});
    }
    members.push_back({.table = &edge, .weight = edge_weight, .rank = static_cast<std::uint32_t>(of_slot.size())});
    out[slot] = mixer.mix(members);
  }
  return out;
}

// The averaged shifted histograms of one edge (`attempts` in value order): kDaySlots tables, each
// the equal-weight mixture (or quantile average) of the bins (one per resolution and shift) that
// hold its slot.
std::vector<QuantileTable> day_tables(const std::vector<SlotSample>& attempts, const QuantileTable& edge,
                                      const EpisodePriors& priors) {
  const auto& o = priors.options;
  const ShiftedBins bins(attempts, o.day_resolutions);
  return o.duration_mixture ? mixed_day_tables(bins, edge, o.duration_prior)
                            : averaged_day_tables(bins, edge, o.duration_prior);
}

}  // namespace

std::vector<std::vector<QuantileTable>> offline_duration_tables(const std::vector<std::vector<Attempt>>& edges,
                                                                const EpisodePriors& priors) {
  Time newest = Time::min();
  for (const auto& attempts : edges) {
    for (const Attempt& a : attempts) newest = std::max(newest, a.start);
  }
  std::vector<std::vector<SlotSample>> weighted;
  std::vector<Sample> pooled;  // every edge with total weight 1
  for (const auto& attempts : edges) {
    weighted.push_back(weighted_attempts(attempts, priors, newest));
    // In value order from here on: the edge's table and its bins' tables then need no sort.
    std::stable_sort(weighted.back().begin(), weighted.back().end(),
                     [](const SlotSample& a, const SlotSample& b) { return a.sample.value < b.sample.value; });
    double total = 0;
    for (const auto& s : weighted.back()) total += s.sample.weight;
    if (total <= 0) continue;
    for (const auto& s : weighted.back()) pooled.push_back({s.sample.value, s.sample.weight / total});
  }
  const QuantileTable pooled_table = QuantileTable::from_weighted_samples(std::move(pooled));
  std::vector<std::vector<QuantileTable>> out;
  out.reserve(edges.size());
  for (const auto& w : weighted) {
    const auto& o = priors.options;
    const QuantileTable edge = shrunk(samples_of(w), pooled_table, o.duration_prior, o.duration_mixture);
    auto tables = day_tables(w, edge, priors);
    for (auto& t : tables) t = t.rounded(3);
    out.push_back(std::move(tables));
  }
  return out;
}

OfflineDurations::OfflineDurations(const std::vector<std::vector<Attempt>>& edges,
                                   std::shared_ptr<const EpisodePriors> priors)
    : priors_(std::move(priors)) {
  if (auto packed = pack(edges))
    packed_ = std::move(*packed);
  else
    edges_ = edges;
}

std::optional<std::vector<OfflineDurations::PackedEdge>> OfflineDurations::pack(
    const std::vector<std::vector<Attempt>>& edges) {
  std::vector<PackedEdge> out(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    PackedEdge& p = out[e];
    p.attempts.reserve(edges[e].size());
    if (!edges[e].empty()) p.first = edges[e].front().start;
    Time previous = p.first;
    for (const Attempt& a : edges[e]) {
      const std::int64_t step = (a.start - previous).count();
      const std::int64_t duration = (a.end - a.start).count();
      const double seconds = to_seconds(a.end - a.start);
      // Only what unpacked() gives back exactly (the seconds' bits too: -0.0 is not 0.0).
      if (step < INT32_MIN || step > INT32_MAX || duration < 0 || duration >= std::int64_t{kSuccessBit} ||
          std::bit_cast<std::uint64_t>(seconds) != std::bit_cast<std::uint64_t>(a.seconds))
        return std::nullopt;
      p.attempts.push_back(
          {static_cast<std::int32_t>(step), static_cast<std::uint32_t>(duration) | (a.success ? kSuccessBit : 0u)});
      previous = a.start;
    }
  }
  return out;
}

std::vector<std::vector<Attempt>> OfflineDurations::unpacked() const {
  if (packed_.empty()) return std::move(edges_);
  std::vector<std::vector<Attempt>> out(packed_.size());
  for (std::size_t e = 0; e < packed_.size(); ++e) {
    Time start = packed_[e].first;
    out[e].reserve(packed_[e].attempts.size());
    for (const Packed& p : packed_[e].attempts) {
      start += Duration{p.step_ms};
      const Duration d{static_cast<Duration::rep>(p.duration_ms & ~kSuccessBit)};
      out[e].push_back({start, start + d, to_seconds(d), (p.duration_ms & kSuccessBit) != 0});
    }
  }
  return out;
}

OfflineDurations::OfflineDurations(std::vector<std::vector<QuantileTable>> tables) : tables_(std::move(tables)) {
  std::call_once(once_, [] {});
  computed_ = true;
}

const std::vector<QuantileTable>& OfflineDurations::of_edge(std::size_t edge) const {
  std::call_once(once_, [this] {
    tables_ = offline_duration_tables(unpacked(), *priors_);
    packed_ = {};
    edges_ = {};
    priors_.reset();
    computed_ = true;
  });
  return tables_[edge];
}

bool OfflineDurations::computed() const {
  return computed_;
}

std::size_t OfflineDurations::input_bytes() const {
  if (computed_) return 0;
  std::size_t bytes = packed_.capacity() * sizeof(PackedEdge) + edges_.capacity() * sizeof(std::vector<Attempt>);
  for (const PackedEdge& p : packed_) bytes += p.attempts.capacity() * sizeof(Packed);
  for (const auto& e : edges_) bytes += e.capacity() * sizeof(Attempt);
  return bytes;
}

}  // namespace rondo::learn
