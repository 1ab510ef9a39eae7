#include "rondo/learn/edge_models.h"

#include <algorithm>
#include <fstream>

#include <fmt/format.h>

#include "json_util.h"
#include "rondo/core/atomic_file.h"
#include "rondo/core/document.h"
#include "rondo/core/utf8.h"
#include "rondo/learn/weekly_memory.h"

namespace rondo::learn {
namespace {

constexpr const char* kFormat = "rondo.edge_models";
constexpr int kVersion = 2;  // 2: time zone, offline duration tables

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

}  // namespace

Result<std::shared_ptr<const EdgeModels>> EdgeModels::fit(std::span<const EdgeSpec> edges,
                                                          std::span<const Traversal> log,
                                                          const EdgeModelsOptions& options) {
  auto out = std::make_shared<EdgeModels>();
  for (const EdgeSpec& spec : edges) {
    if (spec.id.empty()) return Error::invalid("edge models: an edge has an empty id");
    if (!out->index_.emplace(spec.id, out->edges_.size()).second) {
      return Error::invalid("edge models: edge '" + spec.id + "' is listed twice");
    }
    out->edges_.push_back(Entry{spec, 0, nullptr});
  }
  // One attempt list per edge, plus an empty one whose fitted model is the prior of unseen edges.
  std::vector<std::vector<Attempt>> attempts(edges.size() + 1);
  for (const Traversal& t : log) {
    auto it = out->index_.find(t.edge_id);
    if (it == out->index_.end()) continue;
    attempts[it->second].push_back({t.start, t.start + t.duration, to_seconds(t.duration), t.success});
  }
  for (auto& a : attempts) {
    std::stable_sort(a.begin(), a.end(), [](const Attempt& x, const Attempt& y) { return x.start < y.start; });
  }
  EpisodeFit fitted = fit_episode_models(attempts, options.episode);
  out->priors_ = fitted.priors;
  out->prior_rates_ = fitted.edges.back();
  std::vector<double> ratios, durations;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    Entry& e = out->edges_[i];
    e.attempts = static_cast<int>(attempts[i].size());
    if (e.attempts >= options.min_attempts) e.model = fitted.edges[i];
    for (const Attempt& a : attempts[i]) {
      durations.push_back(a.seconds);
      if (e.spec.prior_seconds > 0) ratios.push_back(a.seconds / e.spec.prior_seconds);
    }
  }
  out->have_ratio_ = !ratios.empty();
  out->prior_ratio_mean_ = ratios.empty() ? 1.0 : mean_of(ratios);
  out->prior_ratio_ = QuantileTable::from_samples(std::move(ratios));
  out->pooled_mean_ = mean_of(durations);
  out->pooled_durations_ = QuantileTable::from_samples(std::move(durations));
  return std::shared_ptr<const EdgeModels>(std::move(out));
}

Result<std::size_t> EdgeModels::index_of(std::string_view edge_id) const {
  auto it = index_.find(std::string(edge_id));
  if (it == index_.end()) return Error::not_found("edge models: no edge '" + std::string(edge_id) + "'");
  return it->second;
}

// With a prior time: prior × the pooled actual/prior ratio, or the prior itself when no edge has
// both data and a prior. Without: the pooled durations.
double EdgeModels::prior_quantile(const Entry& e, double q) const {
  if (e.spec.prior_seconds > 0) return e.spec.prior_seconds * (have_ratio_ ? prior_ratio_.at(q) : 1.0);
  return pooled_durations_.at(q);
}

double EdgeModels::prior_mean(const Entry& e) const {
  if (e.spec.prior_seconds > 0) return e.spec.prior_seconds * (have_ratio_ ? prior_ratio_mean_ : 1.0);
  return pooled_mean_;
}

double EdgeModels::success_probability(std::size_t index, Time t) const {
  const Entry& e = edges_[index];
  return e.model ? e.model->probability(t) : prior_rates_->probability(t);
}

double EdgeModels::expected_seconds(std::size_t index, Time t) const {
  const Entry& e = edges_[index];
  return e.model ? e.model->expected_seconds(t) : prior_mean(e);
}

double EdgeModels::quantile_seconds(std::size_t index, Time t, double q) const {
  const Entry& e = edges_[index];
  return e.model ? e.model->quantile_seconds(t, q) : prior_quantile(e, q);
}

