#include "rondo/sim/parametric_world.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "rondo/map/map_geometry.h"
#include "rondo/sim/rng.h"

namespace rondo::sim {
namespace {

// Independent causes of failure: the attempt succeeds only if none of them strikes.
double combine_failure(double p, double q) {
  return 1.0 - (1.0 - std::clamp(p, 0.0, 1.0)) * (1.0 - std::clamp(q, 0.0, 1.0));
}

Duration scaled(Duration d, double factor) {
  return from_seconds(std::max(0.0, to_seconds(d) * factor));
}

}  // namespace

ParametricWorld::ParametricWorld(const map::TopoMap& map, TimeZone zone, ParametricSpec spec)
    : zone_(std::move(zone)),
      spec_(std::move(spec)),
      effects_of_(map.edge_count()),
      burst_(map.edge_count()) {
  const map::TravelTimeOptions options{.default_speed = spec_.default_speed};
  nominal_.reserve(map.edge_count());
  for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) nominal_.push_back(map::nominal_travel_time(map, e, options));
  spell_key_.reserve(map.edge_count());
  for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) spell_key_.push_back(map.edge(e).door.value_or(map.edge(e).id));
  for (std::size_t i = 0; i < spec_.effects.size(); ++i) {
    for (map::EdgeIndex e : spec_.effects[i].edges) {
      auto& list = effects_of_.at(e);
      if (std::find(list.begin(), list.end(), i) == list.end()) list.push_back(i);
    }
  }
}

// The two-state chain is advanced exactly: with rates a = 1/mean_normal (normal -> blocked) and
// b = 1/mean_blocked, P(blocked after dt) = pi + (x0 - pi) e^{-(a+b) dt}, pi = a / (a + b).
bool ParametricWorld::advance_burst(map::EdgeIndex edge, Time t, Rng& rng) {
  const BurstSpec& b = spec_.bursts;
  BurstState& s = burst_.at(edge);
  if (b.mean_blocked <= Duration{0} || b.mean_normal <= Duration{0}) return false;
  const double a_rate = 1.0 / to_seconds(b.mean_normal);
  const double b_rate = 1.0 / to_seconds(b.mean_blocked);
  const double pi = a_rate / (a_rate + b_rate);
  double p_blocked = pi;  // the first look at an edge: the stationary distribution
  if (s.started) {
    const double dt = std::max(0.0, to_seconds(t - s.last));
    p_blocked = pi + ((s.blocked ? 1.0 : 0.0) - pi) * std::exp(-(a_rate + b_rate) * dt);
  }
  s.blocked = rng.bernoulli(p_blocked);
  s.started = true;
  s.last = std::max(s.last, t);
  return s.blocked;
}

EdgeConditions ParametricWorld::conditions(map::EdgeIndex edge, Time start, Rng& rng) {
  EdgeConditions c;
  c.nominal = nominal_.at(edge);
  c.failure_probability = spec_.failure_probability;
  for (std::size_t i : effects_of_.at(edge)) {
    const EdgeEffect& effect = spec_.effects[i];
    if (!active(effect, start)) continue;
    c.closed = c.closed || effect.closed || (effect.spells && shut(i, edge, start));
    c.failure_probability = combine_failure(c.failure_probability, effect.failure_probability);
    c.duration_factor *= effect.duration_factor;
  }
  c.blocked = advance_burst(edge, start, rng);
  if (c.blocked) {
    c.failure_probability = combine_failure(c.failure_probability, spec_.bursts.failure_probability);
    c.duration_factor *= spec_.bursts.duration_factor;
  }
  if (c.closed) c.failure_probability = 1.0;
  return c;
}

bool ParametricWorld::active(const EdgeEffect& effect, Time t) const {
  return (effect.when.empty() || any_matches(effect.when, zone_, t)) && !any_matches(effect.unless, zone_, t);
}

std::optional<bool> ParametricWorld::closed_at(map::EdgeIndex edge, Time t) const {
  for (std::size_t i : effects_of_.at(edge)) {
    const EdgeEffect& effect = spec_.effects[i];
    if (!active(effect, t)) continue;
    if (effect.closed || (effect.spells && shut(i, edge, t))) return true;
  }
  return false;
}

void ParametricWorld::set_seed(std::uint64_t seed) {
  seed_ = seed;
  spells_.clear();
}

// The day's spells come from a generator seeded by the world's seed, the effect, the door and the
// local day: the first state is drawn from the stationary shut share mean_shut / (mean_open +
// mean_shut), then the spells alternate until the day ends.
bool ParametricWorld::shut(std::size_t effect, map::EdgeIndex edge, Time t) const {
  const ShutSpells& s = *spec_.effects[effect].spells;
  if (s.mean_shut <= Duration{0}) return false;
  if (s.mean_open <= Duration{0}) return true;
  const std::chrono::year_month_day day = zone_.local_date(t);
  SpellDay& d = spells_[{effect, spell_key_[edge]}];
  if (d.day != day || d.changes.empty()) {
    std::uint64_t mix = seed_ ^ (0x5EE11ULL * (effect + 1));
    for (char c : spell_key_[edge]) mix = mix * 1099511628211ULL ^ static_cast<unsigned char>(c);
    mix ^= static_cast<std::uint64_t>(std::chrono::sys_days(day).time_since_epoch().count()) * 0x9E3779B97F4A7C15ULL;
    Rng rng(splitmix64(mix));
    const double open_s = to_seconds(s.mean_open);
    const double shut_s = to_seconds(s.mean_shut);
    d = SpellDay{.day = day, .shut_at_midnight = rng.bernoulli(shut_s / (open_s + shut_s)), .changes = {}};
    const Time midnight = zone_.at(day, Duration{0});
    const Time end = zone_.at(day, hours(24));
    bool shut_now = d.shut_at_midnight;
    for (Time at = midnight; at < end; shut_now = !shut_now) {
      at += from_seconds(rng.exponential(shut_now ? shut_s : open_s));
      d.changes.push_back(at);  // the last one lies at or past the day's end
    }
  }
  const auto changes_before = std::upper_bound(d.changes.begin(), d.changes.end(), t) - d.changes.begin();
  return d.shut_at_midnight != (changes_before % 2 == 1);
}

EdgeSample ParametricWorld::sample_edge(map::EdgeIndex edge, Time start, Rng& rng) {
  const EdgeConditions c = conditions(edge, start, rng);
  const DurationNoise& n = spec_.noise;
  double factor = c.duration_factor * rng.lognormal(0.0, n.sigma);
  if (rng.bernoulli(n.tail_probability)) factor *= std::min(rng.pareto(n.tail_alpha), n.tail_max);
  EdgeSample s;
  s.success = !rng.bernoulli(c.failure_probability);
  if (!s.success) factor *= rng.uniform(spec_.failed.min_factor, spec_.failed.max_factor);
  s.duration = scaled(c.nominal, factor);
  return s;
}

}  // namespace rondo::sim
