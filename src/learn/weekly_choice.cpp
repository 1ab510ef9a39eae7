// Choosing the structure of q(t) per edge: time of day alone, or with the time-of-week term
// (episode_model.h). Both structures predict each attempt of a day from the first attempts of the
// days before it (prequential, day-ahead: every score is on data the counts have not seen, and the
// weekly term is judged only once it has a week behind it), and the weekly term is kept when its
// Brier score is lower by `weekly_evidence` standard errors of the paired differences and it was
// lower in at least two different weeks.
#include <cmath>

#include "histogram_family.h"
#include "json_util.h"
#include "rondo/learn/episode_model.h"

namespace rondo::learn {

WeeklyChoice choose_weekly(std::span<const SlotAttempt> all, double pooled_rate, const EpisodeOptions& options) {
  // Counts per bin of every histogram: a prediction reads one bin per histogram (the window of a
  // nightly refit holds thousands of first attempts).
  BinCounts counts(options.day_resolutions);
  double successes = 0, attempts = 0;
  double sum_d = 0, sum_dd = 0, day_loss = 0, week_loss = 0;
  WeeklyChoice out;
  // The counts see a day's attempts only when the next day starts.
  std::vector<SlotAttempt> today;
  auto flush = [&] {
    for (const SlotAttempt& f : today) {
      counts.add(f.week_slot, f.success);
      attempts += 1;
      successes += f.success ? 1 : 0;
    }
    today.clear();
  };
  // The paired differences summed per week (7-day blocks from the first day). The first block
  // never counts as won: it has no earlier week, only bins that cross midnight into yesterday.
  std::int64_t first_day = 0, week_start = 0;
  double week_sum = 0;
  bool any = false;
  auto close_week = [&] {
    if (week_sum < 0 && week_start > first_day) ++out.weeks_won;
    week_sum = 0;
  };
  int firsts = 0;
  for (const SlotAttempt& f : all) {
    if (!f.first || f.week_slot < 0 || f.week_slot >= kWeekSlots) continue;
    ++firsts;
    if (!any) first_day = week_start = f.day;
    any = true;
    if (f.day >= week_start + 7) {
      close_week();
      week_start += (f.day - week_start) / 7 * 7;
    }
    if (!today.empty() && f.day != today.back().day) flush();
    const double edge = (successes + options.edge_prior * pooled_rate) / (attempts + options.edge_prior);
    double q_day = 0, q_week = 0;
    int n = 0;
    counts.for_each_bin_estimate(f.week_slot, edge, options, true, [&](double d, double w) {
      q_day += d;
      q_week += w;
      ++n;
    });
    q_day = n > 0 ? q_day / n : edge;
    q_week = n > 0 ? q_week / n : edge;
    const double y = f.success ? 1.0 : 0.0;
    const double ld = (q_day - y) * (q_day - y), lw = (q_week - y) * (q_week - y);
    day_loss += ld;
    week_loss += lw;
    const double d = lw - ld;
    sum_d += d;
    sum_dd += d * d;
    week_sum += d;
    if (d != 0) ++out.scored;
    today.push_back(f);
  }
  flush();
  close_week();
  if (firsts > 0) {
    out.day_brier = day_loss / firsts;
    out.week_brier = week_loss / firsts;
  }
  out.evidence = sum_dd > 0 ? -sum_d / std::sqrt(sum_dd) : 0.0;
  out.weekly = out.evidence >= options.weekly_evidence && out.weeks_won >= 2;
  return out;
}

Json WeeklyChoice::to_json() const {
  return Json{{"weekly", weekly},       {"evidence", evidence},   {"scored", scored},
              {"weeks_won", weeks_won}, {"day_brier", day_brier}, {"week_brier", week_brier}};
}

Result<WeeklyChoice> WeeklyChoice::from_json(const Json& j) {
  if (!j.is_object() || !j.contains("weekly") || !j["weekly"].is_boolean()) {
    return Error::invalid("model: 'weekly.weekly' must be true or false");
  }
  WeeklyChoice c;
  c.weekly = j["weekly"].get<bool>();
  double scored = 0, weeks_won = 0;
  for (auto [key, out] :
       {std::pair{"evidence", &c.evidence}, std::pair{"scored", &scored}, std::pair{"weeks_won", &weeks_won},
        std::pair{"day_brier", &c.day_brier}, std::pair{"week_brier", &c.week_brier}}) {
    auto v = json_number(j, key);
    if (!v) return v.error().with_context("weekly");
    *out = *v;
  }
  c.scored = static_cast<int>(scored);
  c.weeks_won = static_cast<int>(weeks_won);
  return c;
}

}  // namespace rondo::learn