Result<EdgeEstimate> EdgeModels::estimate(std::string_view edge_id, Time t, std::span<const double> levels) const {
  auto index = index_of(edge_id);
  if (!index) return index.error();
  EdgeEstimate out{success_probability(*index, t), expected_seconds(*index, t), {}};
  for (double q : levels) {
    if (!(q > 0 && q < 1)) return Error::invalid(fmt::format("edge models: quantile level {} is not in (0, 1)", q));
    out.quantile_seconds.push_back(quantile_seconds(*index, t, q));
  }
  return out;
}

Json EdgeModels::to_json() const {
  Json edges = Json::array();
  for (const Entry& e : edges_) {
    edges.push_back({{"id", e.spec.id},
                     {"prior_seconds", e.spec.prior_seconds},
                     {"attempts", e.attempts},
                     {"model", e.model ? e.model->to_json() : Json(nullptr)}});
  }
  return Json{{"format", kFormat},
              {"version", kVersion},
              {"priors", priors_->to_json()},
              {"prior_rates", prior_rates_->to_json()},
              {"have_ratio", have_ratio_},
              {"prior_ratio", prior_ratio_.to_json()},
              {"prior_ratio_mean", prior_ratio_mean_},
              {"pooled_durations", pooled_durations_.to_json()},
              {"pooled_mean", pooled_mean_},
              {"edges", edges}};
}

Result<std::shared_ptr<const EdgeModels>> EdgeModels::from_json(const Json& j) {
  if (!j.is_object() || j.value("format", std::string()) != kFormat) {
    return Error::invalid(std::string("edge models: not a '") + kFormat + "' document");
  }
  if (j.value("version", 0) != kVersion) {
    return Error::invalid(
        fmt::format("edge models: version {} is not supported (this build reads {})", j.value("version", 0), kVersion));
  }
  auto out = std::make_shared<EdgeModels>();
  if (!j.contains("priors")) return Error::invalid("edge models: missing 'priors'");
  auto priors = EpisodePriors::from_json(j["priors"]);
  if (!priors) return priors.error().with_context("edge models: priors");
  out->priors_ = std::make_shared<const EpisodePriors>(std::move(*priors));
  if (!j.contains("prior_rates")) return Error::invalid("edge models: missing 'prior_rates'");
  auto prior_rates = EpisodeEdgeModel::from_json(j["prior_rates"], out->priors_);
  if (!prior_rates) return prior_rates.error().with_context("edge models: prior_rates");
  out->prior_rates_ = std::make_shared<const EpisodeEdgeModel>(std::move(*prior_rates));
  if (!j.contains("have_ratio") || !j["have_ratio"].is_boolean()) {
    return Error::invalid("edge models: 'have_ratio' must be true or false");
  }
  out->have_ratio_ = j["have_ratio"].get<bool>();
  for (auto [key, table] :
       {std::pair{"prior_ratio", &out->prior_ratio_}, std::pair{"pooled_durations", &out->pooled_durations_}}) {
    if (!j.contains(key)) return Error::invalid(std::string("edge models: missing '") + key + "'");
    auto t = QuantileTable::from_json(j[key]);
    if (!t) return t.error().with_context(std::string("edge models: ") + key);
    *table = *t;
  }
  auto ratio_mean = json_number(j, "prior_ratio_mean");
  auto pooled_mean = json_number(j, "pooled_mean");
  if (!ratio_mean) return ratio_mean.error();
  if (!pooled_mean) return pooled_mean.error();
  out->prior_ratio_mean_ = *ratio_mean;
  out->pooled_mean_ = *pooled_mean;
  if (!j.contains("edges") || !j["edges"].is_array()) return Error::invalid("edge models: 'edges' must be an array");
  for (std::size_t i = 0; i < j["edges"].size(); ++i) {
    const Json& e = j["edges"][i];
    const auto where = fmt::format("edge models: edges[{}]", i);
    if (!e.is_object() || !e.contains("id") || !e["id"].is_string())
      return Error::invalid(where + ": 'id' must be a string");
    Entry entry;
    entry.spec.id = e["id"].get<std::string>();
    auto prior_seconds = json_number(e, "prior_seconds");
    auto attempts = json_number(e, "attempts");
    if (!prior_seconds) return prior_seconds.error().with_context(where);
    if (!attempts) return attempts.error().with_context(where);
    entry.spec.prior_seconds = *prior_seconds;
    entry.attempts = static_cast<int>(*attempts);
    if (e.contains("model") && !e["model"].is_null()) {
      auto model = EpisodeEdgeModel::from_json(e["model"], out->priors_);
      if (!model) return model.error().with_context(where);
      entry.model = std::make_shared<const EpisodeEdgeModel>(std::move(*model));
    }
    if (!out->index_.emplace(entry.spec.id, out->edges_.size()).second) {
      return Error::invalid(where + ": edge '" + entry.spec.id + "' is listed twice");
    }
    out->edges_.push_back(std::move(entry));
  }
  return std::shared_ptr<const EdgeModels>(std::move(out));
}

