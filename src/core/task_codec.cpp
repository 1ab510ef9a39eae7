#include "rondo/core/task_codec.h"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "task_problem.h"
#include "time_parsing.h"

namespace rondo {
namespace {

constexpr std::array<std::string_view, 7> kDayNames = {"sun", "mon", "tue", "wed", "thu", "fri", "sat"};
constexpr std::array<std::string_view, 7> kLongDayNames = {"sunday",   "monday", "tuesday", "wednesday",
                                                           "thursday", "friday", "saturday"};

Result<std::string> optional_string(const Field& f, std::string_view key, std::string fallback = "") {
  auto v = f.optional(key);
  if (!v) return fallback;
  return v->as_string();
}

}  // namespace

// An action is a name, or {name, args: {key: scalar}}.
Result<Action> decode_action(const Field& f) {
  if (f.is_string()) {
    RONDO_ASSIGN_OR_RETURN(auto name, f.as_string());
    if (name.empty()) return f.error("an action needs a name");
    return Action{name, {}};
  }
  RONDO_RETURN_IF_ERROR(f.expect_keys({"name", "args"}));
  Action a;
  RONDO_ASSIGN_OR_RETURN(auto name_field, f.required("name"));
  RONDO_ASSIGN_OR_RETURN(a.name, name_field.as_string());
  if (auto args = f.optional("args")) {
    RONDO_ASSIGN_OR_RETURN(auto members, args->members());
    for (const auto& [key, value] : members) {
      if (value.is_string()) {
        a.args[key] = value.json().get<std::string>();
      } else if (value.json().is_number() || value.json().is_boolean()) {
        a.args[key] = value.json().dump();
      } else {
        return value.error("an action argument must be text, a number or true/false");
      }
    }
  }
  return a;
}

namespace {

Result<Delivery> decode_delivery(const Field& f) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"job", "role", "object", "appearance", "load"}));
  Delivery d;
  RONDO_ASSIGN_OR_RETURN(auto job, f.required("job"));
  RONDO_ASSIGN_OR_RETURN(d.job, job.as_string());
  RONDO_ASSIGN_OR_RETURN(auto role_field, f.required("role"));
  RONDO_ASSIGN_OR_RETURN(auto role_text, role_field.as_string());
  auto role = parse_delivery_role(role_text);
  if (!role) return role_field.error(role.error().message);
  d.role = *role;
  RONDO_ASSIGN_OR_RETURN(auto object, f.required("object"));
  RONDO_ASSIGN_OR_RETURN(d.object, object.as_string());
  RONDO_ASSIGN_OR_RETURN(d.appearance, optional_string(f, "appearance", d.object));
  if (auto load = f.optional("load")) {
    RONDO_ASSIGN_OR_RETURN(auto l, load->as_int());
    if (l < 1 || l > 1'000'000) return load->error("load must be from 1 to 1000000");
    d.load = static_cast<int>(l);
  }
  return d;
}

// Everything of a task except id, kind and window, which tasks and routine templates treat
// differently.
Status check_place(const Field& f, std::string_view key, const std::string& node, const PlaceCheck* places) {
  if (!places || !places->known || node.empty() || places->known(node)) return {};
  return f.error_at(key, fmt::format("node '{}' is not on the map '{}'", node, places->map_name));
}

