#include "contenders.h"

#include <algorithm>

#include "rondo/learn/episode_model.h"
#include "rondo/learn/fremen.h"
#include "rondo/learn/static_model.h"

namespace rondo::learn {
namespace {

// The authors' filter applied to a stream of attempts (training, then online observations).
class DedupFilter {
 public:
  explicit DedupFilter(bool enabled) : enabled_(enabled) {}
  bool keep(const Attempt& a) {
    if (!enabled_) return true;
    const auto t = static_cast<std::int64_t>(fremen_seconds(a.start));
    if (a.success != last_value_ || t > last_time_ + 60) {
      last_value_ = a.success;
      last_time_ = t;
      return true;
    }
    return false;
  }

 private:
  bool enabled_;
  bool last_value_ = false;
  std::int64_t last_time_ = 0;
};

class StaticPredictor final : public EdgePredictor {
 public:
  StaticPredictor(const std::vector<Attempt>& train, bool dedup) : filter_(dedup) {
    std::vector<double> durations;
    for (const auto& a : train) {
      if (!filter_.keep(a)) continue;
      add(a);
      durations.push_back(a.seconds);
    }
    quantiles_ = QuantileTable::from_samples(std::move(durations));
  }
  void observe(const Attempt& a) override {
    if (filter_.keep(a)) add(a);
  }
  double probability(Time) const override { return n_ > 0 ? successes_ / n_ : 0.5; }
  double expected_seconds(Time) const override { return n_ > 0 ? seconds_ / n_ : 0.0; }
  double quantile_seconds(Time, double q) const override { return quantiles_.at(q); }

 private:
  void add(const Attempt& a) {
    successes_ += a.success ? 1.0 : 0.0;
    seconds_ += a.seconds;
    n_ += 1.0;
  }
  DedupFilter filter_;
  double successes_ = 0, seconds_ = 0, n_ = 0;
  QuantileTable quantiles_;
};

class FremenPredictor final : public EdgePredictor {
 public:
  FremenPredictor(const std::vector<Attempt>& train, bool dedup, int order) : filter_(dedup), order_(order) {
    std::vector<Attempt> kept;
    for (const auto& a : train) {
      if (filter_.keep(a)) kept.push_back(a);
    }
    for (const auto& a : kept) add(a);
    solve();
    std::vector<double> residuals;
    for (const auto& a : kept) residuals.push_back(a.seconds - expected_seconds(a.start));
    residuals_ = QuantileTable::from_samples(std::move(residuals), true);
  }
  void observe(const Attempt& a) override {
    if (!filter_.keep(a)) return;
    add(a);
    dirty_ = true;
  }
  double probability(Time t) const override {
    solve_if_dirty();
    return std::clamp(static_cast<double>(flags_.raw_estimate(fremen_seconds(t))), 0.01, 0.99);
  }
  double expected_seconds(Time t) const override {
    solve_if_dirty();
    return std::max(0.0, static_cast<double>(durations_.raw_estimate(fremen_seconds(t))));
  }
  double quantile_seconds(Time t, double q) const override {
    return std::max(0.0, expected_seconds(t) + residuals_.at(q));
  }

 private:
  void add(const Attempt& a) {
    flag_spectrum_.add(fremen_seconds(a.start), a.success ? 1.0f : 0.0f);
    duration_spectrum_.add(fremen_seconds(a.start), static_cast<float>(a.seconds));
  }
  void solve() const {
    flags_ = flag_spectrum_.solve(order_);
    durations_ = duration_spectrum_.solve(order_);
    dirty_ = false;
  }
  void solve_if_dirty() const {
    if (dirty_) solve();
  }
  DedupFilter filter_;
  int order_;
  FremenSpectrum flag_spectrum_, duration_spectrum_;
  mutable FremenComponents flags_, durations_;
  mutable bool dirty_ = true;
  QuantileTable residuals_;
};

class StaticContender final : public Contender {
 public:
  explicit StaticContender(bool dedup) : dedup_(dedup) {}
  std::string name() const override { return "static"; }
  bool train_dedup() const override { return dedup_; }
  std::vector<std::unique_ptr<EdgePredictor>> fit(const std::vector<EdgeHistory>& edges, bool) const override {
    std::vector<std::unique_ptr<EdgePredictor>> out;
    for (const auto& e : edges) out.push_back(std::make_unique<StaticPredictor>(e.train, dedup_));
    return out;
  }

