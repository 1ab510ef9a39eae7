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
// random, and copies the template's activity, duration, priority, actions and interruptible flag;
// a delivery template's request is a pickup and a drop instead (DeliveryTemplate), valid together.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
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
  Task task;                 // an on-demand task, or a delivery's pickup
  std::optional<Task> drop;  // a delivery's drop

  std::vector<Task> tasks() const;  // what to add to the executor, together
};

// A courier request: a delivery job of two standard tasks, a pickup at one of the template's
// places (action `load`) and a drop at another place of `to` (action `unload`), both within
// `within` of the request, linked as Task::delivery with the request's id as the job.
struct DeliveryTemplate {
  std::vector<std::string> to{};       // node names; non-empty
  std::vector<std::string> objects{};  // what is carried, chosen at random; non-empty
  Duration within = hours(2);
};

// One kind of request: the task to make (without id, start node or window) and where people ask
// from. Templates are chosen in proportion to their weight.
struct RequestTemplate {
  std::string name{};
  double weight = 1;
  std::vector<std::string> places{};  // node names; non-empty
  Task task{};
  std::optional<DeliveryTemplate> deliver{};
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
  void make_delivery(const DeliveryTemplate& d, Request& r, Rng& rng) const;
  RequestSpec spec_;
  TimeZone zone_;
};

}  // namespace rondo::sim
