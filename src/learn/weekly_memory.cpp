#include "rondo/learn/weekly_memory.h"

#include <fmt/format.h>

#include <cmath>

#include "histogram_family.h"
#include "json_util.h"

namespace rondo::learn {
namespace {

constexpr const char* kFormat = "rondo.weekly_memory";
constexpr int kVersion = 1;

std::size_t idx(int i) {
  return static_cast<std::size_t>(i);
}

// Counts per slot of the day: the week's counts summed over its seven days.
std::vector<double> fold_days(const std::vector<double>& week) {
  std::vector<double> day(kDaySlots, 0.0);
  for (int w = 0; w < kWeekSlots; ++w) day[idx(w % kDaySlots)] += week[idx(w)];
  return day;
}

double total(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

}  // namespace

std::optional<std::int64_t> WeeklyMemory::next_day() const {
  return next_day_;
}

void WeeklyMemory::forget(double factor) {
  for (auto& [id, e] : edges_) {
    for (double& x : e.successes) x *= factor;
    for (double& x : e.attempts) x *= factor;
    e.sum_d *= factor;
    e.sum_dd *= factor;
  }
}

Status WeeklyMemory::add_day(std::int64_t day, std::span<const Traversal> traversals, const EpisodePriors& priors) {
  if (next_day_ && day < *next_day_)
    return Error::invalid(fmt::format("weekly memory: day {} was added already (the next day is {})", day, *next_day_));
  if (next_day_) {
    const double days = static_cast<double>(day - (*next_day_ - 1));
    forget(std::pow(0.5, days / options_.half_life_days));
  }
  if (!first_day_) first_day_ = day;
  next_day_ = day + 1;
  const std::int64_t block = (day - *first_day_) / 7;

  // Each edge's attempts of the day, told apart into first attempts and retries of a failure.
  std::map<std::string, std::vector<SlotAttempt>> firsts;
  for (const Traversal& t : traversals) {
    Edge& e = edges_[t.edge_id];
    const bool retry = e.has_last && !e.last_success && t.start - e.last_end < priors.options.retry_gap;
    if (!retry) firsts[t.edge_id].push_back(priors.slot_attempt(t.start, t.success));
    e.has_last = true;
    e.last_success = t.success;
    e.last_end = t.start + t.duration;
  }
  for (auto& [id, list] : firsts) score_and_add(edges_.at(id), block, list, priors);
  for (auto& [id, e] : edges_)
    while (!e.block_sums.empty() && e.block_sums.begin()->first <= block - options_.weeks_kept)
      e.block_sums.erase(e.block_sums.begin());
  return {};
}

// Predicts each first attempt from the counts of the days before (as choose_weekly does), then
// adds them to the counts.
void WeeklyMemory::score_and_add(Edge& e, std::int64_t block, std::span<const SlotAttempt> firsts,
                                 const EpisodePriors& priors) {
  const EpisodeOptions& o = priors.options;
  const std::vector<double> day_s = fold_days(e.successes), day_n = fold_days(e.attempts);
  const double rate = (total(day_s) + o.edge_prior * priors.first_success) / (total(day_n) + o.edge_prior);
  const SlotCounts counts{day_s.data(), day_n.data(), e.successes.data(), e.attempts.data()};
  if (e.first_block < 0) e.first_block = block;
  double& week_sum = e.block_sums[block];
  for (const SlotAttempt& f : firsts) {
    double q_day = 0, q_week = 0;
    int n = 0;
    for_each_bin_estimate(f.week_slot, counts, rate, o, true, [&](double d, double w) {
      q_day += d;
      q_week += w;
      ++n;
    });
    q_day = n > 0 ? q_day / n : rate;
    q_week = n > 0 ? q_week / n : rate;
    const double y = f.success ? 1.0 : 0.0;
    const double d = (q_week - y) * (q_week - y) - (q_day - y) * (q_day - y);
    e.sum_d += d;
    e.sum_dd += d * d;
    week_sum += d;
  }
  for (const SlotAttempt& f : firsts) {
    e.attempts[idx(f.week_slot)] += 1;
    e.successes[idx(f.week_slot)] += f.success ? 1 : 0;
  }
}

WeeklyChoice WeeklyMemory::choice(const std::string& edge_id, const EpisodeOptions& options) const {
  WeeklyChoice c;
  const auto it = edges_.find(edge_id);
  if (it == edges_.end()) return c;
  const Edge& e = it->second;
  c.evidence = e.sum_dd > 0 ? -e.sum_d / std::sqrt(e.sum_dd) : 0.0;
  // Whole blocks only: a block that has just begun has one day's noise in it.
  const std::int64_t last_day = *next_day_ - 1;
  const std::int64_t current = (last_day - *first_day_) / 7;
  const bool current_whole = (last_day - *first_day_) % 7 == 6;
  for (const auto& [block, sum] : e.block_sums)
    if (block > e.first_block && sum < 0 && (block < current || current_whole)) ++c.weeks_won;
  c.scored = static_cast<int>(std::lround(total(e.attempts)));
  switch (options.weekly) {
    case WeeklyTerm::kOff: c.weekly = false; break;
    case WeeklyTerm::kOn: c.weekly = true; break;
    case WeeklyTerm::kAuto: c.weekly = c.evidence >= options_.evidence && c.weeks_won >= 2; break;
  }
  return c;
}

std::vector<double> WeeklyMemory::shift(const std::string& edge_id, const EpisodeOptions& options) const {
  const auto it = edges_.find(edge_id);
  if (it == edges_.end()) return {};
  const Edge& e = it->second;
  const std::vector<double> day_s = fold_days(e.successes), day_n = fold_days(e.attempts);
  std::vector<double> out(kWeekSlots, 0.0);
  int histograms = 0;
  for_each_shifted_histogram(options.day_resolutions, [&](int width, int offset) {
    for (int w = 0; w < kWeekSlots; ++w) {
      const int d = w % kDaySlots;
      const int back = (((d - offset) % width) + width) % width;
      double s = 0, n = 0, sw = 0, nw = 0;
      for (int k = 0; k < width; ++k) {
        const auto i = idx((d - back + k + kDaySlots) % kDaySlots);
        s += day_s[i];
        n += day_n[i];
        const auto j = idx((w - back + k + kWeekSlots) % kWeekSlots);
        sw += e.successes[j];
        nw += e.attempts[j];
      }
      if (nw > 0 && n > 0) out[idx(w)] += nw / (nw + options.weekly_prior) * (sw / nw - s / n);
    }
    ++histograms;
  });
  if (histograms > 0)
    for (double& x : out) x /= histograms;
  return out;
}

Json WeeklyMemory::edge_json(const Edge& e) {
  Json slots = Json::array();
  for (int w = 0; w < kWeekSlots; ++w)
    if (e.attempts[idx(w)] != 0 || e.successes[idx(w)] != 0)
      slots.push_back(Json::array({w, e.successes[idx(w)], e.attempts[idx(w)]}));
  Json blocks = Json::array();
  for (const auto& [b, sum] : e.block_sums) blocks.push_back(Json::array({b, sum}));
  return Json{{"slots", std::move(slots)},
              {"sum_d", e.sum_d},
              {"sum_dd", e.sum_dd},
              {"first_block", e.first_block},
              {"blocks", std::move(blocks)},
              {"has_last", e.has_last},
              {"last_success", e.last_success},
              {"last_end_ms", e.last_end.time_since_epoch().count()}};
}

Json WeeklyMemory::to_json() const {
  Json edges = Json::object();
  for (const auto& [id, e] : edges_) edges[id] = edge_json(e);
  return Json{{"format", kFormat},
              {"version", kVersion},
              {"half_life_days", options_.half_life_days},
              {"weeks_kept", options_.weeks_kept},
              {"first_day", first_day_ ? Json(*first_day_) : Json(nullptr)},
              {"next_day", next_day_ ? Json(*next_day_) : Json(nullptr)},
              {"edges", std::move(edges)}};
}

namespace {

Result<std::int64_t> whole(const Json& j, const char* key) {
  RONDO_ASSIGN_OR_RETURN(double v, json_number(j, key));
  if (v != std::floor(v) || std::abs(v) > 9.0e15)
    return Error::invalid(fmt::format("'{}' must be a whole number", key));
  return static_cast<std::int64_t>(v);
}

Result<std::optional<std::int64_t>> optional_day(const Json& j, const char* key) {
  if (!j.contains(key)) return Error::invalid(fmt::format("'{}' is missing", key));
  if (j[key].is_null()) return std::optional<std::int64_t>{};
  RONDO_ASSIGN_OR_RETURN(std::int64_t v, whole(j, key));
  return std::optional<std::int64_t>{v};
}

Result<bool> boolean(const Json& j, const char* key) {
  if (!j.contains(key) || !j[key].is_boolean()) return Error::invalid(fmt::format("'{}' must be true or false", key));
  return j[key].get<bool>();
}

// A [number, ...] row of `n` finite numbers.
Result<std::vector<double>> row(const Json& j, std::size_t n, const char* what) {
  if (!j.is_array() || j.size() != n) return Error::invalid(fmt::format("each of '{}' must hold {} numbers", what, n));
  std::vector<double> out;
  for (const Json& x : j) {
    if (!x.is_number() || !std::isfinite(x.get<double>()))
      return Error::invalid(fmt::format("each of '{}' must hold finite numbers", what));
    out.push_back(x.get<double>());
  }
  return out;
}

}  // namespace

Result<WeeklyMemory::Edge> WeeklyMemory::edge_from_json(const Json& j) {
  if (!j.is_object()) return Error::invalid("an edge must be an object");
  Edge e;
  if (!j.contains("slots") || !j["slots"].is_array()) return Error::invalid("'slots' must be a list");
  for (const Json& s : j["slots"]) {
    RONDO_ASSIGN_OR_RETURN(std::vector<double> v, row(s, 3, "slots"));
    if (v[0] != std::floor(v[0]) || v[0] < 0 || v[0] >= kWeekSlots || v[1] < 0 || v[2] < v[1])
      return Error::invalid("'slots' rows are [slot 0..671, successes, attempts >= successes]");
    e.successes[static_cast<std::size_t>(v[0])] = v[1];
    e.attempts[static_cast<std::size_t>(v[0])] = v[2];
  }
  RONDO_ASSIGN_OR_RETURN(e.sum_d, json_number(j, "sum_d"));
  RONDO_ASSIGN_OR_RETURN(e.sum_dd, json_number(j, "sum_dd"));
  if (e.sum_dd < 0) return Error::invalid("'sum_dd' must not be negative");
  RONDO_ASSIGN_OR_RETURN(e.first_block, whole(j, "first_block"));
  if (!j.contains("blocks") || !j["blocks"].is_array()) return Error::invalid("'blocks' must be a list");
  for (const Json& b : j["blocks"]) {
    RONDO_ASSIGN_OR_RETURN(std::vector<double> v, row(b, 2, "blocks"));
    if (v[0] != std::floor(v[0])) return Error::invalid("'blocks' rows are [block, sum]");
    e.block_sums[static_cast<std::int64_t>(v[0])] = v[1];
  }
  RONDO_ASSIGN_OR_RETURN(e.has_last, boolean(j, "has_last"));
  RONDO_ASSIGN_OR_RETURN(e.last_success, boolean(j, "last_success"));
  RONDO_ASSIGN_OR_RETURN(std::int64_t last_end, whole(j, "last_end_ms"));
  e.last_end = Time{Duration{last_end}};
  return e;
}

Result<WeeklyMemory> WeeklyMemory::from_json(const Json& j) {
  const auto fail = [](const Error& e) { return e.with_context("weekly memory"); };
  if (!j.is_object() || !j.contains("format") || j["format"] != kFormat)
    return Error::invalid(fmt::format("weekly memory: 'format' must be \"{}\"", kFormat));
  auto version = whole(j, "version");
  if (!version) return fail(version.error());
  if (*version != kVersion)
    return Error::invalid(fmt::format("weekly memory: version {} is not known (this build reads {})", *version, kVersion));
  WeeklyMemoryOptions o;
  auto half_life = json_number(j, "half_life_days");
  if (!half_life) return fail(half_life.error());
  auto weeks = whole(j, "weeks_kept");
  if (!weeks) return fail(weeks.error());
  if (!(*half_life > 0) || *weeks < 1 || *weeks > 520)
    return Error::invalid("weekly memory: 'half_life_days' must be positive and 'weeks_kept' 1..520");
  o.half_life_days = *half_life;
  o.weeks_kept = static_cast<int>(*weeks);
  WeeklyMemory m(o);
  auto first = optional_day(j, "first_day");
  if (!first) return fail(first.error());
  auto next = optional_day(j, "next_day");
  if (!next) return fail(next.error());
  if (first->has_value() != next->has_value() || (*first && **next <= **first))
    return Error::invalid("weekly memory: 'first_day' and 'next_day' must both be days, the next after the first, or both null");
  m.first_day_ = *first;
  m.next_day_ = *next;
  if (!j.contains("edges") || !j["edges"].is_object()) return Error::invalid("weekly memory: 'edges' must be an object");
  for (const auto& [id, ej] : j["edges"].items()) {
    auto e = edge_from_json(ej);
    if (!e) return e.error().with_context(fmt::format("weekly memory: edge '{}'", id));
    m.edges_.emplace(id, std::move(*e));
  }
  return m;
}

}  // namespace rondo::learn
