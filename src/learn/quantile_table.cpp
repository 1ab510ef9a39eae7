#include "rondo/learn/quantile_table.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rondo::learn {

QuantileTable QuantileTable::from_samples(std::vector<double> values, bool allow_negative) {
  QuantileTable out;
  if (values.empty()) return out;
  if (!allow_negative) {
    for (double& v : values) v = std::max(0.0, v);
  }
  std::sort(values.begin(), values.end());
  const double last = static_cast<double>(values.size() - 1);
  for (int k = 0; k < kKnots; ++k) {
    const double pos = level(k) * last;
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const auto hi = std::min(lo + 1, values.size() - 1);
    const double frac = pos - static_cast<double>(lo);
    out.values_[static_cast<std::size_t>(k)] = values[lo] + frac * (values[hi] - values[lo]);
  }
  // Interpolation of sorted values is already monotone; this guards against rounding.
  for (std::size_t k = 1; k < out.values_.size(); ++k) out.values_[k] = std::max(out.values_[k], out.values_[k - 1]);
  return out;
}

QuantileTable QuantileTable::from_weighted_samples(std::vector<WeightedValue> samples) {
  std::erase_if(samples, [](const WeightedValue& s) { return !(s.weight > 0) || !std::isfinite(s.weight); });
  QuantileTable out;
  if (samples.empty()) return out;
  auto by_value = [](const WeightedValue& a, const WeightedValue& b) { return a.value < b.value; };
  if (!std::is_sorted(samples.begin(), samples.end(), by_value)) std::sort(samples.begin(), samples.end(), by_value);
  // Equal values are one point mass (so the order of ties cannot matter).
  std::size_t kept = 0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (samples[i].value == samples[kept].value) {
      samples[kept].weight += samples[i].weight;
    } else {
      samples[++kept] = samples[i];
    }
  }
  samples.resize(kept + 1);
  double total = 0;
  for (const auto& s : samples) total += s.weight;
  // Walk the samples once: `lo` and `hi` are consecutive share centres around the current level.
  std::size_t i = 0;
  double cumulative = samples[0].weight, centre = samples[0].weight / 2 / total;
  double previous_centre = centre;
  for (int k = 0; k < kKnots; ++k) {
    const double p = level(k);
    while (centre < p && i + 1 < samples.size()) {
      previous_centre = centre;
      ++i;
      centre = (cumulative + samples[i].weight / 2) / total;
      cumulative += samples[i].weight;
    }
    double v = samples[i].value;
    if (centre >= p && i > 0 && centre > previous_centre) {
      const double frac = (p - previous_centre) / (centre - previous_centre);
      v = samples[i - 1].value + std::clamp(frac, 0.0, 1.0) * (samples[i].value - samples[i - 1].value);
    }
    out.values_[static_cast<std::size_t>(k)] = std::max(0.0, v);
  }
  for (std::size_t k = 1; k < out.values_.size(); ++k) out.values_[k] = std::max(out.values_[k], out.values_[k - 1]);
  return out;
}

double QuantileTable::effective_count(const std::vector<WeightedValue>& samples) {
  double sum = 0, squares = 0;
  for (const auto& s : samples) {
    if (!(s.weight > 0) || !std::isfinite(s.weight)) continue;
    sum += s.weight;
    squares += s.weight * s.weight;
  }
  return squares > 0 ? sum * sum / squares : 0.0;
}

QuantileTable QuantileTable::blend(const QuantileTable& a, const QuantileTable& b, double weight) {
  const double w = std::clamp(weight, 0.0, 1.0);
  QuantileTable out;
  for (std::size_t k = 0; k < out.values_.size(); ++k) out.values_[k] = w * a.values_[k] + (1 - w) * b.values_[k];
  for (std::size_t k = 1; k < out.values_.size(); ++k) out.values_[k] = std::max(out.values_[k], out.values_[k - 1]);
  return out;
}

QuantileTable QuantileTable::from_knots(const std::vector<double>& knots) {
  QuantileTable out;
  if (knots.size() != out.values_.size()) return out;
  for (std::size_t k = 0; k < knots.size(); ++k) {
    out.values_[k] = std::isfinite(knots[k]) ? std::max(0.0, knots[k]) : 0.0;
    if (k > 0) out.values_[k] = std::max(out.values_[k], out.values_[k - 1]);
  }
  return out;
}

QuantileTable QuantileTable::average(std::span<const QuantileTable> tables) {
  QuantileTable out;
  if (tables.empty()) return out;
  for (const auto& t : tables) {
    for (std::size_t k = 0; k < out.values_.size(); ++k) out.values_[k] += t.values_[k];
  }
  const auto n = static_cast<double>(tables.size());
  for (std::size_t k = 0; k < out.values_.size(); ++k) out.values_[k] /= n;
  for (std::size_t k = 1; k < out.values_.size(); ++k) out.values_[k] = std::max(out.values_[k], out.values_[k - 1]);
  return out;
}

