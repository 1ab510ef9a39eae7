#include "rondo/schedule/travel_oracle.h"

#include <algorithm>

#include <fmt/format.h>

namespace rondo::schedule {

Result<MatrixTravel> MatrixTravel::create(std::size_t size, std::vector<Duration> row_major) {
  if (row_major.size() != size * size)
    return Error::invalid(fmt::format("travel matrix: expected {} entries, got {}", size * size,
                                      row_major.size()));
  for (std::size_t i = 0; i < row_major.size(); ++i)
    if (row_major[i] < Duration{0})
      return Error::invalid(fmt::format("travel matrix: entry ({}, {}) is negative", i / size, i % size));
  return MatrixTravel(size, std::move(row_major));
}

Result<PiecewiseLinearTravel> PiecewiseLinearTravel::create(std::size_t size,
                                                            std::vector<Breakpoint> breakpoints) {
  if (breakpoints.empty()) return Error::invalid("time-dependent travel: no breakpoints");
  for (std::size_t b = 0; b < breakpoints.size(); ++b) {
    const auto& m = breakpoints[b].row_major;
    if (m.size() != size * size)
      return Error::invalid(fmt::format("time-dependent travel: breakpoint {} has {} entries, expected {}",
                                        b, m.size(), size * size));
    if (b > 0) {
      const Duration span = breakpoints[b].at - breakpoints[b - 1].at;
      if (span <= Duration{0})
        return Error::invalid(fmt::format("time-dependent travel: breakpoint {} is not after the previous one", b));
      for (std::size_t i = 0; i < m.size(); ++i)
        if (breakpoints[b - 1].row_major[i] - m[i] > span)
          return Error::invalid(fmt::format(
              "time-dependent travel: entry ({}, {}) falls faster than time between breakpoints {} and {} "
              "(leaving later would arrive earlier)", i / size, i % size, b - 1, b));
    }
    for (Duration d : m)
      if (d < Duration{0}) return Error::invalid("time-dependent travel: negative entry");
  }
  PiecewiseLinearTravel t;
  t.size_ = size;
  t.lower_ = breakpoints.front().row_major;
  for (const auto& b : breakpoints)
    for (std::size_t i = 0; i < t.lower_.size(); ++i) t.lower_[i] = std::min(t.lower_[i], b.row_major[i]);
  t.points_ = std::move(breakpoints);
  return t;
}

Duration PiecewiseLinearTravel::travel(LocationIndex from, LocationIndex to, Time depart) const {
  const std::size_t i = from * size_ + to;
  if (depart <= points_.front().at) return points_.front().row_major[i];
  if (depart >= points_.back().at) return points_.back().row_major[i];
  auto next = std::upper_bound(points_.begin(), points_.end(), depart,
                               [](Time t, const Breakpoint& b) { return t < b.at; });
  auto prev = std::prev(next);
  const auto span = (next->at - prev->at).count();
  const auto into = (depart - prev->at).count();
  const auto a = prev->row_major[i].count();
  const auto b = next->row_major[i].count();
  // Rounded down in favour of... exactly linear in integer milliseconds; FIFO holds since
  // |slope| <= 1 keeps the floor monotone in depart + travel.
  return Duration{a + (b - a) * into / span};
}

}  // namespace rondo::schedule