Status decode_task_body(const Field& f, Task& t, const PlaceCheck* places) {
  RONDO_ASSIGN_OR_RETURN(t.activity, optional_string(f, "activity"));
  if (auto d = f.optional("duration")) {
    RONDO_ASSIGN_OR_RETURN(t.duration, d->as_duration());
  }
  if (auto p = f.optional("priority")) {
    RONDO_ASSIGN_OR_RETURN(auto priority, p->as_int());
    if (priority < -1'000'000 || priority > 1'000'000) return p->error("priority must be from -1000000 to 1000000");
    t.priority = static_cast<int>(priority);
  }
  RONDO_ASSIGN_OR_RETURN(t.start_node, optional_string(f, "start_node"));
  RONDO_ASSIGN_OR_RETURN(t.end_node, optional_string(f, "end_node"));
  RONDO_RETURN_IF_ERROR(check_place(f, "start_node", t.start_node, places));
  RONDO_RETURN_IF_ERROR(check_place(f, "end_node", t.end_node, places));
  if (auto spec = f.optional("spec")) {
    RONDO_ASSIGN_OR_RETURN(t.spec, spec->as_string());
    if (t.spec.empty()) return spec->error("a spec is a formula over the map's nodes: it must not be empty");
    if (places && places->spec) {
      if (Status ok = places->spec(t.spec); !ok) return spec->error(ok.error().message);
    }
  }
  if (auto actions = f.optional("actions")) {
    RONDO_ASSIGN_OR_RETURN(auto items, actions->items());
    for (const auto& item : items) {
      RONDO_ASSIGN_OR_RETURN(auto a, decode_action(item));
      t.actions.push_back(std::move(a));
    }
  }
  if (auto i = f.optional("interruptible")) {
    RONDO_ASSIGN_OR_RETURN(t.interruptible, i->as_bool());
  }
  if (auto d = f.optional("delivery")) {
    RONDO_ASSIGN_OR_RETURN(auto delivery, decode_delivery(*d));
    t.delivery = std::move(delivery);
  }
  RONDO_ASSIGN_OR_RETURN(t.robot, optional_string(f, "robot"));
  if (f.has("robot") && t.robot.empty()) return f.error_at("robot", "a robot's name must not be empty");
  if (auto after = f.optional("after")) {
    RONDO_ASSIGN_OR_RETURN(auto items, after->items());
    for (const auto& item : items) {
      RONDO_ASSIGN_OR_RETURN(auto id, item.as_string());
      t.after.push_back(std::move(id));
    }
  }
  return {};
}

Result<std::vector<std::chrono::weekday>> decode_days(const Field& f) {
  std::vector<std::chrono::weekday> days;
  auto add_range = [&](unsigned from, unsigned to) {
    for (unsigned d = from; d <= to; ++d) days.emplace_back(d % 7);
  };
  if (f.is_string()) {
    RONDO_ASSIGN_OR_RETURN(auto word, f.as_string());
    if (word == "weekdays") {
      add_range(1, 5);
    } else if (word == "weekends") {
      add_range(6, 7);
    } else if (word == "daily") {
      add_range(1, 7);
    } else {
      return f.error("expected a list of days (mon, tue, ...) or one of weekdays, weekends, daily");
    }
    return days;
  }
  RONDO_ASSIGN_OR_RETURN(auto items, f.items());
  for (const auto& item : items) {
    RONDO_ASSIGN_OR_RETURN(auto name, item.as_string());
    std::string lower;
    for (char c : name) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    bool found = false;
    for (unsigned d = 0; d < 7 && !found; ++d) {
      if (lower == kDayNames[d] || lower == kLongDayNames[d]) {
        days.emplace_back(d);
        found = true;
      }
    }
    if (!found) return item.error("unknown day '" + name + "' (expected mon, tue, wed, thu, fri, sat or sun)");
  }
  return days;
}

// Days sorted Monday first, without repeats; all seven days become "every day" (empty).
std::vector<std::chrono::weekday> normalise_days(std::vector<std::chrono::weekday> days) {
  std::vector<std::chrono::weekday> out;
  for (unsigned iso = 1; iso <= 7; ++iso) {
    const std::chrono::weekday wd{iso % 7};
    if (std::find(days.begin(), days.end(), wd) != days.end()) out.push_back(wd);
  }
  if (out.size() == 7) out.clear();
  return out;
}

Result<std::chrono::year_month_day> decode_date(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(auto text, f.as_string());
  auto d = detail::parse_iso_date(text);
  if (!d) return f.error(d.error().message);
  return *d;
}

