// The per-day schedule picture (src/app/day_svg.h): a well-formed standalone SVG, text escaped,
// a lane per task, time mapped to x monotonically, local hours across daylight-saving changes.
#include "day_svg.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstddef>
#include <regex>
#include <string>
#include <vector>

namespace rondo::app {
namespace {

using namespace std::chrono_literals;
using std::chrono::year_month_day;

// A small XML well-formedness check, enough for what render_day_svg writes: one root, tags
// balanced and properly nested, attribute values quoted, text and attribute values free of raw
// '<' and of '&' that does not start one of the five predefined entities. Returns "" if well formed.
std::string xml_problem(const std::string& doc) {
  static const std::regex entity("^&(amp|lt|gt|quot|apos);");
  auto bad_ampersand = [&](std::size_t at) {
    return !std::regex_search(doc.begin() + static_cast<std::ptrdiff_t>(at), doc.end(), entity);
  };
  std::vector<std::string> open;
  std::size_t roots = 0;
  std::size_t i = 0;
  while (i < doc.size()) {
    if (doc[i] == '&' && bad_ampersand(i)) return "raw & at " + std::to_string(i);
    if (doc[i] == '>') return "raw > outside a tag at " + std::to_string(i);
    if (doc[i] != '<') {
      ++i;
      continue;
    }
    if (doc.compare(i, 5, "<?xml") == 0) {
      if (i != 0) return "xml declaration not first";
      i = doc.find("?>", i) + 2;
      continue;
    }
    bool in_quotes = false;
    std::size_t end = i + 1;
    for (; end < doc.size() && (in_quotes || doc[end] != '>'); ++end) {
      if (doc[end] == '"') in_quotes = !in_quotes;
      else if (in_quotes && doc[end] == '<') return "raw < in an attribute at " + std::to_string(end);
      else if (in_quotes && doc[end] == '&' && bad_ampersand(end)) return "raw & in an attribute";
      else if (!in_quotes && doc[end] == '<') return "raw < at " + std::to_string(end);
    }
    if (end >= doc.size()) return "unterminated tag";
    const std::string tag = doc.substr(i + 1, end - i - 1);
    static const std::regex name_re("^/?([A-Za-z][A-Za-z0-9:-]*)");
    std::smatch m;
    if (!std::regex_search(tag, m, name_re)) return "bad tag <" + tag + ">";
    const std::string name = m[1];
    if (tag[0] == '/') {
      if (open.empty() || open.back() != name) return "</" + name + "> closes " + (open.empty() ? "nothing" : open.back());
      open.pop_back();
    } else if (tag.back() != '/') {
      if (open.empty()) ++roots;
      open.push_back(name);
    } else if (open.empty()) {
      ++roots;
    }
    i = end + 1;
  }
  if (!open.empty()) return "<" + open.back() + "> never closed";
  if (roots != 1) return std::to_string(roots) + " root elements";
  return "";
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The x attribute of every element with class="<css_class>", in document order.
std::vector<double> xs_of(const std::string& svg, const std::string& css_class) {
  std::vector<double> xs;
  const std::regex re("class=\"" + css_class + "\" x=\"([0-9.]+)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
    xs.push_back(std::stod((*it)[1]));
  return xs;
}

TimeZone london() { return TimeZone::named("Europe/London").value(); }

DayPicture day_of(year_month_day date) {
  const TimeZone zone = london();
  DayPicture day{.title = "G4S, test day", .from = zone.at(date, hours(0)), .to = zone.at(date, hours(24)), .zone = zone};
  return day;
}

DayRow row(const std::string& id, Time at, const std::string& outcome) {
  return DayRow{.task_id = id,
                .label = "check " + id,
                .window = TimeWindow{at - minutes(30), at + hours(2)},
                .planned = std::pair{at, at + minutes(5)},
                .actual = std::pair{at + minutes(1), at + minutes(7)},
                .outcome = outcome};
}

TEST(DaySvg, AnOrdinaryDayIsWellFormedWithALanePerTaskAndALegend) {
  DayPicture day = day_of(2026y / 6 / 10);
  day.rows.push_back(row("fd-1", day.from + hours(9), "succeeded"));
  day.rows.push_back(row("fe-2", day.from + hours(11), "failed: navigation overran"));
  day.rows.push_back({.task_id = "od-3", .label = "fetch mail", .outcome = "dropped: window cannot be reached"});
  day.charging.push_back({day.from, day.from + hours(8) + minutes(45)});
  const std::string svg = render_day_svg(day);
  EXPECT_EQ(xml_problem(svg), "") << svg;
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_EQ(count(svg, "class=\"lane task\""), 3u);
  EXPECT_EQ(count(svg, "class=\"lane charger\""), 1u);
  EXPECT_EQ(count(svg, "class=\"window\""), 2u);   // the on-demand task has none
  EXPECT_EQ(count(svg, "class=\"planned\""), 2u);
  EXPECT_EQ(count(svg, "class=\"actual\""), 2u);
  EXPECT_EQ(count(svg, "class=\"charging\""), 1u);
  EXPECT_EQ(count(svg, "class=\"hour\""), 25u);  // 00:00 .. 24:00 on an ordinary day
  EXPECT_NE(svg.find("class=\"legend\""), std::string::npos);
  for (const char* text : {"fd-1 \u00b7 check fd-1", "failed: navigation overran", "dropped: window cannot be reached",
                           "time window", "planned", "on the charger", "09:00"})
    EXPECT_NE(svg.find(text), std::string::npos) << text;
  // The outcome decides the colour of the bar that shows what happened.
  EXPECT_NE(svg.find("class=\"actual\" x=\"" ), std::string::npos);
  const std::regex actual_fill("class=\"actual\"[^>]*fill=\"(#[0-9a-f]{6})\"");
  std::vector<std::string> fills;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), actual_fill); it != std::sregex_iterator(); ++it)
    fills.push_back((*it)[1]);
  ASSERT_EQ(fills.size(), 2u);
  EXPECT_NE(fills[0], fills[1]);
}

TEST(DaySvg, MarkupCharactersInEveryTextAreEscaped) {
  DayPicture day = day_of(2026y / 6 / 10);
  day.title = "day <1> & \"quotes\" 'too'";
  DayRow r = row("a<b>&\"c\"", day.from + hours(10), "failed: x < y & \"z\" > w");
  r.label = "<script>alert(1)</script>";
  day.rows.push_back(r);
  const std::string svg = render_day_svg(day);
  EXPECT_EQ(xml_problem(svg), "") << svg;
  EXPECT_NE(svg.find("day &lt;1&gt; &amp; &quot;quotes&quot; &apos;too&apos;"), std::string::npos);
  EXPECT_NE(svg.find("a&lt;b&gt;&amp;&quot;c&quot;"), std::string::npos);
  EXPECT_NE(svg.find("failed: x &lt; y &amp; &quot;z&quot; &gt; w"), std::string::npos);
  EXPECT_EQ(svg.find("<script"), std::string::npos);
}

TEST(DaySvg, BytesThatAreNotXmlCharactersAreReplaced) {
  DayPicture day = day_of(2026y / 6 / 10);
  day.rows.push_back(row(std::string("bad\x01\xff\x7f", 6) + "id", day.from + hours(10), "succeeded"));
  const std::string svg = render_day_svg(day);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_NE(svg.find("bad???id"), std::string::npos);
  EXPECT_EQ(svg.find('\x01'), std::string::npos);
}

TEST(DaySvg, LongLabelsAreShortenedOnACharacterBoundaryAndKeptWholeInTheTooltip) {
  DayPicture day = day_of(2026y / 6 / 10);
  DayRow r = row("t", day.from + hours(10), "succeeded");
  r.label.clear();
  for (int i = 0; i < 30; ++i) r.label += "\u00e9\u6771";  // 2- and 3-byte characters
  day.rows.push_back(r);
  const std::string svg = render_day_svg(day, {.max_label_chars = 11});
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_NE(svg.find(">t \u00b7 \u00e9\u6771\u00e9\u6771\u00e9\u6771\u00e9\u2026<title>"), std::string::npos) << svg;
  EXPECT_NE(svg.find("<title>t \u00b7 " + r.label + "</title>"), std::string::npos);
}

TEST(DaySvg, LaterTasksAreDrawnFurtherRight) {
  DayPicture day = day_of(2026y / 6 / 10);
  for (int h = 6; h <= 20; h += 2) day.rows.push_back(row("t" + std::to_string(h), day.from + hours(h), "succeeded"));
  const std::string svg = render_day_svg(day);
  for (const char* kind : {"planned", "actual"}) {
    const std::vector<double> xs = xs_of(svg, kind);
    ASSERT_EQ(xs.size(), day.rows.size()) << kind;
    for (std::size_t i = 1; i < xs.size(); ++i) EXPECT_GT(xs[i], xs[i - 1]) << kind << " " << i;
  }
  // Two hours apart = two hours of pixels.
  const std::vector<double> planned = xs_of(svg, "planned");
  EXPECT_NEAR(planned[1] - planned[0], 2 * DaySvgOptions{}.pixels_per_hour, 0.11);
}

RC_GTEST_PROP(DaySvgProperties, TimeMapsToXMonotonicallyAndStaysOnTheAxis, ()) {
  DayPicture day = day_of(2026y / 3 / 29);
  const auto a = *rc::gen::inRange<std::int64_t>(-7200, 30 * 3600);
  const auto b = *rc::gen::inRange<std::int64_t>(-7200, 30 * 3600);
  const Time t1 = day.from + seconds(std::min(a, b));
  const Time t2 = day.from + seconds(std::max(a, b));
  const double x1 = day_x(day, t1), x2 = day_x(day, t2);
  RC_ASSERT(x1 <= x2);
  RC_ASSERT(x1 >= day_x(day, day.from));
  RC_ASSERT(x2 <= day_x(day, day.to));
  if (t1 >= day.from && t2 <= day.to && t1 < t2) RC_ASSERT(x1 < x2);
}

RC_GTEST_PROP(DaySvgProperties, AnyTextGivesAWellFormedDocument, ()) {
  DayPicture day = day_of(2026y / 6 / 10);
  day.title = *rc::gen::arbitrary<std::string>();
  const auto rows = *rc::gen::inRange<int>(0, 6);
  for (int i = 0; i < rows; ++i) {
    DayRow r = row(*rc::gen::arbitrary<std::string>(), day.from + hours(*rc::gen::inRange<int>(-3, 27)),
                   *rc::gen::arbitrary<std::string>());
    r.label = *rc::gen::arbitrary<std::string>();
    day.rows.push_back(r);
  }
  const std::string svg = render_day_svg(day);
  RC_ASSERT(xml_problem(svg) == "");
  RC_ASSERT(count(svg, "class=\"lane task\"") == static_cast<std::size_t>(rows));
}

// Europe/London: clocks go forward at 01:00 UTC on 29 March 2026 and back at 01:00 UTC on
// 25 October 2026.
TEST(DaySvg, ADaylightSavingDayShowsItsLocalHours) {
  struct Case {
    year_month_day date;
    std::size_t hours_long;
  };
  for (const Case& c : {Case{2026y / 3 / 29, 23}, Case{2026y / 10 / 25, 25}, Case{2026y / 6 / 10, 24}}) {
    const DayPicture day = day_of(c.date);
    ASSERT_EQ(day.to - day.from, hours(static_cast<int>(c.hours_long)));
    const std::string svg = render_day_svg(day);
    EXPECT_EQ(xml_problem(svg), "");
    EXPECT_EQ(count(svg, "class=\"hour\""), c.hours_long + 1) << static_cast<unsigned>(c.date.day());
    const std::vector<Time> ticks = local_hour_ticks(day.from, day.to, day.zone);
    ASSERT_EQ(ticks.size(), c.hours_long + 1);
    for (std::size_t i = 1; i < ticks.size(); ++i) EXPECT_EQ(ticks[i] - ticks[i - 1], hours(1));
    // The plot is as wide as the day is long.
    EXPECT_DOUBLE_EQ(day_x(day, day.to) - day_x(day, day.from),
                     static_cast<double>(c.hours_long) * DaySvgOptions{}.pixels_per_hour);
  }
  const DayPicture spring = day_of(2026y / 3 / 29);
  const std::string svg = render_day_svg(spring);
  EXPECT_NE(svg.find(">00:00</text>"), std::string::npos);
  EXPECT_EQ(svg.find(">01:00</text>"), std::string::npos);  // skipped by the clocks
  EXPECT_NE(svg.find(">02:00</text>"), std::string::npos);
  const DayPicture autumn = day_of(2026y / 10 / 25);
  EXPECT_EQ(count(render_day_svg(autumn), ">01:00</text>"), 2u);  // lived twice
}

TEST(DaySvg, HourTicksFallOnLocalWholeHoursInAHalfHourZone) {
  const TimeZone kolkata = TimeZone::named("Asia/Kolkata").value();
  const Time from = kolkata.at(2026y / 6 / 10, hours(0)) + minutes(10);
  const std::vector<Time> ticks = local_hour_ticks(from, from + hours(3), kolkata);
  ASSERT_EQ(ticks.size(), 3u);
  for (Time t : ticks) EXPECT_EQ(kolkata.time_of_day(t) % hours(1), Duration{0});
  EXPECT_EQ(kolkata.time_of_day(ticks[0]), hours(1));
}

TEST(DaySvg, BarsOutsideThePeriodAreClippedOrLeftOut) {
  DayPicture day = day_of(2026y / 6 / 10);
  DayRow r = row("late", day.from + hours(23) + minutes(50), "succeeded");  // window runs past midnight
  day.rows.push_back(r);
  day.rows.push_back(row("tomorrow", day.to + hours(3), "succeeded"));
  const std::string svg = render_day_svg(day);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(count(svg, "class=\"window\""), 1u);
  EXPECT_EQ(count(svg, "class=\"lane task\""), 2u);  // the lane is there, its bars are not
  const std::regex window_rect("class=\"window\" x=\"([0-9.]+)\" y=\"[0-9.]+\" width=\"([0-9.]+)\"");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, window_rect));
  EXPECT_NEAR(std::stod(m[1]) + std::stod(m[2]), day_x(day, day.to), 0.11);
}

TEST(DaySvg, AnEmptyPeriodStillGivesAWellFormedDocument) {
  DayPicture day = day_of(2026y / 6 / 10);
  day.to = day.from;
  day.rows.push_back(row("t", day.from, "succeeded"));
  const std::string svg = render_day_svg(day);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(count(svg, "class=\"hour\""), 0u);
}

}  // namespace
}  // namespace rondo::app
