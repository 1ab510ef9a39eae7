#include "time_parsing.h"

#include <cctype>
#include <string>

namespace rondo::detail {
namespace {

// A cursor over the text that reads fixed-width digit groups and literal characters.
class Scanner {
 public:
  explicit Scanner(std::string_view s) : s_(s) {}
  bool done() const { return pos_ == s_.size(); }
  char peek() const { return done() ? '\0' : s_[pos_]; }
  bool take(char c) {
    if (peek() != c) return false;
    ++pos_;
    return true;
  }
  std::optional<int> digits(std::size_t n) {
    if (pos_ + n > s_.size()) return std::nullopt;
    int v = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const char c = s_[pos_ + i];
      if (std::isdigit(static_cast<unsigned char>(c)) == 0) return std::nullopt;
      v = v * 10 + (c - '0');
    }
    pos_ += n;
    return v;
  }
  // Reads one or more digits after a decimal point, as milliseconds (extra digits truncated).
  std::optional<int> fraction_ms() {
    int ms = 0;
    int scale = 100;
    std::size_t n = 0;
    while (!done() && std::isdigit(static_cast<unsigned char>(peek())) != 0) {
      ms += (s_[pos_] - '0') * scale;
      scale /= 10;
      ++pos_;
      ++n;
    }
    if (n == 0) return std::nullopt;
    return ms;
  }

 private:
  std::string_view s_;
  std::size_t pos_ = 0;
};

Error bad(std::string_view text, const std::string& why) {
  return Error::invalid("time '" + std::string(text) + "': " + why);
}

Result<std::chrono::year_month_day> read_date(Scanner& in, std::string_view text) {
  auto y = in.digits(4);
  if (!y || !in.take('-')) return bad(text, "expected YYYY-MM-DD");
  auto m = in.digits(2);
  if (!m || !in.take('-')) return bad(text, "expected YYYY-MM-DD");
  auto d = in.digits(2);
  if (!d) return bad(text, "expected YYYY-MM-DD");
  const std::chrono::year_month_day ymd{std::chrono::year{*y}, std::chrono::month{static_cast<unsigned>(*m)},
                                        std::chrono::day{static_cast<unsigned>(*d)}};
  if (!ymd.ok()) return bad(text, "no such date");
  return ymd;
}

Result<Duration> read_clock(Scanner& in, std::string_view text, bool allow_24) {
  auto h = in.digits(2);
  if (!h || !in.take(':')) return bad(text, "expected hh:mm");
  auto mi = in.digits(2);
  if (!mi) return bad(text, "expected hh:mm");
  int s = 0;
  int ms = 0;
  if (in.take(':')) {
    auto sv = in.digits(2);
    if (!sv) return bad(text, "expected hh:mm:ss");
    s = *sv;
    if (in.take('.') || in.take(',')) {
      auto f = in.fraction_ms();
      if (!f) return bad(text, "expected digits after the decimal point");
      ms = *f;
    }
  }
  const bool end_of_day = allow_24 && *h == 24 && *mi == 0 && s == 0 && ms == 0;
  if ((*h > 23 && !end_of_day) || *mi > 59 || s > 59) return bad(text, "hour, minute or second out of range");
  return hours(*h) + minutes(*mi) + seconds(s) + milliseconds(ms);
}

}  // namespace

Result<ParsedDateTime> parse_iso_datetime(std::string_view text) {
  Scanner in(text);
  auto date = read_date(in, text);
  if (!date) return date.error();
  ParsedDateTime out{Time{std::chrono::sys_days{*date}}, std::nullopt};
  if (in.done()) return out;
  if (!in.take('T') && !in.take('t') && !in.take(' ')) return bad(text, "expected 'T' between date and time");
  auto clock = read_clock(in, text, /*allow_24=*/false);
  if (!clock) return clock.error();
  out.local += *clock;
  if (in.done()) return out;
  if (in.take('Z') || in.take('z')) {
    out.utc_offset = Duration{0};
  } else if (in.peek() == '+' || in.peek() == '-') {
    const bool negative = in.peek() == '-';
    in.take(in.peek());
    auto oh = in.digits(2);
    in.take(':');
    auto om = in.digits(2);
    if (!oh || !om || *oh > 18 || *om > 59) return bad(text, "expected a UTC offset such as +01:00");
    const Duration off = hours(*oh) + minutes(*om);
    out.utc_offset = negative ? -off : off;
  }
  if (!in.done()) return bad(text, "unexpected characters after the time");
  return out;
}

Result<std::chrono::year_month_day> parse_iso_date(std::string_view text) {
  Scanner in(text);
  auto date = read_date(in, text);
  if (!date) return date.error();
  if (!in.done()) return bad(text, "expected a date YYYY-MM-DD alone");
  return *date;
}

Result<Duration> parse_time_of_day(std::string_view text) {
  Scanner in(text);
  auto clock = read_clock(in, text, /*allow_24=*/true);
  if (!clock) return clock.error();
  if (!in.done()) return bad(text, "expected hh:mm or hh:mm:ss");
  return *clock;
}

}  // namespace rondo::detail

namespace rondo {

Result<Duration> parse_time_of_day(std::string_view text) { return detail::parse_time_of_day(text); }

}  // namespace rondo
