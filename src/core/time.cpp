#include "rondo/core/time.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "rondo/core/utf8.h"
#include "time_parsing.h"

namespace rondo {

Result<Duration> checked_from_seconds(double s) {
  if (!std::isfinite(s) || s > kMaxSeconds || s < -kMaxSeconds) {
    return Error::invalid(fmt::format("{} seconds is out of range (at most {:g} either way)", s, kMaxSeconds));
  }
  return from_seconds(s);
}

Duration from_seconds(double s) {
  if (!std::isfinite(s)) return Duration{0};
  if (s > kMaxSeconds) s = kMaxSeconds;
  if (s < -kMaxSeconds) s = -kMaxSeconds;
  return Duration{static_cast<std::int64_t>(std::llround(s * 1000.0))};
}

double to_seconds(Duration d) { return static_cast<double>(d.count()) / 1000.0; }

Time from_unix_seconds(double s) { return Time{from_seconds(s)}; }

double to_unix_seconds(Time t) { return to_seconds(t.time_since_epoch()); }

Result<Time> parse_time(std::string_view text) {
  auto parsed = detail::parse_iso_datetime(text);
  if (!parsed) return parsed.error();
  if (!parsed->utc_offset) {
    return Error::invalid("time '" + std::string(text) +
                          "' has no zone: add 'Z' for UTC or an offset such as '+01:00'");
  }
  return parsed->local - *parsed->utc_offset;
}

std::string format_time(Time t) {
  const auto day = std::chrono::floor<std::chrono::days>(t);
  const std::chrono::year_month_day ymd{day};
  const auto tod = t - day;
  const auto ms = tod.count();
  const auto h = ms / 3'600'000;
  const auto m = (ms / 60'000) % 60;
  const auto s = (ms / 1000) % 60;
  const auto frac = ms % 1000;
  const auto date = fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", static_cast<int>(ymd.year()),
                                 static_cast<unsigned>(ymd.month()), static_cast<unsigned>(ymd.day()), h, m, s);
  return frac != 0 ? fmt::format("{}.{:03}Z", date, frac) : date + "Z";
}

namespace {

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

// Reads a non-negative decimal number ("12", "2.5") from the front of `s`.
std::optional<double> take_number(std::string_view& s) {
  std::size_t n = 0;
  bool dot = false;
  while (n < s.size() && (std::isdigit(static_cast<unsigned char>(s[n])) != 0 || (s[n] == '.' && !dot))) {
    dot = dot || s[n] == '.';
    ++n;
  }
  if (n == 0 || (n == 1 && s[0] == '.')) return std::nullopt;
  double v = 0;
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + n, v);
  if (ec != std::errc{} || ptr != s.data() + n || !std::isfinite(v)) return std::nullopt;
  s.remove_prefix(n);
  return v;
}

Result<Duration> parse_clock_duration(std::string_view text, std::string_view original) {
  // hh:mm or hh:mm:ss(.fff)
  double parts[3] = {0, 0, 0};
  int count = 0;
  while (true) {
    if (count == 3) return Error::invalid("duration '" + std::string(original) + "': too many ':' fields");
    auto v = take_number(text);
    if (!v) return Error::invalid("duration '" + std::string(original) + "': expected hh:mm[:ss]");
    parts[count++] = *v;
    if (text.empty()) break;
    if (text.front() != ':') return Error::invalid("duration '" + std::string(original) + "': expected hh:mm[:ss]");
    text.remove_prefix(1);
  }
  if (count < 2) return Error::invalid("duration '" + std::string(original) + "': expected hh:mm[:ss]");
  if (parts[1] >= 60 || parts[2] >= 60) {
    return Error::invalid("duration '" + std::string(original) + "': minutes and seconds must be below 60");
  }
  const double total = parts[0] * 3600 + parts[1] * 60 + parts[2];
  if (total > kMaxSeconds) return Error::invalid("duration '" + std::string(original) + "' is too long");
  return from_seconds(total);
}

}  // namespace

Result<Duration> parse_duration(std::string_view text) {
  const std::string_view original = text;
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  if (text.empty()) return Error::invalid("duration is empty");
  if (text.front() == '-') return Error::invalid("duration '" + std::string(original) + "' is negative");
  if (text.find(':') != std::string_view::npos) return parse_clock_duration(text, original);

  double total = 0;
  bool any = false;
  while (!text.empty()) {
    auto v = take_number(text);
    if (!v) {
      return Error::invalid("duration '" + std::string(original) +
                            "': expected a number followed by h, m, s or ms");
    }
    double unit = 1.0;  // a bare number means seconds
    if (text.starts_with("ms")) {
      unit = 0.001;
      text.remove_prefix(2);
    } else if (!text.empty() && (text.front() == 'h' || text.front() == 'm' || text.front() == 's')) {
      unit = text.front() == 'h' ? 3600.0 : text.front() == 'm' ? 60.0 : 1.0;
      text.remove_prefix(1);
    } else if (!text.empty() && !is_space(text.front())) {
      // The whole character, not its first byte, so that the message stays UTF-8 (found by fuzz_problem).
      std::size_t n = 1;
      while (n < text.size() && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) ++n;
      return Error::invalid("duration '" + std::string(original) + "': unknown unit '" +
                            quote_for_message(text.substr(0, n)) + "' (use h, m, s or ms)");
    } else if (any) {
      return Error::invalid("duration '" + std::string(original) + "': a number without a unit");
    }
    total += *v * unit;
    any = true;
    while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  }
  if (total > kMaxSeconds) return Error::invalid("duration '" + std::string(original) + "' is too long");
  return from_seconds(total);
}

std::string format_duration(Duration d) {
  std::string out;
  std::int64_t ms = d.count();
  if (ms < 0) {
    out = "-";
    ms = -ms;
  }
  const std::int64_t h = ms / 3'600'000;
  const std::int64_t m = (ms / 60'000) % 60;
  const std::int64_t s = (ms / 1000) % 60;
  const std::int64_t frac = ms % 1000;
  if (h) out += std::to_string(h) + "h";
  if (m) out += std::to_string(m) + "m";
  if (s || frac || out.empty() || out == "-") {
    out += std::to_string(s);
    if (frac) {
      std::string f = fmt::format(".{:03}", frac);
      while (f.back() == '0') f.pop_back();
      out += f;
    }
    out += "s";
  }
  return out;
}

std::string format_time_of_day(Duration since_midnight) {
  const auto s = std::chrono::duration_cast<std::chrono::seconds>(since_midnight).count();
  if (s % 60 != 0) return fmt::format("{:02}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
  return fmt::format("{:02}:{:02}", s / 3600, (s / 60) % 60);
}

}  // namespace rondo
