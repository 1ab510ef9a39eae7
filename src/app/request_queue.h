// The command line's side of the request queue (store/requests.h): `rondo task add SENTENCE
// --data DIR` queues what the sentence means in the store of a `rondo run` folder or a `rondo
// serve` data folder, in one transaction; the executive running there takes it (request_intake.h):
// tasks, routines or a cancellation. `--store URL` names a store directly (a PostgreSQL one).
//
//   Result<QueuedAt> q = queue_command("runs/office", sentence, command, zone);  // q->id: request 3
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/timezone.h"
#include "rondo/lang/command.h"
#include "rondo/store/store.h"

namespace rondo::app {

struct QueuedAt {
  std::int64_t id = 0;         // the request's id in the queue (0: nothing was queued)
  std::string store;           // the store it is queued in: its file or URL
  std::string what;            // what was queued: "2 task(s): a, b", "1 routine(s): c", "a cancellation"
  // Not empty: the store holds these tasks already, the same and still to do (the sentence was
  // said before in the same minute), and nothing was queued.
  std::vector<std::string> already_queued{};
};

// What a command queues, for people: "2 task(s): pickup-..., drop-...", "2 routine(s):
// check-exit-west, check-exit-east" or "a cancellation".
std::string queued_what(const lang::Command& command);

// The request's body: what `rondo task add --json` prints (a task file, or {"cancel": ...}).
Json request_body(const lang::Command& command, const TimeZone& zone);

// Queues the command unless the store holds its tasks already (QueuedAt::already_queued). Its task
// ids are first settled against the store's tasks (lang::settle_ids: "~2" after them when other
// tasks hold them), so `command` holds the ids queued; routines are settled by the executive that
// takes the request (request_intake.h), which knows the deployment's. kInvalidInput (exit 2)
// naming the folder when it holds no rondo store or holds a finished run (nothing would take the
// request); kStorage when the store cannot be read or written.
Result<QueuedAt> queue_command(const std::filesystem::path& data, const std::string& sentence, lang::Command& command,
                               const TimeZone& zone);
// The same in a store named by `rondo task add --store` (a PostgreSQL URL, or an SQLite file),
// which must hold a rondo store (kNotFound otherwise).
Result<QueuedAt> queue_command(const store::StoreLocation& where, const std::string& sentence, lang::Command& command,
                               const TimeZone& zone);

}  // namespace rondo::app
