#include "rondo/schedule/problem_codec.h"

#include <map>

#include <fmt/format.h>

namespace rondo::schedule {

namespace {

// A time: an ISO 8601 string with its zone, or a number of seconds after `origin`.
Result<Time> read_time(const Field& f, Time origin) {
  if (f.is_string()) return f.as_time(nullptr);
  auto s = f.as_number();
  if (!s) return s.error();
  auto offset = checked_from_seconds(*s);
  if (!offset) return f.error(offset.error().message);
  return origin + *offset;
}

Result<LocationIndex> read_location(const Field& f, const std::map<std::string, LocationIndex>& names) {
  auto name = f.as_string();
  if (!name) return name.error();
  auto it = names.find(*name);
  if (it == names.end()) return f.error(fmt::format("no location '{}' in locations", *name));
  return it->second;
}

#define RONDO_TRY(var, expr)            \
  auto var##_result = (expr);           \
  if (!var##_result) return var##_result.error(); \
  auto var = std::move(var##_result).value()

Result<ItemTransfer> read_transfer(const Field& f) {
  if (auto ok = f.expect_keys({"job", "action", "appearance", "load"}); !ok) return ok.error();
  ItemTransfer x;
  RONDO_TRY(job, f.required("job"));
  RONDO_TRY(job_name, job.as_string());
  x.job = job_name;
  RONDO_TRY(action, f.required("action"));
  RONDO_TRY(action_name, action.as_string());
  if (action_name == "pickup") x.action = ItemAction::kPickup;
  else if (action_name == "drop") x.action = ItemAction::kDrop;
  else return action.error("must be 'pickup' or 'drop'");
  if (auto a = f.optional("appearance")) {
    RONDO_TRY(look, a->as_string());
    x.appearance = look;
  }
  if (auto l = f.optional("load")) {
    RONDO_TRY(load, l->as_int());
    if (load < 0) return l->error("must not be negative");
    x.load = load;
  }
  return x;
}

}  // namespace

Result<Problem> decode_problem(const Document& doc) {
  const Field root = doc.root();
  if (auto ok = root.expect_keys({"locations", "travel", "robot", "tasks", "return"}); !ok) return ok.error();
  Problem p;
  std::map<std::string, LocationIndex> names;
  RONDO_TRY(locations, root.required("locations"));
  RONDO_TRY(location_items, locations.items());
  for (const Field& l : location_items) {
    RONDO_TRY(name, l.as_string());
    if (names.count(name)) return l.error(fmt::format("location '{}' listed twice", name));
    names[name] = p.location_names.size();
    p.location_names.push_back(name);
  }
  const std::size_t size = p.location_names.size();
  if (size == 0) return locations.error("must name at least one location");

  RONDO_TRY(travel, root.required("travel"));
  RONDO_TRY(travel_rows, travel.items());
  if (travel_rows.size() != size)
    return travel.error(fmt::format("expected {} rows (one per location), found {}", size, travel_rows.size()));
  std::vector<Duration> matrix;
  for (const Field& row : travel_rows) {
    RONDO_TRY(cells, row.items());
    if (cells.size() != size)
      return row.error(fmt::format("expected {} entries (one per location), found {}", size, cells.size()));
    for (const Field& c : cells) {
      RONDO_TRY(d, c.as_duration());
      matrix.push_back(d);
    }
  }
  auto oracle = MatrixTravel::create(size, std::move(matrix));
  if (!oracle) return travel.error(oracle.error().message);
  p.travel = std::make_shared<MatrixTravel>(std::move(oracle).value());

  RONDO_TRY(robot, root.required("robot"));
  if (auto ok = robot.expect_keys({"location", "time", "capacity", "on_board"}); !ok) return ok.error();
  RONDO_TRY(robot_location, robot.required("location"));
  RONDO_TRY(start, read_location(robot_location, names));
  p.robot.location = start;
  RONDO_TRY(robot_time, robot.required("time"));
  RONDO_TRY(now, read_time(robot_time, Time{}));
  p.robot.time = now;
  if (auto c = robot.optional("capacity")) {
    RONDO_TRY(capacity, c->as_int());
    if (capacity < 0) return c->error("must not be negative");
    p.robot.capacity = capacity;
  }
  if (auto b = robot.optional("on_board")) {
    RONDO_TRY(items, b->items());
    for (const Field& item : items) {
      if (auto ok = item.expect_keys({"job", "appearance", "load"}); !ok) return ok.error();
      OnBoardItem o;
      RONDO_TRY(job, item.required("job"));
      RONDO_TRY(job_name, job.as_string());
      o.job = job_name;
      if (auto a = item.optional("appearance")) {
        RONDO_TRY(look, a->as_string());
        o.appearance = look;
      }
      if (auto l = item.optional("load")) {
        RONDO_TRY(load, l->as_int());
        o.load = load;
      }
      p.robot.on_board.push_back(o);
    }
  }
  if (auto r = root.optional("return")) {
    if (auto ok = r->expect_keys({"location", "deadline"}); !ok) return ok.error();
    RONDO_TRY(where, r->required("location"));
    RONDO_TRY(loc, read_location(where, names));
    RONDO_TRY(when, r->required("deadline"));
    RONDO_TRY(deadline, read_time(when, p.robot.time));
    p.return_to = ReturnTo{loc, deadline};
  }

  RONDO_TRY(tasks, root.required("tasks"));
  RONDO_TRY(task_items, tasks.items());
  std::map<std::string, std::size_t> ids;
  std::vector<std::vector<std::pair<std::string, Field>>> afters;
  for (const Field& f : task_items) {
    if (auto ok = f.expect_keys({"id", "release", "deadline", "deadline_on", "duration", "priority", "start", "end",
                                 "after", "transfer"});
        !ok)
      return ok.error();
    ProblemTask t;
    RONDO_TRY(id_field, f.required("id"));
    RONDO_TRY(id, id_field.as_string());
    if (ids.count(id)) return id_field.error(fmt::format("task id '{}' used twice", id));
    ids[id] = p.tasks.size();
    t.id = id;
    RONDO_TRY(release_field, f.required("release"));
    RONDO_TRY(release, read_time(release_field, p.robot.time));
    t.release = release;
    RONDO_TRY(deadline_field, f.required("deadline"));
    RONDO_TRY(deadline, read_time(deadline_field, p.robot.time));
    t.deadline = deadline;
    if (auto on = f.optional("deadline_on")) {
      RONDO_TRY(which, on->as_string());
      if (which == "end") t.deadline_on = DeadlineOn::kEnd;
      else if (which == "start") t.deadline_on = DeadlineOn::kStart;
      else return on->error("must be 'end' or 'start'");
    }
    if (auto d = f.optional("duration")) {
      RONDO_TRY(duration, d->as_duration());
      t.duration = duration;
    }
    if (t.latest_start() < t.release)
      return deadline_field.error(t.deadline_on == DeadlineOn::kEnd
                                      ? "the task cannot end by its deadline when it starts at its release"
                                      : "must not be before the release");
    if (auto pr = f.optional("priority")) {
      RONDO_TRY(priority, pr->as_int());
      if (priority < -1000000 || priority > 1000000) return pr->error("must be from -1000000 to 1000000");
      t.priority = static_cast<int>(priority);
    }
    RONDO_TRY(start_field, f.required("start"));
    RONDO_TRY(start_loc, read_location(start_field, names));
    t.start_location = t.end_location = start_loc;
    if (auto e = f.optional("end")) {
      RONDO_TRY(end_loc, read_location(*e, names));
      t.end_location = end_loc;
    }
    if (auto x = f.optional("transfer")) {
      RONDO_TRY(transfer, read_transfer(*x));
      t.transfer = transfer;
    }
    afters.emplace_back();
    if (auto a = f.optional("after")) {
      RONDO_TRY(list, a->items());
      for (const Field& item : list) {
        RONDO_TRY(other, item.as_string());
        afters.back().push_back({other, item});
      }
    }
    p.tasks.push_back(std::move(t));
  }
  for (std::size_t i = 0; i < p.tasks.size(); ++i)
    for (const auto& [other, field] : afters[i]) {
      auto it = ids.find(other);
      if (it == ids.end()) return field.error(fmt::format("no task '{}'", other));
      p.tasks[i].after.push_back(it->second);
    }
  if (auto ok = validate(p); !ok) return ok.error().with_context(doc.source());
  return p;
}

#undef RONDO_TRY

Result<Problem> load_problem(const std::filesystem::path& file) {
  auto doc = Document::load(file);
  if (!doc) return doc.error();
  return decode_problem(*doc);
}

Json schedule_to_json(const Problem& p, const Schedule& s) {
  Json j;
  j["status"] = std::string(to_string(s.status));
  j["objective"] = to_seconds(s.objective);
  if (s.lower_bound) j["lower_bound"] = to_seconds(*s.lower_bound);
  if (auto g = s.gap()) j["gap"] = *g;
  j["seconds"] = s.seconds;
  j["order"] = Json::array();
  for (const auto& e : s.entries) j["order"].push_back(p.tasks[e.task].id);
  j["entries"] = Json::array();
  for (const auto& e : s.entries) {
    j["entries"].push_back(Json{{"id", p.tasks[e.task].id},
                                {"depart", format_time(e.depart)},
                                {"arrival", format_time(e.arrival)},
                                {"start", format_time(e.start)},
                                {"end", format_time(e.end)},
                                {"travel_s", to_seconds(e.travel)},
                                {"waiting_s", to_seconds(e.waiting)}});
  }
  j["dropped"] = Json::array();
  for (const auto& d : s.dropped) j["dropped"].push_back(Json{{"id", p.tasks[d.task].id}, {"reason", d.reason}});
  return j;
}

}  // namespace rondo::schedule
