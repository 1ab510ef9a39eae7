#include "deployment.h"

#include <fmt/format.h>

#include "deployment_robots.h"
#include "rondo/core/document.h"
#include "rondo/sim/sim_world.h"

namespace rondo::app {
namespace {

Result<Duration> time_of_day(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(const std::string text, f.as_string());
  auto t = parse_time_of_day(text);
  if (!t || *t >= hours(24)) return f.error(fmt::format("'{}' is not a time of day hh:mm", text));
  return *t;
}

Result<std::filesystem::path> path_field(const Field& f, const std::filesystem::path& base) {
  RONDO_ASSIGN_OR_RETURN(const std::string text, f.as_string());
  if (text.empty()) return f.error("empty path");
  return base / text;
}

Result<double> positive(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(const double v, f.as_number());
  if (!(v > 0)) return f.error("must be above zero");
  return v;
}

Result<Duration> non_negative_duration(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(const Duration d, f.as_duration());
  if (d < Duration{0}) return f.error("must not be negative");
  return d;
}

// battery_reserve, battery_threshold (0: off) and battery_resume (0: the reserve): states of
// charge, the threshold below the reserve and the resume level above the threshold.
Status decode_battery_levels(const Field& f, exec::ExecutorOptions& o) {
  const auto level = [&f](std::string_view key, double& out) -> Status {
    if (auto v = f.optional(key)) {
      RONDO_ASSIGN_OR_RETURN(out, v->as_number());
      if (!(out >= 0 && out < 1)) return v->error("must be a state of charge from 0 to below 1");
    }
    return Status{};
  };
  RONDO_RETURN_IF_ERROR(level("battery_reserve", o.battery_reserve));
  RONDO_RETURN_IF_ERROR(level("battery_threshold", o.battery_threshold));
  RONDO_RETURN_IF_ERROR(level("battery_resume", o.battery_resume));
  if (o.battery_threshold > o.battery_reserve)
    return f.error_at(f.has("battery_threshold") ? "battery_threshold" : "battery_reserve",
                      fmt::format("the hard threshold {} is above the reserve {}", o.battery_threshold,
                                  o.battery_reserve));
  if (auto v = f.optional("battery_planning")) { RONDO_ASSIGN_OR_RETURN(o.battery_planning, v->as_bool()); }
  if (auto v = f.optional("battery_margin")) {
    RONDO_ASSIGN_OR_RETURN(o.battery_margin, v->as_number());
    if (!(o.battery_margin >= 0 && o.battery_margin <= 10)) return v->error("must be from 0 to 10 standard errors");
  }
  if (o.battery_resume > 0 && o.battery_resume <= o.battery_threshold)
    return f.error_at("battery_resume", fmt::format("the resume level {} must be above the hard threshold {}",
                                                    o.battery_resume, o.battery_threshold));
  return Status{};
}

Status decode_executor(const Field& f, exec::ExecutorOptions& o) {
  RONDO_RETURN_IF_ERROR(f.expect_keys(
      {"navigation_overrun", "navigation_slack", "action_overrun",     "action_slack",    "dock_when_waiting_over",
       "max_failed_edges",   "blocked_edge",     "on_demand_patience", "person_patience", "refit_at",
       "refit_window",       "weekly_half_life", "online_model",       "slot_width",      "scheduler_polls",
       "capacity",           "return_to",        "return_within",      "battery_reserve", "battery_threshold",
       "battery_resume",     "battery_planning", "battery_margin",     "risk_alpha",      "navigation_alpha",
       "navigation_window",  "route_threshold",  "reallocate_after"}));
  if (auto v = f.optional("navigation_overrun")) { RONDO_ASSIGN_OR_RETURN(o.navigation_overrun, positive(*v)); }
  if (auto v = f.optional("navigation_slack")) { RONDO_ASSIGN_OR_RETURN(o.navigation_slack, non_negative_duration(*v)); }
  if (auto v = f.optional("action_overrun")) { RONDO_ASSIGN_OR_RETURN(o.action_overrun, positive(*v)); }
  if (auto v = f.optional("action_slack")) { RONDO_ASSIGN_OR_RETURN(o.action_slack, non_negative_duration(*v)); }
  if (auto v = f.optional("dock_when_waiting_over")) {
    RONDO_ASSIGN_OR_RETURN(o.dock_when_waiting_over, non_negative_duration(*v));
  }
  if (auto v = f.optional("max_failed_edges")) {
    RONDO_ASSIGN_OR_RETURN(const std::int64_t n, v->as_int());
    if (n < 1 || n > 100000) return v->error("must be between 1 and 100000");
    o.max_failed_edges = static_cast<int>(n);
  }
  if (auto v = f.optional("blocked_edge")) {
    RONDO_ASSIGN_OR_RETURN(const std::string s, v->as_string());
    using B = exec::ExecutorOptions::BlockedEdge;
    if (s == "retry")
      o.blocked_edge = B::kRetry;
    else if (s == "give_up")
      o.blocked_edge = B::kGiveUp;
    else if (s == "wait")
      o.blocked_edge = B::kWait;
    else
      return v->error("must be retry, give_up or wait, not '" + s + "'");
  }
  if (auto v = f.optional("reallocate_after")) {
    RONDO_ASSIGN_OR_RETURN(o.reallocate_after, non_negative_duration(*v));
  }
  if (auto v = f.optional("on_demand_patience")) {
    RONDO_ASSIGN_OR_RETURN(o.on_demand_patience, non_negative_duration(*v));
  }
  if (auto v = f.optional("person_patience")) {
    RONDO_ASSIGN_OR_RETURN(o.person_patience, v->as_number());
    if (!(o.person_patience >= 0 && o.person_patience <= 0.98)) return v->error("must be from 0 (off) to 0.98");
  }
  // optional() hides a null value: null is "never" / "the whole log", so ask has() first.
  if (f.has("refit_at") && !f.optional("refit_at")) o.refit_at.reset();
  if (auto v = f.optional("refit_at")) { RONDO_ASSIGN_OR_RETURN(o.refit_at, time_of_day(*v)); }
  if (f.has("refit_window") && !f.optional("refit_window")) o.refit_window.reset();
  if (auto v = f.optional("refit_window")) {
    RONDO_ASSIGN_OR_RETURN(o.refit_window, v->as_duration());
    if (*o.refit_window < hours(24)) return v->error("must be at least 24h (or null: the whole log)");
  }
  if (f.has("weekly_half_life") && !f.optional("weekly_half_life")) o.weekly_half_life.reset();
  if (auto v = f.optional("weekly_half_life")) {
    RONDO_ASSIGN_OR_RETURN(o.weekly_half_life, v->as_duration());
    if (*o.weekly_half_life < hours(24)) return v->error("must be at least 24h (or null: no live weekly term)");
  }
  if (auto v = f.optional("online_model")) { RONDO_ASSIGN_OR_RETURN(o.online_model, v->as_bool()); }
  if (auto v = f.optional("slot_width")) {
    RONDO_ASSIGN_OR_RETURN(o.slot_width, v->as_duration());
    if (o.slot_width < minutes(1) || o.slot_width > hours(24)) return v->error("must be between 1m and 24h");
  }
  if (auto v = f.optional("scheduler_polls")) {
    RONDO_ASSIGN_OR_RETURN(o.scheduler_polls, v->as_int());
    if (o.scheduler_polls < 1) return v->error("must be at least 1");
  }
  if (auto v = f.optional("capacity")) {
    RONDO_ASSIGN_OR_RETURN(const std::int64_t n, v->as_int());
    if (n < 0 || n > 1000000) return v->error("must be between 0 (unlimited) and 1000000");
    o.capacity = static_cast<int>(n);
  }
  if (auto v = f.optional("return_to")) { RONDO_ASSIGN_OR_RETURN(o.return_to, v->as_string()); }
  if (auto v = f.optional("return_within")) {
    RONDO_ASSIGN_OR_RETURN(o.return_within, v->as_duration());
    if (o.return_within < minutes(1)) return v->error("must be at least 1m");
  }
  if (f.has("risk_alpha") && !f.optional("risk_alpha")) o.risk_alpha.reset();
  if (auto v = f.optional("risk_alpha")) {
    RONDO_ASSIGN_OR_RETURN(const double a, v->as_number());
    if (!(a > 0 && a <= 0.5)) return v->error("must be above 0 and at most 0.5 (or null: expected values)");
    o.risk_alpha = a;
  }
  if (f.has("navigation_alpha") && !f.optional("navigation_alpha")) o.navigation_alpha.reset();
  if (auto v = f.optional("navigation_alpha")) {
    RONDO_ASSIGN_OR_RETURN(const double a, v->as_number());
    if (!(a > 0 && a <= 0.5)) return v->error("must be above 0 and at most 0.5 (or null: risk_alpha)");
    o.navigation_alpha = a;
  }
  if (auto v = f.optional("navigation_window")) { RONDO_ASSIGN_OR_RETURN(o.navigation_window, v->as_bool()); }
  if (f.has("route_threshold") && !f.optional("route_threshold")) o.route_threshold.reset();
  if (auto v = f.optional("route_threshold")) {
    RONDO_ASSIGN_OR_RETURN(const Duration d, v->as_duration());
    if (d < seconds(1) || d > hours(1))
      return v->error("must be a duration from 1s to 1h (or null: the departure slot's travel alone)");
    o.route_threshold = d;
  }
  return decode_battery_levels(f, o);
}

// store: {kind: sqlite, file: PATH} or {kind: postgresql, url: URL, password_file: PATH}; paths
// are relative to the deployment file. A password in the URL is refused (StoreLocation::postgres).
Status decode_store(const Field& f, const std::filesystem::path& base, Deployment& d) {
  RONDO_ASSIGN_OR_RETURN(const Field kind, f.required("kind"));
  RONDO_ASSIGN_OR_RETURN(const std::string k, kind.as_string());
  if (k == "sqlite") {
    RONDO_RETURN_IF_ERROR(f.expect_keys({"kind", "file"}));
    RONDO_ASSIGN_OR_RETURN(const Field file, f.required("file"));
    RONDO_ASSIGN_OR_RETURN(const std::filesystem::path path, path_field(file, base));
    d.store = store::StoreLocation::sqlite(path);
    return Status{};
  }
  if (k != "postgresql") return kind.error(fmt::format("'{}' is not a store kind (sqlite or postgresql)", k));
  RONDO_RETURN_IF_ERROR(f.expect_keys({"kind", "url", "password_file"}));
  RONDO_ASSIGN_OR_RETURN(const Field url, f.required("url"));
  RONDO_ASSIGN_OR_RETURN(const std::string text, url.as_string());
  std::optional<std::filesystem::path> password_file;
  if (auto p = f.optional("password_file")) { RONDO_ASSIGN_OR_RETURN(password_file, path_field(*p, base)); }
  auto location = store::StoreLocation::postgres(text, password_file);
  if (!location) return url.error(location.error().message);
  d.store = std::move(*location);
  return Status{};
}

// reference: {name: TEXT, days: N, tasks: N, distance_km: X}: tasks, distance or both.
Status decode_reference(const Field& f, Deployment& d) {
  RONDO_RETURN_IF_ERROR(f.expect_keys({"name", "days", "tasks", "distance_km"}));
  ReferenceFigures r;
  RONDO_ASSIGN_OR_RETURN(const Field name, f.required("name"));
  RONDO_ASSIGN_OR_RETURN(r.name, name.as_string());
  RONDO_ASSIGN_OR_RETURN(const Field days, f.required("days"));
  RONDO_ASSIGN_OR_RETURN(const std::int64_t n, days.as_int());
  if (n < 1 || n > 3660) return days.error("must be between 1 and 3660");
  r.days = static_cast<int>(n);
  if (auto t = f.optional("tasks")) {
    RONDO_ASSIGN_OR_RETURN(r.tasks, t->as_int());
    if (*r.tasks < 0) return t->error("must not be negative");
  }
  if (auto k = f.optional("distance_km")) {
    RONDO_ASSIGN_OR_RETURN(r.distance_km, k->as_number());
    if (*r.distance_km < 0) return k->error("must not be negative");
  }
  if (!r.tasks && !r.distance_km) return f.error("gives neither 'tasks' nor 'distance_km': nothing to compare");
  d.reference = std::move(r);
  return Status{};
}

// The world describes the simulated building: a simulated robot needs it, and a fleet of VDA 5050
// vehicles alone, which drive in the real building, has it refused rather than read and never used
// (docs/deployment.md, "The robots").
Status decode_simulated_building(const Field& root, const std::filesystem::path& base, Deployment& d) {
  if (!d.has_simulated()) {
    if (auto f = root.optional("world"))
      return f->error(
          "a vda5050 vehicle drives in the real building; the simulated world is for robot kind sim only (remove "
          "it, or run the simulated robot)");
    return Status{};
  }
  if (!root.has("world"))
    return root.error("missing field 'world': the simulated robot (robot kind sim, the default) needs its building");
  RONDO_ASSIGN_OR_RETURN(const Field world, root.required("world"));
  RONDO_ASSIGN_OR_RETURN(d.world, path_field(world, base));
  return Status{};
}

Result<Deployment> decode(const Field& root, const std::filesystem::path& file) {
  const std::filesystem::path base = file.parent_path();
  RONDO_RETURN_IF_ERROR(root.expect_keys(
      {"rondo_deployment", "name",    "map",      "time_zone", "dock",      "start",  "days",   "seed",
       "routines",         "world",   "requests", "places",    "executor",  "robot",  "robots", "docks",
       "allocator",        "balance", "battery",  "store",     "reference", "traffic"}));
  Deployment d;
  d.file = file;
  RONDO_ASSIGN_OR_RETURN(const Field version, root.required("rondo_deployment"));
  RONDO_ASSIGN_OR_RETURN(const std::int64_t v, version.as_int());
  if (v != 1) return version.error(fmt::format("version {} is not supported (this build reads 1)", v));
  if (auto f = root.optional("name")) { RONDO_ASSIGN_OR_RETURN(d.name, f->as_string()); }
  RONDO_ASSIGN_OR_RETURN(const Field map, root.required("map"));
  RONDO_ASSIGN_OR_RETURN(d.map, path_field(map, base));
  RONDO_ASSIGN_OR_RETURN(const Field zone, root.required("time_zone"));
  RONDO_ASSIGN_OR_RETURN(const std::string zone_name, zone.as_string());
  auto tz = TimeZone::named(zone_name);
  if (!tz) return zone.error(tz.error().message);
  d.zone = *tz;
  RONDO_ASSIGN_OR_RETURN(const Field dock, root.required("dock"));
  RONDO_ASSIGN_OR_RETURN(d.dock, dock.as_string());
  d.dock_where = dock.where();
  RONDO_ASSIGN_OR_RETURN(const Field start, root.required("start"));
  RONDO_ASSIGN_OR_RETURN(const Time start_time, start.as_time(&d.zone));
  d.start = d.zone.local_date(start_time);
  if (auto f = root.optional("days")) {
    RONDO_ASSIGN_OR_RETURN(const std::int64_t n, f->as_int());
    if (n < 1 || n > 3660) return f->error("must be between 1 and 3660");
    d.days = static_cast<int>(n);
  }
  if (auto f = root.optional("seed")) {
    RONDO_ASSIGN_OR_RETURN(const std::int64_t s, f->as_int());
    if (s < 0) return f->error("must not be negative");
    d.seed = static_cast<std::uint64_t>(s);
  }
  if (auto f = root.optional("routines")) { RONDO_ASSIGN_OR_RETURN(d.routines, path_field(*f, base)); }
  if (auto f = root.optional("requests")) { RONDO_ASSIGN_OR_RETURN(d.requests, path_field(*f, base)); }
  if (auto f = root.optional("places")) { RONDO_ASSIGN_OR_RETURN(d.places, path_field(*f, base)); }
  if (auto f = root.optional("executor")) RONDO_RETURN_IF_ERROR(decode_executor(*f, d.executor));
  RONDO_RETURN_IF_ERROR(decode_robots(root, d));
  if (auto f = root.optional("store")) RONDO_RETURN_IF_ERROR(decode_store(*f, base, d));
  if (auto f = root.optional("reference")) RONDO_RETURN_IF_ERROR(decode_reference(*f, d));
  RONDO_RETURN_IF_ERROR(decode_simulated_building(root, base, d));
  return d;
}

}  // namespace

Result<Deployment> load_deployment(const std::filesystem::path& file) {
  RONDO_ASSIGN_OR_RETURN(const Document doc, Document::load(file));
  return decode(doc.root(), file);
}

// Installed (cmake/RondoInstall.cmake): PREFIX/bin/rondo finds PREFIX/share/rondo/examples; a
// binary in its build folder finds the source tree's examples.
std::filesystem::path default_deployment() {
  const std::filesystem::path in_tree = std::filesystem::path("examples") / "g4s" / "deployment.yaml";
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path installed = self.parent_path().parent_path() / "share" / "rondo" / in_tree;
    if (std::filesystem::is_regular_file(installed, ec)) return installed;
  }
  return std::filesystem::path(RONDO_SOURCE_DIR) / in_tree;
}

}  // namespace rondo::app
