// Observations: what the robot saw of the world and when (a door open or closed, a person at a
// desk, a loading time), kept so that the learners can model when doors are open and people in.
// Append-only, like the other logs.
//
//   Result<std::int64_t> id = add_observation(db, {.what = "door_open", .where = "door_A110",
//                                                  .when = now, .value = 1.0});
//   Result<std::vector<Observation>> seen = find_observations(db, {.what = "door_open",
//                                                                  .where = "door_A110"});
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/store.h"

namespace rondo::store {

struct Observation {
  std::string what;   // the kind, e.g. "door_open", "person_present", "load_time"
  std::string where;  // a node, edge or door id
  Time when;
  double value = 0.0;               // 1/0 for binary observations; a measurement otherwise
  std::optional<std::string> text;  // anything else worth keeping, for people
  std::string robot{};              // the robot that saw it; empty: none (the building's)

  bool operator==(const Observation&) const = default;
};

// Stores `observation` in its own committed transaction and returns its row id.
// Errors: kInvalidInput (a value that is not finite), kStorage.
Result<std::int64_t> add_observation(Store& store, const Observation& observation);

// Which observations to read; every field that is set narrows the result.
struct ObservationQuery {
  std::optional<std::string> what = std::nullopt;
  std::optional<std::string> where = std::nullopt;
  std::optional<Time> from = std::nullopt;   // when >= from
  std::optional<Time> until = std::nullopt;  // when < until
};

// The matching observations ordered by time, then insertion order. Errors: kStorage.
Result<std::vector<Observation>> find_observations(const Store& store, const ObservationQuery& query = {});

}  // namespace rondo::store
