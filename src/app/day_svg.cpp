#include "day_svg.h"

#include <algorithm>
#include <string_view>

#include <fmt/format.h>

#include "rondo/core/utf8.h"

namespace rondo::app {

namespace {

constexpr double kTop = 64;       // title, subtitle and hour labels above the first lane
constexpr double kMargin = 10;
constexpr double kLegendHeight = 44;

// Well-formed UTF-8, no characters XML 1.0 forbids (C0 controls but tab, newline, return), and
// the five markup characters as entities.
std::string xml_text(std::string_view raw) {
  const std::string text = replace_invalid_utf8(raw);
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: {
        const auto u = static_cast<unsigned char>(c);
        out += (u < 0x20 && c != '\t' && c != '\n' && c != '\r') || u == 0x7f ? '?' : c;
      }
    }
  }
  return out;
}

// At most `max_chars` characters (code points), with an ellipsis when shortened.
std::string shorten(std::string_view text, std::size_t max_chars) {
  std::size_t chars = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if ((static_cast<unsigned char>(text[i]) & 0xC0U) == 0x80U) continue;  // continuation byte
    if (chars == max_chars) return std::string(text.substr(0, i)) + "\u2026";
    ++chars;
  }
  return std::string(text);
}

const char* outcome_colour(std::string_view outcome) {
  if (outcome.starts_with("succeeded")) return "#2e8b57";
  if (outcome.starts_with("failed")) return "#c0392b";
  if (outcome.starts_with("dropped")) return "#9e9e9e";
  return "#e69f00";  // preempted, cancelled, still running
}

std::string clock(const TimeZone& zone, Time t) { return format_time_of_day(zone.time_of_day(t)); }

std::string span_text(const DayPicture& day, std::string_view what, std::pair<Time, Time> span) {
  return fmt::format("{} {}\u2013{}", what, clock(day.zone, span.first), clock(day.zone, span.second));
}

struct Layout {
  const DayPicture& day;
  const DaySvgOptions& options;
  double plot_left() const { return kMargin + options.label_width; }
  double plot_width() const {
    return std::max(0.0, to_seconds(day.to - day.from)) / 3600.0 * options.pixels_per_hour;
  }
  double width() const { return plot_left() + plot_width() + options.outcome_width + kMargin; }
  double lane_y(std::size_t lane) const { return kTop + static_cast<double>(lane) * options.lane_height; }
  double lanes_bottom() const { return lane_y(day.rows.size() + 1); }  // + the charger lane
  double height() const { return lanes_bottom() + kLegendHeight; }
  double x(Time t) const { return day_x(day, t, options); }
  bool visible(std::pair<Time, Time> span) const { return span.second >= day.from && span.first <= day.to; }
};

// A bar over [span] in lane `lane`, inset vertically by `inset`, with a tooltip.
void bar(std::string& out, const Layout& l, std::size_t lane, std::pair<Time, Time> span, double inset,
         std::string_view style, std::string_view css_class, std::string_view tooltip) {
  if (!l.visible(span)) return;
  const double x0 = l.x(span.first);
  const double w = std::max(1.5, l.x(span.second) - x0);
  fmt::format_to(std::back_inserter(out),
                 "<rect class=\"{}\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" {}><title>{}</title></rect>\n",
                 css_class, x0, l.lane_y(lane) + inset, w, l.options.lane_height - 2 * inset, style,
                 xml_text(tooltip));
}

void text(std::string& out, double x, double y, std::string_view content, std::string_view attributes = "") {
  fmt::format_to(std::back_inserter(out), "<text x=\"{:.1f}\" y=\"{:.1f}\"{}{}>{}</text>\n", x, y,
                 attributes.empty() ? "" : " ", attributes, xml_text(content));
}

void draw_header(std::string& out, const Layout& l) {
  const auto date = l.day.zone.local_date(l.day.from);
  text(out, kMargin, 20, l.day.title, "font-size=\"16\" font-weight=\"bold\"");
  text(out, kMargin, 38,
       fmt::format("{:04}-{:02}-{:02}, local time ({})", static_cast<int>(date.year()),
                   static_cast<unsigned>(date.month()), static_cast<unsigned>(date.day()), l.day.zone.name()),
       "fill=\"#555\"");
}

void draw_axis(std::string& out, const Layout& l) {
  if (l.day.to <= l.day.from) return;
  const double bottom = l.lanes_bottom();
  for (Time t : local_hour_ticks(l.day.from, l.day.to, l.day.zone)) {
    const double x = l.x(t);
    fmt::format_to(std::back_inserter(out),
                   "<line class=\"hour\" x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#ddd\"/>\n", x,
                   kTop - 4, bottom);
    text(out, x, kTop - 8, clock(l.day.zone, t), "class=\"hour-label\" text-anchor=\"middle\" fill=\"#333\"");
  }
}

void draw_lane_frame(std::string& out, const Layout& l, std::size_t lane, std::string_view kind,
                     std::string_view label, std::string_view full_label) {
  const double y = l.lane_y(lane);
  fmt::format_to(std::back_inserter(out),
                 "<rect class=\"lane {}\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\"/>\n",
                 kind, kMargin, y, l.width() - 2 * kMargin, l.options.lane_height, lane % 2 == 0 ? "#fafafa" : "#f0f0f0");
  fmt::format_to(std::back_inserter(out), "<text x=\"{:.1f}\" y=\"{:.1f}\">{}<title>{}</title></text>\n", kMargin + 4,
                 y + l.options.lane_height * 0.7, xml_text(label), xml_text(full_label));
}