Result<Duration> decode_time_of_day(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(auto text, f.as_string());
  auto d = detail::parse_time_of_day(text);
  if (!d) return f.error(d.error().message);
  return *d;
}

std::string format_date(std::chrono::year_month_day d) {
  return fmt::format("{:04}-{:02}-{:02}", static_cast<int>(d.year()), static_cast<unsigned>(d.month()),
                     static_cast<unsigned>(d.day()));
}


}  // namespace

Result<Task> decode_task(const Field& f, const TimeZone* zone, const PlaceCheck* places) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"id", "activity", "kind", "window", "duration", "priority", "start_node",
                                       "end_node", "spec", "actions", "interruptible", "delivery", "after", "robot"}));
  Task t;
  RONDO_ASSIGN_OR_RETURN(auto id, f.required("id"));
  RONDO_ASSIGN_OR_RETURN(t.id, id.as_string());
  if (auto k = f.optional("kind")) {
    RONDO_ASSIGN_OR_RETURN(auto text, k->as_string());
    auto kind = parse_task_kind(text);
    if (!kind) return k->error(kind.error().message);
    t.kind = *kind;
  }
  if (auto w = f.optional("window")) {
    RONDO_RETURN_IF_ERROR(w->expect_keys({"release", "deadline"}));
    RONDO_ASSIGN_OR_RETURN(auto release, w->required("release"));
    RONDO_ASSIGN_OR_RETURN(auto deadline, w->required("deadline"));
    TimeWindow window;
    RONDO_ASSIGN_OR_RETURN(window.release, release.as_time(zone));
    RONDO_ASSIGN_OR_RETURN(window.deadline, deadline.as_time(zone));
    t.window = window;
  }
  RONDO_RETURN_IF_ERROR(decode_task_body(f, t, places));
  if (auto p = detail::first_problem(t)) return f.error_at(p->field, p->message);
  return t;
}

Result<Routine> decode_routine(const Field& f, const PlaceCheck* places) {
  RONDO_RETURN_IF_ERROR(
      f.expect_keys({"name", "task", "window", "every", "days", "days_off", "dates_off", "first_day", "last_day"}));
  Routine r;
  RONDO_ASSIGN_OR_RETURN(auto name, f.required("name"));
  RONDO_ASSIGN_OR_RETURN(r.name, name.as_string());
  RONDO_ASSIGN_OR_RETURN(auto task, f.required("task"));
  RONDO_RETURN_IF_ERROR(task.expect_keys(
      {"activity", "duration", "priority", "start_node", "end_node", "spec", "actions", "interruptible", "robot"}));
  RONDO_RETURN_IF_ERROR(decode_task_body(task, r.task, places));
  RONDO_ASSIGN_OR_RETURN(auto window, f.required("window"));
  RONDO_RETURN_IF_ERROR(window.expect_keys({"from", "to"}));
  RONDO_ASSIGN_OR_RETURN(auto from, window.required("from"));
  RONDO_ASSIGN_OR_RETURN(auto to, window.required("to"));
  RONDO_ASSIGN_OR_RETURN(r.window_start, decode_time_of_day(from));
  RONDO_ASSIGN_OR_RETURN(r.window_end, decode_time_of_day(to));
  if (auto every = f.optional("every")) {
    RONDO_ASSIGN_OR_RETURN(auto e, every->as_duration());
    r.every = e;
  }
  if (f.has("days") && f.has("days_off")) {
    return f.error_at("days_off", "give either the days the routine runs or its days off, not both");
  }
  if (auto days = f.optional("days")) {
    RONDO_ASSIGN_OR_RETURN(auto list, decode_days(*days));
    if (list.empty()) return days->error("an empty list of days: the routine would never run");
    r.days = normalise_days(std::move(list));
  }
  if (auto off = f.optional("days_off")) {
    RONDO_ASSIGN_OR_RETURN(auto list, decode_days(*off));
    std::vector<std::chrono::weekday> on;
    for (unsigned d = 0; d < 7; ++d) {
      if (std::find(list.begin(), list.end(), std::chrono::weekday{d}) == list.end()) on.emplace_back(d);
    }
    if (on.empty()) return off->error("every day is off: the routine would never run");
    r.days = normalise_days(std::move(on));
  }
  if (auto dates = f.optional("dates_off")) {
    RONDO_ASSIGN_OR_RETURN(auto items, dates->items());
    for (const auto& item : items) {
      RONDO_ASSIGN_OR_RETURN(auto d, decode_date(item));
      if (std::find(r.dates_off.begin(), r.dates_off.end(), d) == r.dates_off.end()) r.dates_off.push_back(d);
    }
    std::sort(r.dates_off.begin(), r.dates_off.end());
  }
  if (auto d = f.optional("first_day")) {
    RONDO_ASSIGN_OR_RETURN(auto day, decode_date(*d));
    r.first_day = day;
  }
  if (auto d = f.optional("last_day")) {
    RONDO_ASSIGN_OR_RETURN(auto day, decode_date(*d));
    r.last_day = day;
  }
  if (auto p = detail::first_problem(r)) return f.error_at(p->field, p->message);
  return r;
}

