// The routines changed through the API or added by a queued request (`rondo task add --data`),
// kept in the store so that they survive a restart (`rondo serve`, and a resumed `rondo run`): the
// store's meta key "serve.routines" holds {"added": [routine, ...], "removed": [name, ...]}, the
// routines in the task-file JSON of docs/task-format.md.
//
//   RONDO_RETURN_IF_ERROR(remember_added_routine(db, routine));   // after the executor took it
//   auto routines = routines_to_run(db, deployment_routines, map, zone);  // at start
//
// At start the deployment's routines are run, less every name removed or added through the API,
// plus the added ones: so a deployment routine removed through the API stays removed, and one
// replaced (removed, then added again under its name) comes back as it was added.
#pragma once

#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/routine.h"
#include "rondo/core/timezone.h"
#include "rondo/map/topo_map.h"
#include "rondo/store/store.h"

namespace rondo::service {

// The store's meta key of dispatch out of service ("1") or not ("0" or absent): written by
// POST /api/v1/pause and /resume, read at start.
inline constexpr const char* kOutOfServiceKey = "serve.out_of_service";
// One robot of a fleet out of service (POST /api/v1/robots/{name}/pause): this key, a dot, its name.
inline std::string out_of_service_key(const std::string& robot) {
  return std::string(kOutOfServiceKey) + "." + robot;
}

// The meta key of the stored changes.
inline constexpr const char* kStoredRoutinesKey = "serve.routines";

// Each is one committed write. kStorage when the store cannot write.
Status remember_added_routine(store::Store& store, const Routine& routine);
Status remember_removed_routine(store::Store& store, const std::string& name);
// The value of kStoredRoutinesKey once `routines` are added, for a caller that writes it in a
// transaction of its own (a queued request is marked taken with it). kStorage, kInvalidInput as
// routines_to_run.
Result<std::string> stored_with_added(const store::Store& store, const std::vector<Routine>& routines);

// The routines to run: `deployment` with the stored changes applied. An added routine that no
// longer fits the map (the deployment was edited) is left out, named in `skipped` with why.
// kStorage for a store that cannot be read, kInvalidInput for a "serve.routines" that is not what
// this file writes.
Result<std::vector<Routine>> routines_to_run(store::Store& store, std::vector<Routine> deployment,
                                             const map::TopoMap& map, const TimeZone& zone,
                                             std::vector<std::string>* skipped = nullptr);

}  // namespace rondo::service
