#include "run_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "rondo/plan/travel_evaluation.h"

namespace rondo::app {

Json task_summary(const fleet::Fleet& fleet) {
  int completed = 0, pending = 0;
  std::map<std::string, std::map<std::string, int>> by_state;  // sorted: a stable report
  std::map<std::string, int> dropped_after_leaving;
  for (const auto& [id, r] : fleet.tasks()) {
    if (!is_final(r.state)) {
      ++pending;
      continue;
    }
    if (r.state == TaskState::kSucceeded) {
      ++completed;
      continue;
    }
    ++by_state[to_string(r.state)][std::string(exec::to_string(r.outcome))];
    if (r.state == TaskState::kDropped && r.started) ++dropped_after_leaving[std::string(exec::to_string(r.outcome))];
  }
  Json tasks = Json::object();
  tasks["added"] = fleet.tasks().size();
  tasks["completed"] = completed;
  tasks["pending"] = pending;
  for (const char* state : {"failed", "dropped", "cancelled"}) {
    Json reasons = Json::object();
    for (const auto& [reason, n] : by_state[state]) reasons[reason] = n;
    tasks[state] = reasons;
  }
  // Of the dropped: those the robot had left for at least once (their journey came back, and the
  // window could not be met again), by code.
  Json after = Json::object();
  for (const auto& [reason, n] : dropped_after_leaving) after[reason] = n;
  tasks["dropped_after_leaving"] = after;
  return tasks;
}

// Tasks written as formulas (docs/ltl.md): how many, satisfied (the journey reached a node that
// satisfies the formula), succeeded, failed and dropped by code, and the satisfying journeys' mean
// time against the mean the plan expected when each left. Nothing when the run had none.
std::optional<Json> spec_summary(const fleet::Fleet& fleet) {
  int added = 0, satisfied = 0, succeeded = 0, pending = 0, journeys = 0;
  double taken_s = 0, expected_s = 0;
  std::map<std::string, std::map<std::string, int>> ended;
  for (const TaskId& id : fleet.task_order()) {
    const exec::TaskRecord& r = fleet.tasks().at(id);
    if (!r.task.has_spec()) continue;
    ++added;
    if (!r.spec_place.empty()) ++satisfied;
    if (r.spec_journey) {
      ++journeys;
      expected_s += to_seconds(r.spec_journey->first);
      taken_s += to_seconds(r.spec_journey->second);
    }
    if (r.state == TaskState::kSucceeded)
      ++succeeded;
    else if (!is_final(r.state))
      ++pending;
    else
      ++ended[to_string(r.state)][std::string(exec::to_string(r.outcome))];
  }
  if (added == 0) return std::nullopt;
  Json j{{"added", added}, {"satisfied", satisfied}, {"succeeded", succeeded}, {"pending", pending}};
  for (const char* state : {"failed", "dropped", "cancelled"}) {
    Json codes = Json::object();
    for (const auto& [code, n] : ended[state]) codes[code] = n;
    j[state] = codes;
  }
  const auto round1 = [](double x) { return std::round(x * 10) / 10; };
  Json time{{"journeys", journeys}};
  if (journeys > 0) {
    time["mean_s"] = round1(taken_s / journeys);
    time["mean_expected_s"] = round1(expected_s / journeys);
    if (expected_s > 0) time["ratio"] = std::round(taken_s / expected_s * 1000) / 1000;
  }
  j["journey_time"] = time;
  return j;
}

// Delivery jobs by how their drop ended (the job's own drop, not a return made later): delivered,
// failed or cancelled by code, pending; returns made and done; what is on board at the end.
// Nothing when the run had no delivery.
std::optional<Json> delivery_summary(const fleet::Fleet& fleet) {
  std::map<std::string, std::vector<const exec::TaskRecord*>> drops;  // job -> its drops, in order added
  for (const TaskId& id : fleet.task_order()) {
    const exec::TaskRecord& r = fleet.tasks().at(id);
    if (r.task.delivery && r.task.delivery->role == DeliveryRole::kDrop) drops[r.task.delivery->job].push_back(&r);
  }
  if (drops.empty()) return std::nullopt;
  int delivered = 0, pending = 0, returns = 0, returned = 0, late = 0;
  double lateness_s = 0;  // summed over delivered jobs: how far past its deadline the drop ended
  std::map<std::string, std::map<std::string, int>> ended;
  for (const auto& [job, list] : drops) {
    const exec::TaskRecord& own = *list.front();
    if (own.state == TaskState::kSucceeded) {
      ++delivered;
      if (own.task.window && own.ended && *own.ended > own.task.window->deadline) {
        ++late;
        lateness_s += to_seconds(*own.ended - own.task.window->deadline);
      }
    } else if (!is_final(own.state))
      ++pending;
    else
      ++ended[to_string(own.state)][std::string(exec::to_string(own.outcome))];
    for (std::size_t i = 1; i < list.size(); ++i) {
      ++returns;
      if (list[i]->state == TaskState::kSucceeded) ++returned;
    }
  }
  Json j{{"jobs", drops.size()},
         {"delivered", delivered},
         {"pending", pending},
         {"delivered_late", late},
         {"mean_lateness_s", delivered > 0 ? std::round(lateness_s / delivered * 10) / 10 : 0.0}};
  for (const char* state : {"failed", "cancelled", "dropped"}) {
    Json codes = Json::object();
    for (const auto& [code, n] : ended[state]) codes[code] = n;
    j[state] = codes;
  }
  j["returns"] = Json{{"made", returns}, {"done", returned}};
  Json on_board = Json::array();
  for (const auto& robot : fleet.robots())
    for (const exec::OnBoard& o : robot->on_board()) on_board.push_back(Json{{"job", o.job}, {"object", o.object}});
  j["on_board_at_end"] = on_board;
  return j;
}

// What the door observations did (docs/executor.md, "Assumptions" and "Opportunities"); nothing
// when the robot saw no door (no door sensor), so such reports stay as they were.
std::optional<Json> assumption_summary(const fleet::Fleet& fleet, Time end) {
  exec::AssumptionStats a;
  for (const auto& robot : fleet.robots()) {
    const exec::AssumptionStats& r = robot->assumption_stats();
    a.door_observations += r.door_observations;
    a.broken += r.broken;
    a.reschedules += r.reschedules;
    a.opportunities_taken += r.opportunities_taken;
    a.opportunities_declined += r.opportunities_declined;
    a.failed_blocked += r.failed_blocked;
    a.retries += r.retries;
  }
  if (a.door_observations == 0) return std::nullopt;
  Json doors = Json::object();
  // The learned chance that each door the schedules rested on is open, at a few hours of the last
  // day (local time), against the rhythm of the world file.
  const TimeZone& zone = fleet.zone();
  const auto day = zone.local_date(end - seconds(1));
  for (const std::string& door : fleet.door_names()) {
    Json by_hour = Json::object();
    for (int h : {8, 10, 12, 13, 16, 20})
      if (const auto p = fleet.door_open_probability(door, zone.at(day, hours(h))))
        by_hour[fmt::format("{:02}:00", h)] = std::round(*p * 1000) / 1000;
    if (!by_hour.empty()) doors[door] = by_hour;
  }
  return Json{{"door_observations", a.door_observations},
              {"broken", a.broken},
              {"reschedules", a.reschedules},
              {"opportunities_taken", a.opportunities_taken},
              {"opportunities_declined", a.opportunities_declined},
              {"retries", a.retries},
              {"failed_blocked", a.failed_blocked},
              {"door_open_learned", doors}};
}

// What happened on the way that is not a final outcome: preemptions (the task went back to the
// queue), drops for now and re-offers, cancels that waited, robot faults; each by outcome code.
Json event_summary(const fleet::Fleet& fleet) {
  const auto& counts = fleet.book().event_counts();
  const auto by_code = [&](std::string_view event, std::initializer_list<exec::Outcome> only = {}) {
    Json j = Json::object();
    const auto it = counts.find(std::string(event));
    if (it == counts.end()) return j;
    for (const auto& [code, n] : it->second)
      if (only.size() == 0 || std::find(only.begin(), only.end(), code) != only.end())
        j[std::string(exec::to_string(code))] = n;
    return j;
  };
  using exec::EventKind;
  const std::string_view queued = to_string(TaskState::kQueued);
  return Json{{"preempted", by_code(queued, {exec::Outcome::kPreemptedOnDemand, exec::Outcome::kOutranked})},
              {"interrupted", by_code(queued, {exec::Outcome::kInterrupted})},
              {"dropped_for_now", by_code(to_string(EventKind::kDroppedForNow))},
              {"re_offered", by_code(to_string(EventKind::kReOffered))},
              {"cancel_pending", by_code(to_string(EventKind::kCancelPending))},
              {"robot_faults", by_code(to_string(EventKind::kFault))},
              {"rejected_requests", by_code(to_string(EventKind::kRejected))}};
}

// The battery (docs/executor.md, "Battery"): the lowest state of charge read, the stays on the
// charger, the falls below the hard threshold, the tasks moved, dropped or failed for charging
// (events with the code `charging`, by event), and the learned costs with their standard errors.
namespace {

// The tasks moved, dropped or failed for charging (events with the code `charging`), by event.
Json for_charging(const exec::TaskBook& book) {
  Json j = Json::object();
  for (const auto& [event, codes] : book.event_counts()) {
    const auto it = codes.find(exec::Outcome::kCharging);
    if (it != codes.end() && event != to_string(exec::EventKind::kBatteryLow) &&
        event != to_string(exec::EventKind::kCharged))
      j[event] = it->second;
  }
  return j;
}

double round_to(double v, double digits) {
  return std::round(v * digits) / digits;
}

// One robot's battery: what it read and what it learned of the costs.
Json robot_battery(const exec::Executor& executor) {
  const exec::BatteryFigures f = executor.battery_figures();
  const auto rates = [&](const exec::BatteryRates& r) {
    return Json{{"per_km", round_to(r.per_metre * 1000, 1e5)},
                {"moving_per_hour", round_to(r.moving_per_hour, 1e5)},
                {"acting_per_hour", round_to(r.acting_per_hour, 1e5)},
                {"idle_per_hour", round_to(r.idle_per_hour, 1e5)},
                {"charging_per_hour", round_to(r.charging_per_hour, 1e5)}};
  };
  Json j{{"readings", f.readings},
         {"lowest", round_to(f.lowest, 1e4)},
         {"charges", f.charges},
         {"on_charger_s", to_seconds(f.on_charger)},
         {"below_threshold", f.low_battery},
         {"empty_readings", f.empty_readings},
         {"for_charging", for_charging(executor.book())},
         {"learned", rates(f.learned)},
         {"standard_errors", rates(f.standard_errors)},
         {"intervals_learned", f.intervals_learned}};
  if (f.lowest_at) j["lowest_at"] = format_time(*f.lowest_at);
  return j;
}

}  // namespace

Json battery_summary(const fleet::Fleet& fleet) {
  if (fleet.robots().size() == 1) return robot_battery(fleet.robot());
  exec::BatteryFigures sum;
  for (const auto& robot : fleet.robots()) {
    const exec::BatteryFigures f = robot->battery_figures();
    sum.readings += f.readings;
    if (f.readings > 0 && f.lowest < sum.lowest) sum.lowest = f.lowest, sum.lowest_at = f.lowest_at;
    sum.charges += f.charges;
    sum.on_charger += f.on_charger;
    sum.low_battery += f.low_battery;
    sum.empty_readings += f.empty_readings;
  }
  Json j{{"readings", sum.readings},
         {"lowest", round_to(sum.lowest, 1e4)},
         {"charges", sum.charges},
         {"on_charger_s", to_seconds(sum.on_charger)},
         {"below_threshold", sum.low_battery},
         {"empty_readings", sum.empty_readings},
         {"for_charging", for_charging(fleet.book())}};
  if (sum.lowest_at) j["lowest_at"] = format_time(*sum.lowest_at);
  return j;
}

namespace {

Json time_use(const exec::ExecutorStats& s, Duration charging) {
  return Json{{"busy", to_seconds(s.busy)},
              {"travelling", to_seconds(s.travelling)},
              {"acting", to_seconds(s.acting)},
              {"waiting", to_seconds(s.waiting)},
              {"charging", to_seconds(charging)}};
}

}  // namespace

Json robot_summaries(const fleet::Fleet& fleet, const RunFigures& figures) {
  std::map<std::string, std::map<std::string, int>> tasks;  // robot -> state -> count
  for (const auto& [id, r] : fleet.tasks()) {
    std::map<std::string, int>& t = tasks[r.robot];
    ++t["allocated"];
    ++t[is_final(r.state) ? std::string(to_string(r.state)) : "pending"];
  }
  Json robots = Json::array();
  for (const auto& robot : fleet.robots()) {
    const std::string& name = robot->name();
    Json t = Json::object();
    for (const char* key : {"allocated", "succeeded", "failed", "dropped", "cancelled", "pending"})
      t[key] = tasks[name][key];
    const auto distance = figures.distance_by_robot.find(name);
    const auto charging = figures.charging_by_robot.find(name);
    robots.push_back(Json{
        {"name", name},
        {"tasks", t},
        {"distance_m", std::round((distance == figures.distance_by_robot.end() ? 0.0 : distance->second) * 10) / 10},
        {"time_s",
         time_use(robot->stats(), charging == figures.charging_by_robot.end() ? Duration{0} : charging->second)},
        {"battery", robot_battery(*robot)}});
  }
  return robots;
}

Json travel_table(const map::TopoMap& map, std::span<const Traversal> log, Time start, int days,
                  const TimeZone& zone) {
  const Duration week = hours(24 * 7);
  plan::TravelEvaluationOptions o;
  o.models.episode.episode.zone = zone;
  if (days >= 21) {
    // The protocol: the estimates of week 3 from models trained on no data, week 1, weeks 1-2.
    o.trainings = {{"none", start, start}, {"week1", start, start + week}, {"weeks1-2", start, start + 2 * week}};
    o.test = {"week3", start + 2 * week, start + 3 * week};
  } else if (days >= 14) {
    // A two-week run: week 2 from no data and from week 1.
    o.trainings = {{"none", start, start}, {"week1", start, start + week}};
    o.test = {"week2", start + week, start + 2 * week};
  } else {
    return Json{{"note", "Table I needs at least 14 days (train on week 1, test on week 2)"}};
  }
  auto e = plan::evaluate_travel(map, log, o);
  if (!e) return Json{{"note", e.error().message}};
  return plan::travel_evaluation_to_json(*e);
}

// The error of the travel estimates the executor used when it left for each task (the online
// model, when on), next to what the nightly snapshot alone said for the same journeys, in Table
// I's columns: relative error (estimate - actual) / actual of the navigations that arrived.
Json live_estimates(std::span<const exec::NavigationRecord> navigations) {
  std::vector<double> used, offline;
  double used_sum = 0, offline_sum = 0, actual_sum = 0;
  for (const exec::NavigationRecord& n : navigations) {
    if (!n.arrived || n.actual <= Duration{0}) continue;
    const double actual = to_seconds(n.actual);
    used.push_back((to_seconds(n.expected) - actual) / actual);
    offline.push_back((to_seconds(n.offline_expected) - actual) / actual);
    used_sum += to_seconds(n.expected);
    offline_sum += to_seconds(n.offline_expected);
    actual_sum += actual;
  }
  const auto row = [actual_sum](const plan::ErrorSummary& e, double sum) {
    return Json{{"q10", e.q10},   {"q25", e.q25},
                {"q75", e.q75},   {"q90", e.q90},
                {"mean_abs", e.mean_abs}, {"std", e.std},
                {"count", e.count}, {"sum_ratio", actual_sum > 0 ? sum / actual_sum : 0.0}};
  };
  return Json{{"used", row(plan::summarize_errors(used), used_sum)},
              {"offline_snapshot", row(plan::summarize_errors(offline), offline_sum)}};
}

namespace {

// The robot events of the executor's own journeys (docs/executor.md, "Journeys"), and their keys.
using exec::EventKind;
constexpr std::array<std::pair<EventKind, const char*>, 5> kOwnJourney{{{EventKind::kDeparted, "departed"},
                                                                        {EventKind::kArrived, "arrived"},
                                                                        {EventKind::kWaits, "waits"},
                                                                        {EventKind::kGaveUp, "gave_up"},
                                                                        {EventKind::kStopped, "stopped"}}};

// A week's own journeys: each event's count, 0 when none.
Json own_journeys(const std::map<std::string, int>& counts) {
  Json j = Json::object();
  for (const auto& [event, key] : kOwnJourney) {
    const auto it = counts.find(std::string(to_string(event)));
    j[key] = it == counts.end() ? 0 : it->second;
  }
  return j;
}

}  // namespace

Json weekly_summary(std::span<const Traversal> log, std::span<const store::Event> events, Time from, Time to) {
  struct Week {
    int attempts = 0, failed = 0;
    int task_journeys = 0;  // a task's departures (to its place or its end place)
    std::map<std::string, int> failed_by_edge, navigation_failures;
    std::map<std::string, int> own_journeys;  // the executor's own journeys' robot events, by event
  };
  const Duration week = hours(24 * 7);
  std::vector<Week> weeks(static_cast<std::size_t>(std::max<std::int64_t>(1, (to - from + week - Duration{1}) / week)));
  const auto week_of = [&](Time t) -> Week* {
    if (t < from || t >= to) return nullptr;
    return &weeks[static_cast<std::size_t>((t - from) / week)];
  };
  for (const Traversal& t : log) {
    Week* w = week_of(t.start);
    if (w == nullptr) continue;
    ++w->attempts;
    if (!t.success) {
      ++w->failed;
      ++w->failed_by_edge[t.edge_id];
    }
  }
  static constexpr std::array<exec::Outcome, 4> kNavigation{exec::Outcome::kNavigationOverrun,
                                                            exec::Outcome::kNavigationGaveUp, exec::Outcome::kNoRoute,
                                                            exec::Outcome::kNoRouteNow};
  for (const store::Event& e : events) {
    Week* w = week_of(e.time);
    if (w == nullptr) continue;
    if (e.subject == store::Subject::kTask && e.code == exec::to_string(exec::Outcome::kDeparted)) ++w->task_journeys;
    const std::optional<EventKind> kind = exec::parse_event_kind(e.event);
    if (e.subject == store::Subject::kRobot && kind &&
        std::any_of(kOwnJourney.begin(), kOwnJourney.end(), [&](const auto& own) { return own.first == *kind; }))
      ++w->own_journeys[e.event];
    if (e.event != to_string(TaskState::kFailed)) continue;
    const std::optional<exec::Outcome> code = exec::parse_outcome(e.code);
    if (code && std::find(kNavigation.begin(), kNavigation.end(), *code) != kNavigation.end())
      ++w->navigation_failures[e.code];
  }
  Json out = Json::array();
  for (std::size_t i = 0; i < weeks.size(); ++i) {
    const Week& w = weeks[i];
    Json row{{"week", i + 1},
             {"from", format_time(from + week * static_cast<std::int64_t>(i))},
             {"edge_attempts", w.attempts},
             {"failed_attempts", w.failed},
             {"navigation_failures", w.navigation_failures},
             {"journeys", {{"task", w.task_journeys}, {"own", own_journeys(w.own_journeys)}}}};
    // The edge that failed most (the first in id order among equals: a stable report).
    const auto most = std::max_element(w.failed_by_edge.begin(), w.failed_by_edge.end(),
                                       [](const auto& a, const auto& b) { return a.second < b.second; });
    if (most != w.failed_by_edge.end()) row["most_failed_edge"] = Json{{"edge", most->first}, {"failed", most->second}};
    out.push_back(std::move(row));
  }
  return out;
}

Json run_report(const fleet::Fleet& fleet, const RunFigures& figures) {
  exec::ExecutorStats s;  // the fleet's totals
  std::vector<exec::NavigationRecord> navigations;
  for (const auto& robot : fleet.robots()) {
    const exec::ExecutorStats& r = robot->stats();
    s.busy += r.busy;
    s.travelling += r.travelling;
    s.acting += r.acting;
    s.waiting += r.waiting;
    s.schedules += r.schedules;
    navigations.insert(navigations.end(), robot->navigations().begin(), robot->navigations().end());
  }
  Json j = Json::object();
  j["from"] = format_time(figures.from);
  j["to"] = format_time(figures.to);
  j["tasks"] = task_summary(fleet);
  j["events"] = event_summary(fleet);
  if (std::optional<Json> d = delivery_summary(fleet)) j["deliveries"] = *d;
  if (std::optional<Json> sp = spec_summary(fleet)) j["spec_tasks"] = *sp;
  if (std::optional<Json> a = assumption_summary(fleet, figures.to)) j["assumptions"] = *a;
  const std::vector<exec::LearnedActionTime> learned = fleet.loading_times();
  if (!learned.empty()) {
    Json times = Json::array();
    for (const exec::LearnedActionTime& t : learned)
      times.push_back(Json{{"action", t.action}, {"place", t.place}, {"samples", t.samples},
                           {"learned_s", std::round(t.expected_seconds * 10) / 10}});
    j["loading_times"] = times;
  }
  j["navigation"] = Json{{"attempts", figures.navigation_attempts},
                         {"successes", figures.navigation_successes},
                         {"distance_m", std::round(figures.distance_m * 10) / 10}};
  j["time_s"] = time_use(s, figures.charging);
  j["scheduler_calls"] = s.schedules;
  j["model_refits"] = fleet.refits();
  j["live_estimates"] = live_estimates(navigations);
  j["battery"] = battery_summary(fleet);
  j["robots"] = robot_summaries(fleet, figures);
  return j;
}

Json reference_figures(const ReferenceFigures& reference, const Json& report, int days) {
  const auto per_day = [](double v, int n) { return round_to(v / n, 10); };
  Json real{{"name", reference.name}, {"days", reference.days}};
  const std::int64_t added = report["tasks"]["added"].get<std::int64_t>();
  const std::int64_t completed = report["tasks"]["completed"].get<std::int64_t>();
  const double km = report["navigation"]["distance_m"].get<double>() / 1000.0;
  Json run{{"days", days}, {"tasks_added", added}, {"tasks_completed", completed}, {"distance_km", round_to(km, 100)}};
  if (reference.tasks) {
    real["tasks"] = *reference.tasks;
    real["tasks_per_day"] = per_day(static_cast<double>(*reference.tasks), reference.days);
    run["tasks_completed_per_day"] = per_day(static_cast<double>(completed), days);
  }
  if (reference.distance_km) {
    real["distance_km"] = *reference.distance_km;
    real["km_per_day"] = round_to(*reference.distance_km / reference.days, 100);
    run["km_per_day"] = round_to(km / days, 100);
  }
  return Json{{"real", std::move(real)}, {"run", std::move(run)}};
}

DayPicture day_picture(const exec::Executor& executor, const std::string& title, Time from, Time to,
                       const TimeZone& zone, bool every_task) {
  DayPicture day{.title = title, .from = from, .to = to, .zone = zone, .rows = {}, .charging = {}};
  for (const TaskId& id : executor.task_order()) {
    const exec::TaskRecord& r = executor.tasks().at(id);
    if (!every_task && r.robot != executor.name()) continue;
    const Time a = r.task.window ? r.task.window->release : r.added;
    const Time b = r.task.window ? r.task.window->deadline : r.ended.value_or(r.added);
    if (b < from || a >= to) continue;
    DayRow row{.task_id = id, .label = r.task.activity.empty() ? id : r.task.activity, .window = r.task.window,
               .planned = {}, .actual = {}, .outcome = {}};
    if (r.planned_start && r.planned_end) row.planned = std::make_pair(*r.planned_start, *r.planned_end);
    if (r.started && r.ended) row.actual = std::make_pair(*r.started, *r.ended);
    row.outcome = r.state == TaskState::kSucceeded || !is_final(r.state)
                      ? std::string(to_string(r.state))
                      : fmt::format("{}: {}", to_string(r.state), r.reason);
    day.rows.push_back(std::move(row));
  }
  return day;
}

}  // namespace rondo::app
