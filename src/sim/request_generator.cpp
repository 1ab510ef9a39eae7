#include "rondo/sim/request_generator.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace rondo::sim {
namespace {

std::string request_id(const std::string& prefix, const TimeZone& zone, Time at) {
  const auto date = zone.local_date(at);
  const auto tod = std::chrono::duration_cast<std::chrono::seconds>(zone.time_of_day(at)).count();
  return fmt::format("{}-{:04}-{:02}-{:02}-{:02}{:02}{:02}", prefix, static_cast<int>(date.year()),
                     static_cast<unsigned>(date.month()), static_cast<unsigned>(date.day()), tod / 3600,
                     tod / 60 % 60, tod % 60);
}

Time ceil_to_second(Time t) { return std::chrono::ceil<std::chrono::seconds>(t); }

}  // namespace

Request RequestGenerator::make(Time at, Rng& rng) const {
  double total = 0;
  for (const auto& t : spec_.templates) total += t.weight;
  double pick = rng.uniform() * total;
  const RequestTemplate* chosen = &spec_.templates.back();
  for (const auto& t : spec_.templates) {
    if (pick < t.weight) {
      chosen = &t;
      break;
    }
    pick -= t.weight;
  }
  Request r{at, chosen->task};
  r.task.id = request_id(spec_.id_prefix, zone_, at);
  r.task.kind = TaskKind::kOnDemand;
  r.task.window.reset();
  r.task.start_node = chosen->places[rng.uniform_int(chosen->places.size())];
  return r;
}

std::vector<Request> RequestGenerator::between(Time from, Time to, Rng& rng) const {
  std::vector<Request> out;
  if (from >= to || spec_.per_day <= 0 || spec_.templates.empty()) return out;
  Time last = from - seconds(1);
  for (auto day = std::chrono::sys_days(zone_.local_date(from)); zone_.at(day, Duration{0}) < to;
       day += std::chrono::days(1)) {
    const std::chrono::year_month_day date{day};
    if (!spec_.days.empty() &&
        std::find(spec_.days.begin(), spec_.days.end(), std::chrono::weekday(day)) == spec_.days.end()) {
      continue;
    }
    const Time open = zone_.at(date, spec_.from);
    const Time close = zone_.at(date, spec_.to);
    const Time lo = std::max(open, from);
    const Time hi = std::min(close, to);
    if (lo >= hi) continue;
    // Arrivals of a Poisson process with per_day arrivals per office day: exponential gaps.
    const double mean_gap_s = to_seconds(close - open) / spec_.per_day;
    for (Time t = lo + from_seconds(rng.exponential(mean_gap_s)); t < hi;
         t += from_seconds(rng.exponential(mean_gap_s))) {
      Time at = std::max(ceil_to_second(t), last + seconds(1));
      if (at >= hi) break;
      out.push_back(make(at, rng));
      last = at;
    }
  }
  return out;
}

}  // namespace rondo::sim
