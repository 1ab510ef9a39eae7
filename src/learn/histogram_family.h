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
//
//   BinCounts bins(options.day_resolutions);  bins.add(week_slot, success);
//   bins.for_each_bin_estimate(week_slot, edge_rate, options, weekly, f);
//
// The same estimates from counts kept per bin of every histogram as attempts are added (O(1) a
// histogram instead of a sum over the bin's slots). Counts are whole numbers, so both sums are
// exact and the estimates are equal.
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

// One histogram's estimates from its bin's counts: s successes of n first attempts in the day bin,
// sw of nw in the week bin.
template <class F>
void bin_estimate(double s, double n, double sw, double nw, double edge_rate, const EpisodeOptions& o, bool weekly,
                  F&& f) {
  const double q_day = (s + o.bin_prior * edge_rate) / (n + o.bin_prior);
  // The week bin's deviation from the day bin, both as observed, shrunk towards none: the term
  // then carries weekly structure only (a correction towards the week bin's own rate would also
  // undo some of the day bin's shrinkage, which looks like an improvement on any series).
  if (!weekly || nw <= 0) return f(q_day, q_day);
  const double correction = nw / (nw + o.weekly_prior) * (sw / nw - s / n);
  f(q_day, std::clamp(q_day + correction, 0.0, 1.0));
}

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
    double sw = 0, nw = 0;
    if (weekly)
      for (int k = 0; k < width; ++k) {
        const auto i = static_cast<std::size_t>((week_slot - back + k + kWeekSlots) % kWeekSlots);
        sw += c.week_successes[i];
        nw += c.week_attempts[i];
      }
    bin_estimate(s, n, sw, nw, edge_rate, o, weekly, f);
  });
}

class BinCounts {
 public:
  explicit BinCounts(const std::vector<int>& day_resolutions) {
    std::size_t day = 0, week = 0;
    for_each_shifted_histogram(day_resolutions, [&](int width, int offset) {
      histograms_.push_back({width, offset, day, week});
      day += static_cast<std::size_t>(kDaySlots / width);
      week += static_cast<std::size_t>(kWeekSlots / width);
    });
    day_s_.assign(day, 0.0);
    day_n_.assign(day, 0.0);
    week_s_.assign(week, 0.0);
    week_n_.assign(week, 0.0);
  }

  // A first attempt at `week_slot` (0..kWeekSlots-1).
  void add(int week_slot, bool success) {
    for (const Histogram& h : histograms_) {
      const std::size_t d = h.day_bin(week_slot), w = h.week_bin(week_slot);
      day_n_[d] += 1;
      week_n_[w] += 1;
      if (success) {
        day_s_[d] += 1;
        week_s_[w] += 1;
      }
    }
  }

  // What ::for_each_bin_estimate gives from the slot counts of the same attempts, in its order.
  template <class F>
  void for_each_bin_estimate(int week_slot, double edge_rate, const EpisodeOptions& o, bool weekly, F&& f) const {
    for (const Histogram& h : histograms_) {
      const std::size_t d = h.day_bin(week_slot), w = h.week_bin(week_slot);
      bin_estimate(day_s_[d], day_n_[d], weekly ? week_s_[w] : 0.0, weekly ? week_n_[w] : 0.0, edge_rate, o, weekly, f);
    }
  }

 private:
  struct Histogram {
    int width = 1, offset = 0;
    std::size_t day_first = 0, week_first = 0;  // its first bin in the day and week counts
    // The bin of a slot: ((slot − offset) mod slots) / width, for the day and for the week.
    std::size_t day_bin(int week_slot) const {
      return day_first +
             static_cast<std::size_t>(((week_slot % kDaySlots - offset) % kDaySlots + kDaySlots) % kDaySlots / width);
    }
    std::size_t week_bin(int week_slot) const {
      return week_first +
             static_cast<std::size_t>(((week_slot - offset) % kWeekSlots + kWeekSlots) % kWeekSlots / width);
    }
  };
  std::vector<Histogram> histograms_;
  std::vector<double> day_s_, day_n_, week_s_, week_n_;
};

}  // namespace rondo::learn
