// The offline duration distribution of every edge by local time of day: what an attempt starting at
// t takes when nothing is known about the edge's recent outcomes (EpisodeEdgeModel's offline
// quantiles). Internal to rondo::learn.
//
//   auto tables = offline_duration_tables(per_edge_attempts, priors);   // [edge][15-minute slot]
//   double median = tables[e][priors.day_slot(t)].at(0.5);
//
// Three ideas, each a counterpart of the success model's:
//   - episodes, not attempts: a failed episode's quick retries (sometimes hundreds of sub-second
//     attempts in one storm) share the weight of a typical failed episode, (L − 1) retries with L
//     the edge's retry length (EpisodeEdgeModel::retry_length), so one storm cannot own the table;
//   - recency: each attempt's weight halves every `duration_half_life` before the newest attempt
//     of the fit (edges drift: a door that starts sticking makes long failures common);
//   - time of day without a bin width to pick: per slot, the equal-weight mixture of the
//     distributions of the bins (one per resolution and shift of `day_resolutions`) that hold it;
//     each bin is shrunk towards the edge's distribution (`duration_prior` effective
//     observations), the edge's towards the pooled one. With `duration_mixture = false`, quantile
//     averages (Vincentisation) instead of mixtures.
//
// OfflineDurations keeps a fit's inputs and computes those tables, for all its edges at once, when
// one is first read. The executor's nightly refit plans with p and E[τ] and never reads them (they
// were most of its cost); `rondo learn`, `rondo eval` and the service's edge route do.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "rondo/learn/edge_predictor.h"
#include "rondo/learn/episode_model.h"
#include "rondo/learn/quantile_table.h"

namespace rondo::learn {

// One vector of kDaySlots tables per edge (same order as `edges`, each in start order). `priors`
// must be the pooled priors of the same fit (options, pooled log retry length).
std::vector<std::vector<QuantileTable>> offline_duration_tables(const std::vector<std::vector<Attempt>>& edges,
                                                                const EpisodePriors& priors);

// The tables of offline_duration_tables(edges, *priors), computed on the first read of any edge's
// (bit for bit the same), or tables already known (a loaded model). Thread-safe.
class OfflineDurations {
 public:
  OfflineDurations(const std::vector<std::vector<Attempt>>& edges, std::shared_ptr<const EpisodePriors> priors);
  explicit OfflineDurations(std::vector<std::vector<QuantileTable>> tables);

  // Edge `edge`'s kDaySlots tables. Precondition: edge < the number of edges.
  const std::vector<QuantileTable>& of_edge(std::size_t edge) const;
  // Whether the tables have been computed (or were given).
  bool computed() const;
  // Bytes the kept inputs take until then (their arrays; 0 once computed).
  std::size_t input_bytes() const;

 private:
  mutable std::once_flag once_;
  mutable std::atomic<bool> computed_{false};
  mutable std::vector<std::vector<QuantileTable>> tables_;
  // The fit's inputs, released once the tables are computed. The executor's refit never reads the
  // tables, so a service holds the inputs of its latest refit for good: every attempt of the
  // learning window (14 days), which its memory grew with (docs/operations.md, "Memory over
  // time", session 16). Attempts made from traversals (end = start + whole milliseconds, seconds =
  // to_seconds of them) are kept in 8 bytes instead of an Attempt's 32: the milliseconds since the
  // edge's previous attempt (or its `first`), and the duration's with the outcome in the top bit.
  // unpacked() gives back the same Attempts bit for bit; a fit with any other attempt keeps them
  // as they are (edges_).
  struct Packed {
    std::int32_t step_ms = 0;       // start - the previous attempt's start
    std::uint32_t duration_ms = 0;  // end - start, with kSuccessBit when it succeeded
  };
  static constexpr std::uint32_t kSuccessBit = 1u << 31;
  struct PackedEdge {
    Time first{};
    std::vector<Packed> attempts;
  };
  static std::optional<std::vector<PackedEdge>> pack(const std::vector<std::vector<Attempt>>& edges);
  std::vector<std::vector<Attempt>> unpacked() const;
  mutable std::vector<PackedEdge> packed_;
  mutable std::vector<std::vector<Attempt>> edges_;
  mutable std::shared_ptr<const EpisodePriors> priors_;
};

}  // namespace rondo::learn
