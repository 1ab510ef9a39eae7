// People asking the robot for things: on-demand tasks ("come to WayPoint17 and talk") arriving at
// random moments of office hours, as a Poisson process with a given mean number per office day.
//
//   auto people = RequestGenerator::load("examples/g4s/requests.yaml", map, zone);
//   Rng rng(7);
//   for (const Request& r : people->between(monday, monday + days(7), rng))
//     clock.schedule_at(r.at, [&, task = r.task] { executor.add_on_demand(task); });
//
// Contract: between(from, to) returns the requests arriving in [from, to) in time order, only on
// the configured days and inside the local office hours, at whole seconds; it depends only on
// the arguments and the rng state. Ids are "<prefix>-<local date>-<hhmmss>" (e.g.
// "req-2026-11-23-103412"): unique within a call, and across calls on disjoint intervals. Each
// task is on-demand, valid (rondo::validate), starts at one of its template's places, chosen at
// random, and copies the template's activity, duration, priority, actions and interruptible flag.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/task.h"
#include "rondo/core/timezone.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/rng.h"

namespace rondo::sim {

struct Request {
  Time at;
  Task task;
};

// One kind of request: the task to make (without id, start node or window) and where people ask
// from. Templates are chosen in proportion to their weight.
struct RequestTemplate {
  std::string name{};
  double weight = 1;
  std::vector<std::string> places{};  // node names; non-empty
  Task task{};
};

struct RequestSpec {
  std::string id_prefix = "req";
  std::vector<std::chrono::weekday> days{};  // empty: every day
  Duration from = hours(9);                  // local office hours [from, to)
  Duration to = hours(17);
  double per_day = 3;                        // mean requests per office day
  std::vector<RequestTemplate> templates{};  // non-empty
};

class RequestGenerator {
 public:
  // Precondition: spec.from < spec.to, templates non-empty with positive total weight, each with
  // places (load() checks all of this and that the places are nodes of the map).
  RequestGenerator(RequestSpec spec, TimeZone zone) : spec_(std::move(spec)), zone_(std::move(zone)) {}

  static Result<RequestGenerator> load(const std::filesystem::path& file, const map::TopoMap& map,
                                       const TimeZone& zone);
  static Result<RequestGenerator> decode(const Document& doc, const map::TopoMap& map, const TimeZone& zone);

  std::vector<Request> between(Time from, Time to, Rng& rng) const;
  const RequestSpec& spec() const { return spec_; }

 private:
  Request make(Time at, Rng& rng) const;
  RequestSpec spec_;
  TimeZone zone_;
};

}  // namespace rondo::sim
