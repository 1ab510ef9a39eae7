// Small synthetic series for the learn tests.
#pragma once

#include <vector>

#include "rondo/learn/edge_predictor.h"
#include "rondo/learn/temporal_model.h"

namespace rondo::learn::testing {

// 2014-07-07T00:00:00Z, a Monday.
inline Time monday() {
  return from_unix_seconds(1404691200);
}

// One sample every `step_s` for `days`, true between 08:00 and 20:00 UTC.
inline std::vector<BinarySample> day_night_series(int days, int step_s = 600) {
  std::vector<BinarySample> out;
  for (std::int64_t s = 0; s < std::int64_t{days} * 86400; s += step_s) {
    const auto tod = s % 86400;
    out.push_back({monday() + seconds(s), tod >= 8 * 3600 && tod < 20 * 3600});
  }
  return out;
}

// An edge crossed every 30 minutes for `days`; on even days it fails in bursts: the first
// attempt after 12:00 fails, followed by 5 quick retries (2 s after each failure) that fail too.
inline std::vector<Attempt> bursty_edge(int days) {
  std::vector<Attempt> out;
  for (int d = 0; d < days; ++d) {
    for (int slot = 0; slot < 48; ++slot) {
      Time start = monday() + hours(24 * d) + minutes(30 * slot);
      const bool burst = d % 2 == 0 && slot == 24;
      const int attempts = burst ? 6 : 1;
      for (int k = 0; k < attempts; ++k) {
        const double secs = burst ? 8.0 : 12.0;
        out.push_back({start, start + from_seconds(secs), secs, !burst});
        start = start + from_seconds(secs) + seconds(2);
      }
    }
  }
  return out;
}

// One sample every `step_s` for `days` from monday(), true with probability p(seconds since
// Monday 00:00 UTC, seconds since the first sample); `uniform()` draws from [0, 1).
template <class P, class U>
std::vector<BinarySample> bernoulli_series(int days, int step_s, P&& p, U&& uniform) {
  std::vector<BinarySample> out;
  for (std::int64_t s = 0; s < std::int64_t{days} * 86400; s += step_s) {
    out.push_back({monday() + seconds(s), uniform() < p(s % (7 * 86400), s)});
  }
  return out;
}

// A weekly closure: true with probability `open` except on Wednesdays 13:00-17:00 (never).
inline double wednesday_closure(std::int64_t time_of_week_s, double open) {
  const auto day = time_of_week_s / 86400, tod = time_of_week_s % 86400;
  return day == 2 && tod >= 13 * 3600 && tod < 17 * 3600 ? 0.0 : open;
}

}  // namespace rondo::learn::testing
