// The model families that `evaluate_edges` compares, each able to fit one EdgePredictor per edge
// from the training attempts of all edges (so a family may pool across edges).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rondo/learn/edge_predictor.h"
#include "rondo/learn/episode_model.h"

namespace rondo::learn {

struct EdgeHistory {
  std::string id;
  std::vector<Attempt> train;  // in start order
};

class Contender {
 public:
  virtual ~Contender() = default;
  virtual std::string name() const = 0;
  // True when training flags go through the FreMEn authors' de-duplication.
  virtual bool train_dedup() const { return false; }
  // One predictor per edge, same order as `edges`, already fitted on `train`. `online`: the
  // predictors will be told every outcome as it becomes known (some families predict differently).
  virtual std::vector<std::unique_ptr<EdgePredictor>> fit(const std::vector<EdgeHistory>& edges, bool online) const = 0;
};

// static, fremen-1..3 and fremen-auto, without and with de-duplication, then our models (fitted
// with `episode`): "episode" with time of day only, "episode-week" with the time-of-week term
// chosen per edge (whatever `episode.weekly` says).
std::vector<std::unique_ptr<Contender>> all_contenders(const EpisodeOptions& episode = {});

}  // namespace rondo::learn
