#include "decode_util.h"

#include "rondo/core/task_codec.h"

#include <algorithm>
#include <array>
#include <cctype>

#include <fmt/format.h>

namespace rondo::sim::detail {
namespace {

constexpr std::array<std::string_view, 7> kDayNames = {"sun", "mon", "tue", "wed", "thu", "fri", "sat"};
constexpr std::array<std::string_view, 7> kLongDayNames = {"sunday",   "monday", "tuesday", "wednesday",
                                                           "thursday", "friday", "saturday"};

std::string lower(std::string_view text) {
  std::string out;
  for (char c : text) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

Result<std::chrono::weekday> day_named(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(auto name, f.as_string());
  const std::string l = lower(name);
  for (unsigned d = 0; d < 7; ++d) {
    if (l == kDayNames[d] || l == kLongDayNames[d]) return std::chrono::weekday{d};
  }
  return f.error("unknown day '" + name + "' (expected mon, tue, wed, thu, fri, sat or sun)");
}

}  // namespace

Result<double> number_in(const Field& f, double low, double high) {
  RONDO_ASSIGN_OR_RETURN(double v, f.as_number());
  if (v < low || v > high) return f.error(fmt::format("must be from {} to {}, not {}", low, high, v));
  return v;
}

Status read_number(const Field& parent, std::string_view key, double low, double high, double& out) {
  if (auto f = parent.optional(key)) {
    RONDO_ASSIGN_OR_RETURN(out, number_in(*f, low, high));
  }
  return {};
}

Status read_duration(const Field& parent, std::string_view key, Duration& out) {
  if (auto f = parent.optional(key)) {
    RONDO_ASSIGN_OR_RETURN(out, f->as_duration());
  }
  return {};
}

Result<Duration> time_of_day(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(Duration d, f.as_duration());
  if (d > hours(24)) return f.error("a time of day must be from 00:00 to 24:00");
  return d;
}

Result<std::vector<std::chrono::weekday>> days(const Field& f) {
  if (f.is_string()) {
    RONDO_ASSIGN_OR_RETURN(auto word, f.as_string());
    const std::string l = lower(word);
    if (l == "weekdays") return weekdays();
    if (l == "weekends") return weekend_days();
    if (l == "daily") return std::vector<std::chrono::weekday>{};
    auto one = day_named(f);
    if (one) return std::vector<std::chrono::weekday>{*one};
    return f.error("expected a list of days (mon, tue, ...) or one of weekdays, weekends, daily");
  }
  RONDO_ASSIGN_OR_RETURN(auto items, f.items());
  if (items.empty()) return f.error("an empty list of days would never match");
  std::vector<std::chrono::weekday> out;
  for (const auto& item : items) {
    RONDO_ASSIGN_OR_RETURN(auto d, day_named(item));
    if (std::find(out.begin(), out.end(), d) == out.end()) out.push_back(d);
  }
  return out;
}

Result<TimeCondition> time_condition(const Field& f, const TimeZone& zone) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"days", "from", "to", "dates"}));
  TimeCondition c;
  if (auto d = f.optional("days")) {
    RONDO_ASSIGN_OR_RETURN(c.days, days(*d));
  }
  if (auto from = f.optional("from")) {
    RONDO_ASSIGN_OR_RETURN(c.from, time_of_day(*from));
  }
  if (auto to = f.optional("to")) {
    RONDO_ASSIGN_OR_RETURN(c.to, time_of_day(*to));
  }
  if (c.from && c.to && *c.from == *c.to) return f.error_at("to", "an empty span: 'to' equals 'from'");
  if (auto dates = f.optional("dates")) {
    RONDO_ASSIGN_OR_RETURN(auto items, dates->items());
    for (const auto& item : items) {
      RONDO_ASSIGN_OR_RETURN(Time t, item.as_time(&zone));
      c.dates.push_back(zone.local_date(t));
    }
  }
  return c;
}

Result<std::vector<TimeCondition>> time_conditions(const Field& f, const TimeZone& zone) {
  std::vector<TimeCondition> out;
  if (f.is_object()) {  // one condition without the list around it
    RONDO_ASSIGN_OR_RETURN(auto c, time_condition(f, zone));
    out.push_back(std::move(c));
    return out;
  }
  RONDO_ASSIGN_OR_RETURN(auto items, f.items());
  for (const auto& item : items) {
    RONDO_ASSIGN_OR_RETURN(auto c, time_condition(item, zone));
    out.push_back(std::move(c));
  }
  return out;
}

Result<Action> action(const Field& f) { return decode_action(f); }

}  // namespace rondo::sim::detail
