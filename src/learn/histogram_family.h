// The family of shifted time-of-day histograms behind both the success model's q(t) and the
// offline duration tables. Internal to rondo::learn.
//
//   for_each_shifted_histogram(options.day_resolutions, [&](int width, int offset) { ... });
//
// For each resolution that divides 24 (bins per day, so that every shifted bin edge falls on the
// 15-minute slot grid; others are ignored): kHistogramShifts copies whose bin edges move by a
// quarter bin, or one copy for a single bin. f gets the bin width in slots and the copy's offset
// in slots; the bin of slot s is ((s − offset) mod kDaySlots) / width.
#pragma once

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

}  // namespace rondo::learn