QuantileTable QuantileTable::mixture(std::span<const QuantileTable> tables, std::span<const double> weights) {
  std::vector<const QuantileTable*> pointers;
  pointers.reserve(tables.size());
  for (const QuantileTable& t : tables) pointers.push_back(&t);
  return mixture(std::span<const QuantileTable* const>(pointers), weights);
}

QuantileTable QuantileTable::mixture(std::span<const QuantileTable* const> tables, std::span<const double> weights) {
  const std::size_t n = std::min(tables.size(), weights.size());
  double total = 0;
  for (std::size_t i = 0; i < n; ++i) total += weights[i] > 0 && std::isfinite(weights[i]) ? weights[i] : 0.0;
  if (!(total > 0)) return QuantileTable{};
  // Every table's knots are a sorted run; merging the runs pairwise (stable: ties keep table, then
  // knot order) sorts the events in O(K log n) for K knots. The buffers are kept per thread: a
  // refit mixes thousands of tables.
  thread_local std::vector<KnotEvent> events, buffer;
  thread_local std::vector<std::size_t> runs, merged;
  thread_local std::vector<double> share;
  events.clear();
  share.assign(n, 0.0);
  runs.assign(1, 0);  // run boundaries in `events`
  for (std::size_t i = 0; i < n; ++i) {
    if (!(weights[i] > 0) || !std::isfinite(weights[i])) continue;
    share[i] = weights[i] / total;
    for (std::size_t k = 0; k < tables[i]->values_.size(); ++k)
      events.push_back({tables[i]->values_[k], static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(k)});
    runs.push_back(events.size());
  }
  buffer.resize(events.size());
  auto by_value = [](const KnotEvent& a, const KnotEvent& b) { return a.value < b.value; };
  while (runs.size() > 2) {
    merged.assign(1, 0);
    for (std::size_t r = 0; r + 1 < runs.size(); r += 2) {
      const auto first = events.begin() + static_cast<std::ptrdiff_t>(runs[r]);
      const auto middle = events.begin() + static_cast<std::ptrdiff_t>(runs[r + 1]);
      const auto end = r + 2 < runs.size() ? events.begin() + static_cast<std::ptrdiff_t>(runs[r + 2]) : middle;
      std::merge(first, middle, middle, end, buffer.begin() + static_cast<std::ptrdiff_t>(runs[r]), by_value);
      merged.push_back(static_cast<std::size_t>(end - events.begin()));
    }
    events.swap(buffer);
    runs.swap(merged);
  }
  return sweep(events, tables, share);
}

// Sweeps the knots of all tables in value order, keeping the mixture's CDF F: between knots it
// rises linearly with the summed slopes of the tables' active segments; at a knot it jumps by the
// table's 0.02 mass when that knot is the first, the last, or equal to the one before (an atom).
// A level is read where F reaches it: inside a segment by linear interpolation, at a jump there.
QuantileTable QuantileTable::sweep(std::span<const KnotEvent> events, std::span<const QuantileTable* const> tables,
                                   std::span<const double> share) {
  QuantileTable out;
  if (events.empty()) return out;
  constexpr double kStep = 0.02;  // probability between consecutive knots (and in each tail)
  constexpr double kTolerance = 1e-12;
  // Knots closer than this (relative) are one atom: a segment of width ~1e-15 (rounding in
  // from_samples) would add and later remove a slope of ~1e13 and ruin the running sum.
  auto atom = [](double a, double b) { return b - a <= 1e-9 * (1.0 + std::abs(b)); };
  const auto last = static_cast<std::size_t>(kKnots - 1);
  std::size_t next = 0;  // next output knot
  double cdf = 0, slope = 0, x = events.front().value;
  for (const KnotEvent& e : events) {
    // Linear rise from x to e.value.
    const double rise = slope * (e.value - x);
    while (next <= last && level(static_cast<int>(next)) <= cdf + rise + kTolerance) {
      const double need = level(static_cast<int>(next)) - cdf;
      out.values_[next++] = slope > 0 ? std::clamp(x + need / slope, x, e.value) : e.value;
    }
    cdf += rise;
    x = e.value;
    const auto& v = tables[e.table]->values_;
    const double w = share[e.table];
    if (e.knot > 0 && !atom(v[e.knot - 1], v[e.knot])) slope -= w * kStep / (v[e.knot] - v[e.knot - 1]);
    if (e.knot == 0 || atom(v[e.knot - 1], v[e.knot])) cdf += w * kStep;
    if (e.knot == last) cdf += w * kStep;
    if (e.knot < last && !atom(v[e.knot], v[e.knot + 1])) slope += w * kStep / (v[e.knot + 1] - v[e.knot]);
    while (next <= last && level(static_cast<int>(next)) <= cdf + kTolerance) out.values_[next++] = x;
  }
  for (; next <= last; ++next) out.values_[next] = x;
  for (std::size_t k = 0; k < out.values_.size(); ++k) out.values_[k] = std::max(0.0, out.values_[k]);
  for (std::size_t k = 1; k < out.values_.size(); ++k) out.values_[k] = std::max(out.values_[k], out.values_[k - 1]);
  return out;
}

