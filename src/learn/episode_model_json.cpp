// JSON form of the episode model: priors (once per fitted set), each edge's statistics and tables.
#include <algorithm>
#include <cmath>

#include "json_util.h"
#include "offline_durations.h"
#include "rondo/learn/episode_model.h"

namespace rondo::learn {
namespace {

std::size_t idx(int i) {
  return static_cast<std::size_t>(i);
}

template <std::size_t N>
Json array_json(const std::array<double, N>& a) {
  return Json(std::vector<double>(a.begin(), a.end()));
}

template <std::size_t N>
Status read_array(const Json& j, const char* key, std::array<double, N>& out) {
  auto v = json_numbers(j, key);
  if (!v) return v.error();
  if (v->size() != N)
    return Error::invalid(std::string("model: '") + key + "' must have " + std::to_string(N) + " numbers");
  std::copy(v->begin(), v->end(), out.begin());
  return {};
}

const char* weekly_name(WeeklyTerm w) {
  switch (w) {
    case WeeklyTerm::kOff:
      return "off";
    case WeeklyTerm::kOn:
      return "on";
    case WeeklyTerm::kAuto:
      break;
  }
  return "auto";
}

}  // namespace

Json EpisodePriors::to_json() const {
  const auto& o = options;
  return Json{{"retry_gap_s", to_seconds(o.retry_gap)},
              {"time_zone", o.zone.name()},
              {"duration_half_life_s", to_seconds(o.duration_half_life)},
              {"bin_prior", o.bin_prior},
              {"edge_prior", o.edge_prior},
              {"length_prior", o.length_prior},
              {"state_prior", o.state_prior},
              {"pooled_state_prior", o.pooled_state_prior},
              {"duration_prior", o.duration_prior},
              {"day_resolutions", o.day_resolutions},
              {"duration_bins", o.duration_bins},
              {"duration_mixture", o.duration_mixture},
              {"weekly", weekly_name(o.weekly)},
              {"weekly_evidence", o.weekly_evidence},
              {"weekly_prior", o.weekly_prior},
              {"first_success", first_success},
              {"log_retry_length", log_retry_length},
              {"state_successes", array_json(state_successes)},
              {"state_attempts", array_json(state_attempts)},
              {"retry_ratio", retry_ratio.to_json()},
              {"retry_intercept", retry_intercept},
              {"retry_slope", retry_slope}};
}

Result<EpisodePriors> EpisodePriors::from_json(const Json& j) {
  EpisodePriors p;
  struct NumberField {
    const char* key;
    double* out;
  };
  double retry_gap_s = 0, half_life_s = 0, duration_bins = 0;
  const NumberField numbers[] = {{"retry_gap_s", &retry_gap_s},
                                 {"duration_half_life_s", &half_life_s},
                                 {"bin_prior", &p.options.bin_prior},
                                 {"edge_prior", &p.options.edge_prior},
                                 {"length_prior", &p.options.length_prior},
                                 {"state_prior", &p.options.state_prior},
                                 {"pooled_state_prior", &p.options.pooled_state_prior},
                                 {"duration_prior", &p.options.duration_prior},
                                 {"duration_bins", &duration_bins},
                                 {"first_success", &p.first_success},
                                 {"log_retry_length", &p.log_retry_length},
                                 {"retry_intercept", &p.retry_intercept},
                                 {"retry_slope", &p.retry_slope}};
  for (const auto& f : numbers) {
    auto v = json_number(j, f.key);
    if (!v) return v.error();
    *f.out = *v;
  }
  if (duration_bins < 1 || duration_bins > 1440 || duration_bins != std::floor(duration_bins)) {
    return Error::invalid("model: 'duration_bins' must be a whole number in 1..1440");
  }
  p.options.duration_bins = static_cast<int>(duration_bins);
  auto resolutions = json_numbers(j, "day_resolutions");
  if (!resolutions) return resolutions.error();
  p.options.day_resolutions.clear();
  for (double r : *resolutions) {
    if (r < 1 || r > 24 || r != std::floor(r) || 24 % static_cast<int>(r) != 0) {
      return Error::invalid("model: 'day_resolutions' must hold divisors of 24");
    }
    p.options.day_resolutions.push_back(static_cast<int>(r));
  }
  // Optional: files written before it existed used quantile averaging.
  p.options.duration_mixture = false;
  if (j.contains("duration_mixture")) {
    if (!j["duration_mixture"].is_boolean()) return Error::invalid("model: 'duration_mixture' must be true or false");
    p.options.duration_mixture = j["duration_mixture"].get<bool>();
  }
  // Optional: files written before the time-of-week term had none.
  p.options.weekly = WeeklyTerm::kOff;
  if (j.contains("weekly")) {
    const Json& w = j["weekly"];
    if (!w.is_string() || (w != "off" && w != "auto" && w != "on")) {
      return Error::invalid("model: 'weekly' must be \"off\", \"auto\" or \"on\"");
    }
    p.options.weekly = w == "off" ? WeeklyTerm::kOff : w == "on" ? WeeklyTerm::kOn : WeeklyTerm::kAuto;
    for (auto [key, out] : {std::pair{"weekly_evidence", &p.options.weekly_evidence},
                            std::pair{"weekly_prior", &p.options.weekly_prior}}) {
      auto v = json_number(j, key);
      if (!v) return v.error();
      *out = *v;
    }
  }
  p.options.retry_gap = from_seconds(retry_gap_s);
  p.options.duration_half_life = from_seconds(half_life_s);
  if (!j.contains("time_zone") || !j["time_zone"].is_string()) {
    return Error::invalid("model: 'time_zone' must be an IANA zone name such as \"Europe/London\"");
  }
  auto zone = TimeZone::named(j["time_zone"].get<std::string>());
  if (!zone) return Error::invalid("model: 'time_zone': " + zone.error().message);
  p.options.zone = *zone;
  if (auto s = read_array(j, "state_successes", p.state_successes); !s) return s.error();
  if (auto s = read_array(j, "state_attempts", p.state_attempts); !s) return s.error();
  if (!j.contains("retry_ratio")) return Error::invalid("model: missing 'retry_ratio'");
  auto ratio = QuantileTable::from_json(j["retry_ratio"]);
  if (!ratio) return ratio.error();
  p.retry_ratio = *ratio;
  return p;
}

Json EpisodeStats::to_json() const {
  return Json{{"first_successes", first_successes},
              {"first_attempts", first_attempts},
              {"week_successes", week_successes},
              {"week_attempts", week_attempts},
              {"failed_episodes", failed_episodes},
              {"log_length_sum", log_length_sum},
              {"state_successes", array_json(state_successes)},
              {"state_attempts", array_json(state_attempts)},
              {"has_last", has_last},
              {"last_success", last_success},
              {"last_end_ms", last_end.time_since_epoch().count()},
              {"last_seconds", last_seconds},
              {"episode_length", episode_length},
              {"episode_first_failed", episode_first_failed}};
}

Result<EpisodeStats> EpisodeStats::from_json(const Json& j) {
  EpisodeStats s;
  auto fs = json_numbers(j, "first_successes");
  auto fa = json_numbers(j, "first_attempts");
  if (!fs) return fs.error();
  if (!fa) return fa.error();
  if (fs->size() != idx(kDaySlots) || fa->size() != idx(kDaySlots)) {
    return Error::invalid("model: 'first_successes'/'first_attempts' must have one number per 15 minutes of the day");
  }
  s.first_successes = *fs;
  s.first_attempts = *fa;
  // Optional: files written before the time-of-week term kept day counts only (their models have
  // no weekly term, so the week counts only start with new observations).
  if (j.contains("week_successes") || j.contains("week_attempts")) {
    auto ws = json_numbers(j, "week_successes");
    auto wa = json_numbers(j, "week_attempts");
    if (!ws) return ws.error();
    if (!wa) return wa.error();
    if (ws->size() != idx(kWeekSlots) || wa->size() != idx(kWeekSlots)) {
      return Error::invalid("model: 'week_successes'/'week_attempts' must have one number per 15 minutes of the week");
    }
    s.week_successes = *ws;
    s.week_attempts = *wa;
  }
  auto failed = json_number(j, "failed_episodes");
  auto log_sum = json_number(j, "log_length_sum");
  auto last_end = json_number(j, "last_end_ms");
  auto last_seconds = json_number(j, "last_seconds");
  auto length = json_number(j, "episode_length");
  if (!failed) return failed.error();
  if (!log_sum) return log_sum.error();
  if (!last_end) return last_end.error();
  if (!last_seconds) return last_seconds.error();
  if (!length) return length.error();
  s.failed_episodes = *failed;
  s.log_length_sum = *log_sum;
  s.last_end = Time{Duration{static_cast<std::int64_t>(*last_end)}};
  s.last_seconds = *last_seconds;
  s.episode_length = static_cast<int>(*length);
  for (auto [key, out] : {std::pair{"has_last", &s.has_last}, std::pair{"last_success", &s.last_success},
                          std::pair{"episode_first_failed", &s.episode_first_failed}}) {
    if (!j.contains(key) || !j[key].is_boolean())
      return Error::invalid(std::string("model: '") + key + "' must be true or false");
    *out = j[key].get<bool>();
  }
  if (auto st = read_array(j, "state_successes", s.state_successes); !st) return st.error();
  if (auto st = read_array(j, "state_attempts", s.state_attempts); !st) return st.error();
  return s;
}

Json EpisodeEdgeModel::to_json() const {
  Json success = Json::array(), failure = Json::array(), offline = Json::array();
  for (const auto& t : durations_.success) success.push_back(t.to_json());
  for (const auto& t : durations_.failure) failure.push_back(t.to_json());
  for (const auto& t : offline_tables()) offline.push_back(t.to_json());
  return Json{{"stats", stats_.to_json()},
              {"weekly", weekly_.to_json()},
              {"durations",
               {{"success", success},
                {"failure", failure},
                {"offline", offline},
                {"success_mean", durations_.success_mean},
                {"failure_mean", durations_.failure_mean}}}};
}

Result<EpisodeEdgeModel> EpisodeEdgeModel::from_json(const Json& j, std::shared_ptr<const EpisodePriors> priors) {
  if (!j.is_object() || !j.contains("stats") || !j.contains("durations")) {
    return Error::invalid("model: an episode edge needs 'stats' and 'durations'");
  }
  auto stats = EpisodeStats::from_json(j["stats"]);
  const auto bins = idx(priors->options.duration_bins);
  if (!stats) return stats.error();
  const Json& d = j["durations"];
  DurationTables tables;
  for (auto [key, out] : {std::pair{"success", &tables.success}, std::pair{"failure", &tables.failure}}) {
    if (!d.contains(key) || !d[key].is_array() || d[key].size() != bins) {
      return Error::invalid(std::string("model: 'durations.") + key + "' must have one table per day bin");
    }
    for (const Json& t : d[key]) {
      auto table = QuantileTable::from_json(t);
      if (!table) return table.error();
      out->push_back(*table);
    }
  }
  if (!d.contains("offline") || !d["offline"].is_array() || d["offline"].size() != idx(kDaySlots)) {
    return Error::invalid("model: 'durations.offline' must have one table per 15 minutes of the day");
  }
  std::vector<QuantileTable> offline;
  for (const Json& t : d["offline"]) {
    auto table = QuantileTable::from_json(t);
    if (!table) return table.error().with_context("durations.offline");
    offline.push_back(*table);
  }
  tables.offline =
      std::make_shared<const OfflineDurations>(std::vector<std::vector<QuantileTable>>{std::move(offline)});
  auto success_mean = json_numbers(d, "success_mean");
  auto failure_mean = json_numbers(d, "failure_mean");
  if (!success_mean) return success_mean.error();
  if (!failure_mean) return failure_mean.error();
  if (success_mean->size() != bins || failure_mean->size() != bins) {
    return Error::invalid("model: duration means must have one number per duration bin");
  }
  tables.success_mean = *success_mean;
  tables.failure_mean = *failure_mean;
  WeeklyChoice weekly;  // optional: none in files written before the time-of-week term
  if (j.contains("weekly")) {
    auto w = WeeklyChoice::from_json(j["weekly"]);
    if (!w) return w.error();
    weekly = *w;
    if (weekly.weekly && !j["stats"].contains("week_attempts")) {
      return Error::invalid("model: an edge with a weekly term needs 'stats.week_attempts'");
    }
  }
  return EpisodeEdgeModel(std::move(priors), std::move(*stats), std::move(tables), weekly);
}

Json EpisodeBinaryModel::to_json() const {
  return Json{{"type", "episode"}, {"priors", model_->priors()->to_json()}, {"edge", model_->to_json()}};
}

}  // namespace rondo::learn