 private:
  bool dedup_;
};

class FremenContender final : public Contender {
 public:
  FremenContender(int order, bool dedup) : order_(order), dedup_(dedup) {}
  std::string name() const override { return order_ < 0 ? "fremen-auto" : "fremen-" + std::to_string(order_); }
  bool train_dedup() const override { return dedup_; }
  std::vector<std::unique_ptr<EdgePredictor>> fit(const std::vector<EdgeHistory>& edges, bool) const override {
    std::vector<std::unique_ptr<EdgePredictor>> out;
    for (const auto& e : edges) {
      int order = order_;
      if (order < 0) {
        std::vector<BinarySample> flags;
        DedupFilter filter(dedup_);
        for (const auto& a : e.train) {
          if (filter.keep(a)) flags.push_back({a.start, a.success});
        }
        order = choose_fremen_order(flags, 4);
      }
      out.push_back(std::make_unique<FremenPredictor>(e.train, dedup_, order));
    }
    return out;
  }

 private:
  int order_;  // < 0: chosen per edge on a time-ordered split
  bool dedup_;
};

// Offline use of an episode model: never conditioned on the edge's recent outcomes.
class OfflineEpisodePredictor final : public EdgePredictor {
 public:
  explicit OfflineEpisodePredictor(std::shared_ptr<const EpisodeEdgeModel> model) : model_(std::move(model)) {}
  void observe(const Attempt&) override {}
  double probability(Time t) const override { return model_->probability(t); }
  double expected_seconds(Time t) const override { return model_->expected_seconds(t); }
  double quantile_seconds(Time t, double q) const override { return model_->quantile_seconds(t, q); }

 private:
  std::shared_ptr<const EpisodeEdgeModel> model_;
};

class EpisodeContender final : public Contender {
 public:
  EpisodeContender(std::string name, EpisodeOptions options) : name_(std::move(name)), options_(std::move(options)) {}
  std::string name() const override { return name_; }
  std::vector<std::unique_ptr<EdgePredictor>> fit(const std::vector<EdgeHistory>& edges, bool online) const override {
    std::vector<std::vector<Attempt>> attempts;
    for (const auto& e : edges) attempts.push_back(e.train);
    auto fitted = fit_episode_models(attempts, options_);
    std::vector<std::unique_ptr<EdgePredictor>> out;
    for (auto& m : fitted.edges) {
      if (online) {
        out.push_back(std::make_unique<EpisodePredictor>(m));
      } else {
        out.push_back(std::make_unique<OfflineEpisodePredictor>(m));
      }
    }
    return out;
  }

 private:
  std::string name_;
  EpisodeOptions options_;
};

EpisodeOptions with_weekly(EpisodeOptions o, WeeklyTerm weekly) {
  o.weekly = weekly;
  return o;
}

}  // namespace

std::vector<std::unique_ptr<Contender>> all_contenders(const EpisodeOptions& episode) {
  std::vector<std::unique_ptr<Contender>> out;
  for (bool dedup : {false, true}) {
    out.push_back(std::make_unique<StaticContender>(dedup));
    for (int order : {1, 2, 3, -1}) out.push_back(std::make_unique<FremenContender>(order, dedup));
  }
  // "episode": time of day only (the model of issue 3); "episode-week": the time-of-week term
  // chosen per edge (the default of EpisodeOptions since issue 19).
  out.push_back(std::make_unique<EpisodeContender>("episode", with_weekly(episode, WeeklyTerm::kOff)));
  out.push_back(std::make_unique<EpisodeContender>("episode-week", with_weekly(episode, WeeklyTerm::kAuto)));
  return out;
}

}  // namespace rondo::learn