Result<TaskFile> decode_task_file(const Document& doc, const PlaceCheck* places) {
  const Field root = doc.root();
  if (root.is_null()) return root.error("the file is empty: expected 'tasks' and/or 'routines'");
  RONDO_RETURN_IF_ERROR(root.expect_keys({"timezone", "tasks", "routines"}));
  TaskFile file;
  if (auto tz = root.optional("timezone")) {
    RONDO_ASSIGN_OR_RETURN(auto name, tz->as_string());
    auto zone = TimeZone::named(name);
    if (!zone) return tz->error(zone.error().message);
    file.zone = *zone;
  }
  const TimeZone* zone = file.zone ? &*file.zone : nullptr;
  if (auto tasks = root.optional("tasks")) {
    RONDO_ASSIGN_OR_RETURN(auto items, tasks->items());
    for (const auto& item : items) {
      RONDO_ASSIGN_OR_RETURN(auto t, decode_task(item, zone, places));
      file.tasks.push_back(std::move(t));
    }
    if (auto p = detail::first_problem(file.tasks)) {
      return items[p->index].error_at(p->problem.field, p->problem.message);
    }
  }
  if (auto routines = root.optional("routines")) {
    if (!file.zone) {
      return routines->error("routines run at local times of day: give the file a 'timezone' such as Europe/London");
    }
    RONDO_ASSIGN_OR_RETURN(auto items, routines->items());
    for (std::size_t i = 0; i < items.size(); ++i) {
      RONDO_ASSIGN_OR_RETURN(auto r, decode_routine(items[i], places));
      for (const auto& other : file.routines) {
        if (other.name == r.name) return items[i].error_at("name", "duplicate routine name '" + r.name + "'");
      }
      file.routines.push_back(std::move(r));
    }
  }
  // A one-off task named like a routine's instances would collide with one of them on some day.
  if (!file.tasks.empty() && !file.routines.empty()) {
    RONDO_ASSIGN_OR_RETURN(auto tasks, root.required("tasks"));
    RONDO_ASSIGN_OR_RETURN(auto items, tasks.items());
    for (std::size_t i = 0; i < file.tasks.size(); ++i) {
      const std::string& id = file.tasks[i].id;
      const std::size_t at = id.find('@');
      if (at == std::string::npos) continue;
      for (const auto& r : file.routines) {
        if (id.compare(0, at, r.name) == 0 && at == r.name.size()) {
          return items[i].error_at("id", fmt::format("'{}' has the form of the ids of routine '{}' ('{}@<date>T<hh:mm>'); "
                                                     "give the task another id",
                                                     id, r.name, r.name));
        }
      }
    }
  }
  return file;
}

