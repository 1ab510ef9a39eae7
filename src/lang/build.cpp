#include "build.h"

#include <fmt/format.h>

#include "rondo/lang/words.h"

namespace rondo::lang::detail {
namespace {

constexpr Duration kAtSlack = minutes(30);  // "at 09:00" means a window [09:00, 09:30]

std::string local_minute(const TimeZone& zone, Time t) {
  return zone.format_local(t).substr(0, 16);
}

std::string date_text(std::chrono::year_month_day d) {
  return fmt::format("{:04}-{:02}-{:02}", static_cast<int>(d.year()), static_cast<unsigned>(d.month()),
                     static_cast<unsigned>(d.day()));
}

// The daily window the time words give, as times since local midnight: [00:00, 24:00] by default.
Result<std::pair<Duration, Duration>> daily_window(const Timing& t) {
  if (t.at && (t.between || t.before || t.after)) {
    return Error::invalid("'at' cannot go with 'between', 'before' or 'after': give one of them");
  }
  if (t.between && (t.before || t.after)) {
    return Error::invalid("'between' cannot go with 'before' or 'after': give one of them");
  }
  if (t.at) return std::pair<Duration, Duration>{*t.at, *t.at + kAtSlack};
  if (t.between) return *t.between;
  const Duration from = t.after.value_or(Duration{0});
  const Duration to = t.before.value_or(hours(24));
  if (to <= from) {
    return Error::invalid(
        fmt::format("'after {}' and 'before {}' leave no time", format_time_of_day(from), format_time_of_day(to)));
  }
  return std::pair<Duration, Duration>{from, to};
}

// The local date the task is for: today, tomorrow, the next such weekday (today included), a date.
Result<std::chrono::year_month_day> day_of(const Timing& t, const CommandContext& ctx) {
  const int named = (t.day_offset ? 1 : 0) + (t.on_weekday ? 1 : 0) + (t.on_date ? 1 : 0);
  if (named > 1) return Error::invalid("name the day once: 'today', 'tomorrow', 'on friday' or 'on 2026-11-24'");
  const auto today = ctx.zone.local_date(ctx.now);
  const std::chrono::sys_days base{today};
  if (t.day_offset) return std::chrono::year_month_day{base + std::chrono::days{*t.day_offset}};
  if (t.on_weekday) {
    const auto ahead = (*t.on_weekday - std::chrono::weekday{base}).count();
    return std::chrono::year_month_day{base + std::chrono::days{ahead}};
  }
  if (t.on_date) {
    if (std::chrono::sys_days{*t.on_date} < base) {
      return Error::invalid(fmt::format("{} is past (today is {})", date_text(*t.on_date), date_text(today)));
    }
    return *t.on_date;
  }
  return today;
}

}  // namespace

std::string id_tag(const CommandContext& ctx) {
  return local_minute(ctx.zone, ctx.now);
}

Status apply_one_off(const Timing& t, const CommandContext& ctx, Task& task) {
  if (t.now) {
    if (t.day_offset || t.on_weekday || t.on_date || t.before || t.after || t.at || t.between || t.in) {
      return Error::invalid("'now' cannot go with a day or a time: drop one of them");
    }
    task.kind = TaskKind::kOnDemand;
    task.window.reset();
    return {};
  }
  Time opens{};
  Time closes{};
  if (t.in) {
    // "in 10 minutes": a time from now, as "at" that time; it may fall on another day.
    if (t.day_offset || t.on_weekday || t.on_date || t.before || t.after || t.at || t.between) {
      return Error::invalid(fmt::format("'in {}' is a time from now: it cannot go with a day or another time; give one "
                                        "of them",
                                        format_duration(*t.in)));
    }
    opens = ctx.now + *t.in;
    closes = opens + kAtSlack;
  } else {
    RONDO_ASSIGN_OR_RETURN(auto day, day_of(t, ctx));
    RONDO_ASSIGN_OR_RETURN(auto span, daily_window(t));
    opens = ctx.zone.at(day, span.first);
    closes = ctx.zone.at(day, span.second);
  }
  if (closes <= ctx.now) {
    return Error::invalid(
        fmt::format("the time asked for ends at {}, which is past (it is {}); say 'tomorrow' or "
                    "'on DAY' for a later day",
                    local_minute(ctx.zone, closes), local_minute(ctx.zone, ctx.now)));
  }
  const Time release = std::max(opens, ctx.now);
  if (closes - release < task.duration) {
    return Error::invalid(fmt::format("from {} to {} is too short for the {} it takes", local_minute(ctx.zone, release),
                                      local_minute(ctx.zone, closes), format_duration(task.duration)));
  }
  task.kind = TaskKind::kStandard;
  task.window = TimeWindow{release, closes};
  return {};
}

Result<Routine> make_routine(const Timing& t, const CommandContext& ctx, const Job& job, int priority) {
  if (t.now || t.day_offset || t.on_date || t.in) {
    return Error::invalid(
        "a repeated task ('every ...') cannot also be for 'now', 'today', 'tomorrow', a date or a time from now "
        "('in ...')");
  }
  Routine r;
  r.name = job.verb + "-" + slug(job.node);
  r.task.activity = job.activity;
  r.task.duration = t.duration.value_or(job.duration);
  r.task.priority = priority;
  r.task.start_node = job.node;
  r.task.actions = {Action{job.verb, {}}};
  RONDO_ASSIGN_OR_RETURN(auto span, daily_window(t));
  r.window_start = span.first;
  r.window_end = span.second;
  r.every = t.every;
  if (t.days && t.on_weekday) return Error::invalid("name the days once ('every weekday' or 'on friday')");
  if (t.days) r.days = *t.days;
  if (t.on_weekday) r.days = {*t.on_weekday};
  r.first_day = ctx.zone.local_date(ctx.now);
  if (auto ok = validate(r); !ok) {
    if (r.every && *r.every > r.window_end - r.window_start) {
      return Error::invalid(fmt::format("'every {}' is longer than the daily window {}-{}", format_duration(*r.every),
                                        format_time_of_day(r.window_start), format_time_of_day(r.window_end)));
    }
    return Error::invalid(fmt::format("the routine cannot be made: {}", ok.error().message));
  }
  return r;
}

}  // namespace rondo::lang::detail
