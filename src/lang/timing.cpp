#include "timing.h"

#include <fmt/format.h>

#include "rondo/core/time.h"

namespace rondo::lang::detail {
namespace {

using std::chrono::weekday;

std::vector<weekday> weekdays() {
  return {std::chrono::Monday, std::chrono::Tuesday, std::chrono::Wednesday, std::chrono::Thursday,
          std::chrono::Friday};
}

// "weekdays", "weekday", "working days", "weekends", "weekend", "day(s)", or a day name: the days.
std::optional<std::vector<weekday>> day_set(std::string_view w) {
  if (w == "weekday" || w == "weekdays") return weekdays();
  if (w == "weekend" || w == "weekends") return std::vector<weekday>{std::chrono::Saturday, std::chrono::Sunday};
  if (w == "day" || w == "days") return std::vector<weekday>{};
  if (auto d = weekday_named(w)) return std::vector<weekday>{*d};
  return std::nullopt;
}

std::optional<std::chrono::year_month_day> iso_date(std::string_view w) {
  if (w.size() != 10 || w[4] != '-' || w[7] != '-') return std::nullopt;
  auto num = [&](std::size_t b, std::size_t n) -> std::optional<int> {
    int v = 0;
    for (std::size_t i = b; i < b + n; ++i) {
      if (w[i] < '0' || w[i] > '9') return std::nullopt;
      v = v * 10 + (w[i] - '0');
    }
    return v;
  };
  const auto y = num(0, 4);
  const auto m = num(5, 2);
  const auto d = num(8, 2);
  if (!y || !m || !d) return std::nullopt;
  const std::chrono::year_month_day ymd{std::chrono::year{*y}, std::chrono::month{static_cast<unsigned>(*m)},
                                        std::chrono::day{static_cast<unsigned>(*d)}};
  if (!ymd.ok()) return std::nullopt;
  return ymd;
}

// A span from now at tokens[i]: "N UNIT" ("10 minutes", "one hour"), "a/an UNIT" ("an hour") or
// "half an hour"; the span and the number of words it takes.
std::optional<std::pair<Duration, std::size_t>> span_from_now(const Tokens& t, std::size_t i) {
  const auto word = [&](std::size_t k) { return k < t.size() ? std::string_view(t[k].word) : std::string_view(); };
  const auto unit = unit_of(word(i + 1));
  if (auto n = count_of(word(i)); n && unit) return std::pair{*n * *unit, std::size_t{2}};
  if ((word(i) == "a" || word(i) == "an") && unit) return std::pair{*unit, std::size_t{2}};
  if (word(i) == "half" && (word(i + 1) == "an" || word(i + 1) == "a") && unit_of(word(i + 2)) == hours(1))
    return std::pair{Duration{minutes(30)}, std::size_t{3}};
  return std::nullopt;
}

class TimingParser {
 public:
  TimingParser(const Tokens& t, std::size_t i) : t_(t), i_(i) {}

  Result<Timing> run() {
    while (i_ < t_.size()) RONDO_RETURN_IF_ERROR(clause());
    return out_;
  }

 private:
  std::string_view word(std::size_t k) const { return k < t_.size() ? std::string_view(t_[k].word) : ""; }
  std::string_view next() const { return word(i_ + 1); }

  Error error(std::string_view what) const { return Error::invalid(std::string(what)); }

  template <class T>
  Status once(std::optional<T>& slot, T value, std::string_view clause) {
    if (slot) return error(fmt::format("'{}' is given twice", clause));
    slot = std::move(value);
    return {};
  }

  Result<Duration> time_after(std::string_view keyword) {
    const std::string_view w = word(i_ + 1);
    const auto t = clock_time(w);
    if (!t) {
      return error(w.empty()
                       ? fmt::format("'{}' needs a time of day such as 15:00", keyword)
                       : fmt::format("'{}' needs a time of day such as 15:00, not '{}'", keyword, t_[i_ + 1].text));
    }
    i_ += 2;
    return *t;
  }

  // "N unit", "unit" (one), or a duration word ("90s", "1h30m"), starting at i_.
  Result<Duration> span(std::string_view keyword, bool allow_one) {
    const std::string_view w = word(i_);
    if (auto n = count_of(w); n && unit_of(word(i_ + 1))) {
      const Duration d = *n * *unit_of(word(i_ + 1));
      i_ += 2;
      if (d <= Duration{0}) return error(fmt::format("'{} {}' must be longer than nothing", keyword, w));
      return d;
    }
    if (allow_one) {
      if (auto u = unit_of(w)) {
        ++i_;
        return *u;
      }
    }
    if (!w.empty() && w.front() >= '0' && w.front() <= '9' && w.find(':') == std::string_view::npos) {
      if (auto d = parse_duration(w); d && *d > Duration{0} && *d <= hours(24)) {
        ++i_;
        return *d;
      }
    }
    return error(w.empty() ? fmt::format("'{}' needs a length such as '2 hours'", keyword)
                           : fmt::format("'{}' needs a length such as '2 hours', not '{}'", keyword, t_[i_].text));
  }

  Status every() {
    ++i_;  // "every"
    const std::string_view w = word(i_);
    if (auto days = day_set(w)) {
      ++i_;
      return once(out_.days, *days, "every " + std::string(w));
    }
    if (w == "working" && (word(i_ + 1) == "day" || word(i_ + 1) == "days")) {
      i_ += 2;
      return once(out_.days, weekdays(), "every working day");
    }
    RONDO_ASSIGN_OR_RETURN(auto d, span("every", true));
    return once(out_.every, d, "every");
  }

