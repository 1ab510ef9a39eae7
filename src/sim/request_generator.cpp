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
  Request r{at, chosen->task, std::nullopt};
  r.task.id = request_id(spec_.id_prefix, zone_, at);
  r.task.kind = TaskKind::kOnDemand;
  r.task.window.reset();
  r.task.start_node = chosen->places[rng.uniform_int(chosen->places.size())];
  if (chosen->deliver) make_delivery(*chosen->deliver, r, rng);
  return r;
}

void RequestGenerator::make_delivery(const DeliveryTemplate& d, Request& r, Rng& rng) const {
  const std::string job = r.task.id;
  const std::string object = d.objects[rng.uniform_int(d.objects.size())];
  std::vector<std::string> to;
  for (const std::string& n : d.to)
    if (n != r.task.start_node) to.push_back(n);
  if (to.empty()) to = d.to;  // decode() makes sure there is another place
  Task& pickup = r.task;
  pickup.kind = TaskKind::kStandard;
  pickup.window = TimeWindow{r.at, r.at + d.within};
  pickup.id = job + "-pickup";
  pickup.activity = fmt::format("collect the {} at {}", object, pickup.start_node);
  pickup.actions = {Action{.name = "load", .args = {{"object", object}}}};
  Task drop = pickup;
  drop.id = job + "-drop";
  drop.start_node = to[rng.uniform_int(to.size())];
  drop.activity = fmt::format("bring the {} to {}", object, drop.start_node);
  drop.actions = {Action{.name = "unload", .args = {{"object", object}}}};
  pickup.delivery = Delivery{.job = job, .role = DeliveryRole::kPickup, .object = object, .appearance = object, .load = 1};
  drop.delivery = pickup.delivery;
  drop.delivery->role = DeliveryRole::kDrop;
  r.drop = std::move(drop);
}

std::vector<Task> Request::tasks() const {
  std::vector<Task> out{task};
  if (drop) out.push_back(*drop);
  return out;
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