std::string row_label(const DayRow& row) {
  return row.label.empty() ? row.task_id : row.task_id + " \u00b7 " + row.label;
}

// Lane backgrounds and names first, then the hour grid, then the bars over both.
void draw_lanes(std::string& out, const Layout& l) {
  draw_lane_frame(out, l, 0, "charger", "on the charger", "spans on the charger");
  for (std::size_t i = 0; i < l.day.rows.size(); ++i) {
    const std::string full = row_label(l.day.rows[i]);
    draw_lane_frame(out, l, i + 1, "task", shorten(full, l.options.max_label_chars), full);
  }
}

void draw_charging(std::string& out, const Layout& l) {
  for (const auto& span : l.day.charging)
    bar(out, l, 0, span, 4, "fill=\"#f1c40f\"", "charging", span_text(l.day, "charging", span));
}

void draw_row(std::string& out, const Layout& l, std::size_t lane, const DayRow& row) {
  if (row.window)
    bar(out, l, lane, {row.window->release, row.window->deadline}, 1, "fill=\"#cfe3f7\"", "window",
        span_text(l.day, "window", {row.window->release, row.window->deadline}));
  if (row.planned)
    bar(out, l, lane, *row.planned, 3, "fill=\"none\" stroke=\"#1f3b73\" stroke-width=\"1.5\"", "planned",
        span_text(l.day, "planned", *row.planned));
  if (row.actual)
    bar(out, l, lane, *row.actual, 7, fmt::format("fill=\"{}\"", outcome_colour(row.outcome)), "actual",
        span_text(l.day, "actual", *row.actual) + ": " + row.outcome);
  const double y = l.lane_y(lane) + l.options.lane_height * 0.7;
  fmt::format_to(std::back_inserter(out), "<text class=\"outcome\" x=\"{:.1f}\" y=\"{:.1f}\" fill=\"{}\">{}<title>{}</title></text>\n",
                 l.plot_left() + l.plot_width() + 8, y, outcome_colour(row.outcome),
                 xml_text(shorten(row.outcome, l.options.max_label_chars)), xml_text(row.outcome));
}

void draw_legend(std::string& out, const Layout& l) {
  struct Key {
    const char* style;
    const char* name;
  };
  static constexpr Key kKeys[] = {
      {"fill=\"#cfe3f7\"", "time window"},
      {"fill=\"none\" stroke=\"#1f3b73\" stroke-width=\"1.5\"", "planned"},
      {"fill=\"#2e8b57\"", "ran: succeeded"},
      {"fill=\"#c0392b\"", "ran: failed"},
      {"fill=\"#e69f00\"", "ran: preempted, cancelled or running"},
      {"fill=\"#9e9e9e\"", "dropped"},
      {"fill=\"#f1c40f\"", "on the charger"},
  };
  const double y = l.lanes_bottom() + 16;
  double x = kMargin;
  out += "<g class=\"legend\">\n";
  for (const Key& k : kKeys) {
    fmt::format_to(std::back_inserter(out), "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"18\" height=\"12\" {}/>\n", x, y, k.style);
    text(out, x + 24, y + 10, k.name);
    x += 40 + 7.0 * static_cast<double>(std::string_view(k.name).size());
  }
  out += "</g>\n";
}

}  // namespace

double day_x(const DayPicture& day, Time t, const DaySvgOptions& options) {
  const double left = kMargin + options.label_width;
  if (day.to <= day.from) return left;
  const Time clipped = std::clamp(t, day.from, day.to);
  return left + to_seconds(clipped - day.from) / 3600.0 * options.pixels_per_hour;
}

std::vector<Time> local_hour_ticks(Time from, Time to, const TimeZone& zone) {
  std::vector<Time> ticks;
  if (to < from) return ticks;
  const Duration into = zone.time_of_day(from) % hours(1);
  Time t = into == Duration{0} ? from : from + (hours(1) - into);
  while (t <= to) {
    ticks.push_back(t);
    Time next = t + hours(1);
    next -= zone.time_of_day(next) % hours(1);  // zones whose offset changes by part of an hour
    t = next > t ? next : t + hours(1);
  }
  return ticks;
}

std::string render_day_svg(const DayPicture& day, const DaySvgOptions& options) {
  const Layout l{day, options};
  std::string out;
  fmt::format_to(std::back_inserter(out),
                 "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                 "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{0:.0f}\" height=\"{1:.0f}\" "
                 "viewBox=\"0 0 {0:.0f} {1:.0f}\" font-family=\"sans-serif\" font-size=\"12\">\n",
                 l.width(), l.height());
  fmt::format_to(std::back_inserter(out), "<title>{}</title>\n", xml_text(day.title));
  fmt::format_to(std::back_inserter(out), "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
  draw_header(out, l);
  draw_lanes(out, l);
  draw_axis(out, l);
  draw_charging(out, l);
  for (std::size_t i = 0; i < day.rows.size(); ++i) draw_row(out, l, i + 1, day.rows[i]);
  draw_legend(out, l);
  out += "</svg>\n";
  return out;
}

}  // namespace rondo::app