  Status on() {
    const std::string_view w = next();
    if (auto date = iso_date(w)) {
      i_ += 2;
      return once(out_.on_date, *date, "on DATE");
    }
    const bool plural = w == "weekdays" || w == "weekends" || (w.size() > 6 && w.ends_with("days"));
    if (plural || w == "weekday") {
      auto days = day_set(w);
      i_ += 2;
      return once(out_.days, *days, "on " + std::string(w));
    }
    if (auto d = weekday_named(w)) {
      i_ += 2;
      return once(out_.on_weekday, *d, "on " + std::string(w));
    }
    return error(fmt::format("'on' needs a day (monday, weekdays) or a date (2026-11-24), not '{}'", w));
  }

  Status clause() {
    const std::string_view w = word(i_);
    if (w == "now" || w == "immediately") {
      if (out_.now) return error(fmt::format("'{}' is given twice", w));
      out_.now = true;
      ++i_;
      return {};
    }
    if (w == "today" || w == "tomorrow") {
      ++i_;
      return once(out_.day_offset, w == "today" ? 0 : 1, "today/tomorrow");
    }
    if (w == "on") return on();
    if (w == "before" || w == "by" || w == "until") {
      RONDO_ASSIGN_OR_RETURN(auto t, time_after(w));
      return once(out_.before, t, "before");
    }
    if (w == "after") {
      RONDO_ASSIGN_OR_RETURN(auto t, time_after(w));
      return once(out_.after, t, "after");
    }
    if (w == "at") {
      RONDO_ASSIGN_OR_RETURN(auto t, time_after(w));
      return once(out_.at, t, "at");
    }
    if (w == "between" || w == "from") {
      const std::string keyword(w);
      RONDO_ASSIGN_OR_RETURN(auto a, time_after(keyword));
      const std::string_view link = word(i_);
      const bool ok = keyword == "between" ? link == "and" : (link == "to" || link == "until");
      if (!ok) {
        return error(fmt::format("'{} {}' needs '{}' and a second time", keyword, t_[i_ - 1].text,
                                 keyword == "between" ? "and" : "to"));
      }
      RONDO_ASSIGN_OR_RETURN(auto b, time_after(link));
      if (b <= a) {
        return error(fmt::format("'{} {} {} {}': the second time must be later", keyword, format_time_of_day(a), link,
                                 format_time_of_day(b)));
      }
      return once(out_.between, std::pair{a, b}, keyword);
    }
    if (w == "in") {
      const auto span = span_from_now(t_, i_ + 1);
      if (!span) {
        return error(next().empty() ? std::string("'in' needs a length such as '10 minutes' or 'half an hour'")
                                    : fmt::format("'in' needs a length such as '10 minutes' or 'half an hour', not '{}'",
                                                  t_[i_ + 1].text));
      }
      if (span->first <= Duration{0}) {
        return error(fmt::format("'in {}' must be later than now", text_of(t_, i_ + 1, i_ + 1 + span->second)));
      }
      i_ += 1 + span->second;
      return once(out_.in, span->first, "in ...");
    }
    if (w == "every") return every();
    if (w == "daily") {
      ++i_;
      return once(out_.days, std::vector<weekday>{}, "daily");
    }
    if (w == "hourly") {
      ++i_;
      return once(out_.every, Duration{hours(1)}, "hourly");
    }
    if (w == "for") {
      ++i_;
      RONDO_ASSIGN_OR_RETURN(auto d, span("for", false));
      return once(out_.duration, d, "for");
    }
    if (w == "with" && next() == "priority") {
      const std::string_view n = word(i_ + 2);
      int sign = 1;
      std::string_view digits = n;
      if (!digits.empty() && digits.front() == '-') {
        sign = -1;
        digits.remove_prefix(1);
      }
      const auto v = count_of(digits);
      if (!v || *v > 1'000'000) return error(fmt::format("'with priority' needs a whole number, not '{}'", n));
      i_ += 3;
      return once(out_.priority, sign * *v, "with priority");
    }
    return error(
        fmt::format("I do not understand '{}' here: after the place come only time words (now, "
                    "today, tomorrow, on DAY, before/after/at TIME, between TIME and TIME, every ..., "
                    "in LENGTH, for LENGTH, with priority N)",
                    t_[i_].text));
  }

  const Tokens& t_;
  std::size_t i_;
  Timing out_;
};

}  // namespace

bool Timing::any() const {
  return now || day_offset || on_weekday || on_date || before || after || at || between || in || every || days ||
         duration || priority;
}

bool starts_timing(const Tokens& tokens, std::size_t i) {
  const std::string_view w = tokens[i].word;
  const std::string_view next = i + 1 < tokens.size() ? std::string_view(tokens[i + 1].word) : "";
  if (w == "now" || w == "immediately" || w == "today" || w == "tomorrow" || w == "before" || w == "after" ||
      w == "between" || w == "every" || w == "daily" || w == "hourly" || w == "until") {
    return true;
  }
  if (w == "by" || w == "at" || w == "from") return clock_time(next).has_value();
  if (w == "on") return weekday_named(next) || iso_date(next) || next == "weekdays" || next == "weekends";
  if (w == "for") return count_of(next).has_value() || (!next.empty() && next.front() >= '0' && next.front() <= '9');
  if (w == "with") return next == "priority";
  if (w == "in") return span_from_now(tokens, i + 1).has_value();  // "in 10 minutes", not "the desk in A-110"
  return false;
}

Result<Timing> parse_timing(const Tokens& tokens, std::size_t from) {
  return TimingParser(tokens, from).run();
}

}  // namespace rondo::lang::detail