QuantileTable QuantileMixer::mix(std::span<const Member> members) {
  // The members of this call by rank; the ranks whose table is the same as last time keep their
  // sorted knots, the others' knots leave and the new members' knots are merged in.
  std::uint32_t ranks = 0;  // one past the highest rank
  double total = 0;
  for (const Member& m : members) {
    if (m.rank + 1 <= ranks || !m.table) {  // ranks not increasing: the plain mixture, in the order given
      std::vector<const QuantileTable*> tables;
      std::vector<double> weights;
      for (const Member& x : members)
        if (x.table) {
          tables.push_back(x.table);
          weights.push_back(x.weight);
        }
      return QuantileTable::mixture(std::span<const QuantileTable* const>(tables), weights);
    }
    ranks = m.rank + 1;
    if (m.weight > 0 && std::isfinite(m.weight)) total += m.weight;
  }
  std::vector<const QuantileTable*> now(std::max<std::size_t>(ranks, table_of_rank_.size()), nullptr);
  for (const Member& m : members)
    if (m.weight > 0 && std::isfinite(m.weight)) now[m.rank] = m.table;
  table_of_rank_.resize(now.size(), nullptr);
  const auto by_order = [](const KnotEvent& a, const KnotEvent& b) {
    if (a.value != b.value) return a.value < b.value;
    if (a.table != b.table) return a.table < b.table;
    return a.knot < b.knot;
  };
  fresh_.clear();
  for (std::uint32_t r = 0; r < now.size(); ++r) {
    if (!now[r] || now[r] == table_of_rank_[r]) continue;
    for (std::size_t k = 0; k < now[r]->values_.size(); ++k)
      fresh_.push_back({now[r]->values_[k], r, static_cast<std::uint32_t>(k)});
  }
  std::sort(fresh_.begin(), fresh_.end(), by_order);
  buffer_.clear();
  auto f = fresh_.begin();
  for (const KnotEvent& e : events_) {
    if (now[e.table] != table_of_rank_[e.table]) continue;  // its member left or changed
    for (; f != fresh_.end() && by_order(*f, e); ++f) buffer_.push_back(*f);
    buffer_.push_back(e);
  }
  buffer_.insert(buffer_.end(), f, fresh_.end());
  events_.swap(buffer_);
  table_of_rank_ = std::move(now);
  if (!(total > 0)) return QuantileTable{};
  share_.assign(table_of_rank_.size(), 0.0);
  for (const Member& m : members)
    if (m.weight > 0 && std::isfinite(m.weight)) share_[m.rank] = m.weight / total;
  return QuantileTable::sweep(events_, table_of_rank_, share_);
}

QuantileTable QuantileTable::rounded(int decimals) const {
  QuantileTable out = *this;
  const double scale = std::pow(10.0, std::clamp(decimals, 0, 9));  // exact for these powers
  for (double& v : out.values_) v = std::round(v * scale) / scale;
  for (std::size_t k = 1; k < out.values_.size(); ++k) out.values_[k] = std::max(out.values_[k], out.values_[k - 1]);
  return out;
}

double QuantileTable::at(double q) const {
  if (!(q > level(0))) return values_.front();
  if (q >= level(kKnots - 1)) return values_.back();
  const double pos = q / 0.02 - 1.0;
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const auto hi = std::min(lo + 1, values_.size() - 1);
  const double frac = pos - static_cast<double>(lo);
  return values_[lo] + frac * (values_[hi] - values_[lo]);
}

Json QuantileTable::to_json() const {
  return Json(values_);
}

Result<QuantileTable> QuantileTable::from_json(const Json& j) {
  if (!j.is_array() || j.size() != static_cast<std::size_t>(kKnots)) {
    return Error::invalid("quantile table: expected an array of " + std::to_string(kKnots) + " numbers");
  }
  QuantileTable out;
  for (std::size_t k = 0; k < j.size(); ++k) {
    if (!j[k].is_number() || !std::isfinite(j[k].get<double>())) {
      return Error::invalid("quantile table: element " + std::to_string(k) + " is not a finite number");
    }
    out.values_[k] = j[k].get<double>();
    if (k > 0 && out.values_[k] < out.values_[k - 1]) {
      return Error::invalid("quantile table: values must be non-decreasing (element " + std::to_string(k) + ")");
    }
  }
  return out;
}

}  // namespace rondo::learn
