// The family of shifted time-of-day histograms behind both the success model's q(t) and the
// offline duration tables. Internal to rondo::learn.
//
//   for_each_shifted_histogram(options.day_resolutions, [&](int width, int offset) { ... });
//
// For each resolution that divides 24 (bins per day, so that every shifted bin edge falls on the
// 15-minute slot grid; others are ignored): kHistogramShifts copies whose bin edges move by a
// quarter bin, or one copy for a single bin. f gets the bin width in slots and the copy's offset
// in slots; the bin of slot s is ((s − offset) mod kDaySlots) / width.
//
//   for_each_bin_estimate(week_slot, counts, edge_rate, options, weekly, [&](double q_day, double q_week) { ... });
//
// The first-attempt estimate of each of those histograms at one slot: the day bin shrunk towards
// the edge's rate and, with `weekly`, the same bin on the same day of the week shrunk towards the
// day bin (q_week is q_day otherwise): q_week = q_day + nw / (nw + weekly_prior) · (week bin's rate −
// day bin's rate), clamped to [0, 1], nw the week bin's count.
#pragma once

#include <algorithm>
#include <vector>

#include "rondo/learn/episode_model.h"

namespace rondo::learn {

template <class F>
void for_each_shifted_histogram(const std::vector<int>& day_resolutions, F&& f) {
  for (int bins : day_resolutions) {
    if (bins < 1 || 24 % bins != 0) continue;
    const int width = kDaySlots / bins;
    const int shifts = bins == 1 ? 1 : kHistogramShifts;
    for (int shift = 0; shift < shifts; ++shift) f(width, shift * width / kHistogramShifts);
  }
}

// Counts of first attempts per slot of the day and of the week (EpisodeStats' arrays).
struct SlotCounts {
  const double* day_successes;
  const double* day_attempts;
  const double* week_successes;
  const double* week_attempts;
};

template <class F>
void for_each_bin_estimate(int week_slot, const SlotCounts& c, double edge_rate, const EpisodeOptions& o, bool weekly,
                           F&& f) {
  const int day_slot = week_slot % kDaySlots;
  for_each_shifted_histogram(o.day_resolutions, [&](int width, int offset) {
    // The bin's first slot; 96 is a multiple of width, so the week bin is the day bin on one day.
    const int back = (((day_slot - offset) % width) + width) % width;
    double s = 0, n = 0;
    for (int k = 0; k < width; ++k) {
      const auto i = static_cast<std::size_t>((day_slot - back + k + kDaySlots) % kDaySlots);
      s += c.day_successes[i];
      n += c.day_attempts[i];
    }
    const double q_day = (s + o.bin_prior * edge_rate) / (n + o.bin_prior);
    if (!weekly) return f(q_day, q_day);
    double sw = 0, nw = 0;
    for (int k = 0; k < width; ++k) {
      const auto i = static_cast<std::size_t>((week_slot - back + k + kWeekSlots) % kWeekSlots);
      sw += c.week_successes[i];
      nw += c.week_attempts[i];
    }
    // The week bin's deviation from the day bin, both as observed, shrunk towards none: the term
    // then carries weekly structure only (a correction towards the week bin's own rate would also
    // undo some of the day bin's shrinkage, which looks like an improvement on any series).
    if (nw <= 0) return f(q_day, q_day);
    const double correction = nw / (nw + o.weekly_prior) * (sw / nw - s / n);
    f(q_day, std::clamp(q_day + correction, 0.0, 1.0));
  });
}

}  // namespace rondo::learn
