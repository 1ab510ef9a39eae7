// A `rondo run` folder's store: made fresh, or opened again to resume the run it holds. The store
// records what run it holds (meta run.deployment, run.deployment_file, run.seed, run.days,
// run.realtime, run.start) and, once report.json is written, run.finished.
//
//   Result<RunFolder> f = open_run_folder(request, start);  // "DIR holds a run of seed 3, not 1" -> exit 2
//   if (f->finished) ...                              // nothing to do: report.json is there
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/store.h"
#include "run_session.h"

namespace rondo::app {

struct RunFolder {
  std::optional<store::Store> store;  // open for writing; none for a finished run
  bool existed = false;               // the folder held a run (of this request) before
  bool finished = false;              // ... and it was finished: meta run.finished
  Time start{};                       // when the run began: meta run.start
};

// The store's identity entries for `request` (what must match to resume).
std::vector<std::pair<std::string, std::string>> run_identity(const RunRequest& request);

// Opens request.out/rondo.sqlite: a missing one is made (with the folder and days/); an existing
// one must hold a run of the same deployment, file, seed, days and clock, else kInvalidInput
// naming what differs, with the folder left as it was. Identity keys an interrupted first start
// did not write yet are written now; `start` is the run's start when the store does not have one.
// A finished run's store is not kept open. Errors: kInvalidInput, kIo, kStorage.
Result<RunFolder> open_run_folder(const RunRequest& request, Time start);

// The run is over and its report written: a later `rondo run` on the folder says so.
Status mark_finished(store::Store& store);

}  // namespace rondo::app