Result<TaskFile> load_task_file(const std::filesystem::path& file, const PlaceCheck* places) {
  RONDO_ASSIGN_OR_RETURN(auto doc, Document::load(file));
  return decode_task_file(doc, places);
}

Result<TaskFile> parse_task_file(std::string_view text, DocumentFormat format, std::string source,
                                 const PlaceCheck* places) {
  RONDO_ASSIGN_OR_RETURN(auto doc, Document::parse(text, format, std::move(source)));
  return decode_task_file(doc, places);
}

namespace {

void encode_task_body(const Task& t, Json& j) {
  if (!t.activity.empty()) j["activity"] = t.activity;
  if (t.duration != Duration{0}) j["duration"] = format_duration(t.duration);
  if (t.priority != 0) j["priority"] = t.priority;
  if (!t.start_node.empty()) j["start_node"] = t.start_node;
  if (!t.end_node.empty()) j["end_node"] = t.end_node;
  if (t.has_spec()) j["spec"] = t.spec;
  if (!t.actions.empty()) {
    Json actions = Json::array();
    for (const auto& a : t.actions) {
      if (a.args.empty()) {
        actions.push_back(a.name);
        continue;
      }
      Json action{{"name", a.name}};
      for (const auto& [k, v] : a.args) action["args"][k] = v;
      actions.push_back(std::move(action));
    }
    j["actions"] = std::move(actions);
  }
  if (!t.interruptible) j["interruptible"] = false;
  if (t.delivery) {
    const auto& d = *t.delivery;
    Json dj{{"job", d.job}, {"role", to_string(d.role)}, {"object", d.object}};
    if (d.appearance != d.object) dj["appearance"] = d.appearance;
    if (d.load != 1) dj["load"] = d.load;
    j["delivery"] = std::move(dj);
  }
  if (!t.after.empty()) j["after"] = t.after;
  if (!t.robot.empty()) j["robot"] = t.robot;
}

}  // namespace

Json encode(const Task& t) {
  Json j{{"id", t.id}};
  if (t.kind != TaskKind::kStandard) j["kind"] = to_string(t.kind);
  if (t.window) j["window"] = Json{{"release", format_time(t.window->release)}, {"deadline", format_time(t.window->deadline)}};
  encode_task_body(t, j);
  return j;
}

Json encode(const Routine& r) {
  Json task = Json::object();
  encode_task_body(r.task, task);
  Json j{{"name", r.name}, {"task", std::move(task)},
         {"window", Json{{"from", format_time_of_day(r.window_start)}, {"to", format_time_of_day(r.window_end)}}}};
  if (r.every) j["every"] = format_duration(*r.every);
  if (!r.days.empty()) {
    Json days = Json::array();
    for (auto d : r.days) days.push_back(std::string(kDayNames[d.c_encoding()]));
    j["days"] = std::move(days);
  }
  if (!r.dates_off.empty()) {
    Json dates = Json::array();
    for (auto d : r.dates_off) dates.push_back(format_date(d));
    j["dates_off"] = std::move(dates);
  }
  if (r.first_day) j["first_day"] = format_date(*r.first_day);
  if (r.last_day) j["last_day"] = format_date(*r.last_day);
  return j;
}

Json encode(const TaskFile& file) {
  Json j = Json::object();
  if (file.zone) j["timezone"] = file.zone->name();
  if (!file.tasks.empty()) {
    Json tasks = Json::array();
    for (const auto& t : file.tasks) tasks.push_back(encode(t));
    j["tasks"] = std::move(tasks);
  }
  if (!file.routines.empty()) {
    Json routines = Json::array();
    for (const auto& r : file.routines) routines.push_back(encode(r));
    j["routines"] = std::move(routines);
  }
  return j;
}

}  // namespace rondo