Status EdgeModels::save(const std::filesystem::path& file) const {
  // The whole text is made before the file is touched: a failure leaves an existing file as it was.
  std::string text;
  try {
    text = to_json().dump() + '\n';
  } catch (const Json::type_error& e) {  // 316: a string that is not UTF-8 (an edge id)
    return Error::invalid(printable_path(file) + ": cannot write the models: " + e.what());
  }
  return write_file_atomically(file, text);
}

Result<std::shared_ptr<const EdgeModels>> EdgeModels::load(const std::filesystem::path& file) {
  auto text = read_text_file(file, Document::kMaxBytes);
  if (!text) return text.error();
  // Through Document, so the models file gets the same limits (size, nesting, values) and UTF-8 check.
  auto doc = Document::parse(*text, DocumentFormat::kJson, printable_path(file));
  if (!doc) return doc.error();
  auto models = from_json(doc->json());
  if (!models) return models.error().with_context(printable_path(file));
  return models;
}

std::shared_ptr<const EdgeModels> EdgeModels::with_weekly(const WeeklyMemory& memory) const {
  auto copy = std::make_shared<EdgeModels>(*this);
  for (Entry& e : copy->edges_) {
    if (!e.model) continue;
    const WeeklyChoice choice = memory.choice(e.spec.id, priors_->options);
    e.model = e.model->with_week_shift(choice, choice.weekly ? memory.shift(e.spec.id, priors_->options)
                                                             : std::vector<double>{});
  }
  return copy;
}

LiveEdgeModels::LiveEdgeModels(std::shared_ptr<const EdgeModels> models) : models_(std::move(models)) {
  live_.reserve(models_->size());
  for (const auto& e : models_->edges_) live_.push_back(e.model ? e.model->stats() : EpisodeStats{});
  slots_.resize(live_.size());
}

bool LiveEdgeModels::observe(const Traversal& t) {
  auto index = models_->index_of(t.edge_id);
  if (!index) return false;
  observe(*index, {t.start, t.start + t.duration, to_seconds(t.duration), t.success});
  return true;
}

void LiveEdgeModels::observe(std::size_t index, const Attempt& a) {
  live_[index].add(a, *models_->priors_);
  slots_[index].clear();
}

const EpisodeEdgeModel& LiveEdgeModels::rates(std::size_t index) const {
  const auto& e = models_->edges_[index];
  return e.model ? *e.model : models_->prior_rates();
}

double LiveEdgeModels::slot_value(std::size_t index, Time t) const {
  std::vector<double>& slots = slots_[index];
  const EpisodeEdgeModel& model = rates(index);
  if (slots.empty()) slots = model.slot_probabilities(live_[index], live_[index].has_last);
  return slots[static_cast<std::size_t>(model.priors()->week_slot(t))];
}

double LiveEdgeModels::success_probability(std::size_t index, Time t) const {
  return rates(index).probability_from(t, live_[index], slot_value(index, t));
}

double LiveEdgeModels::expected_seconds(std::size_t index, Time t) const {
  const auto& e = models_->edges_[index];
  return e.model ? e.model->expected_seconds_from(t, live_[index], slot_value(index, t)) : models_->prior_mean(e);
}

double LiveEdgeModels::quantile_seconds(std::size_t index, Time t, double q) const {
  const auto& e = models_->edges_[index];
  return e.model ? e.model->quantile_seconds(t, q, live_[index], true) : models_->prior_quantile(e, q);
}

}  // namespace rondo::learn
