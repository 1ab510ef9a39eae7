// The command line's side of the request queue (store/requests.h): `rondo task add SENTENCE
// --data DIR` queues what the sentence means in the store of a `rondo run` folder or a `rondo
// serve` data folder, in one transaction; the executive running there takes it (request_intake.h):
// tasks, routines or a cancellation.
//
//   Result<QueuedAt> q = queue_command("runs/office", sentence, command, zone);  // q->id: request 3
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "rondo/core/result.h"
#include "rondo/core/timezone.h"
#include "rondo/lang/command.h"

namespace rondo::app {

struct QueuedAt {
  std::int64_t id = 0;         // the request's id in the queue
  std::filesystem::path file;  // the store it is queued in
  std::string what;            // what was queued: "2 task(s): a, b", "1 routine(s): c", "a cancellation"
};

// What a command queues, for people: "2 task(s): pickup-..., drop-...", "2 routine(s):
// check-exit-west, check-exit-east" or "a cancellation".
std::string queued_what(const lang::Command& command);

// The request's body: what `rondo task add --json` prints (a task file, or {"cancel": ...}).
Json request_body(const lang::Command& command, const TimeZone& zone);

// kInvalidInput (exit 2) naming the folder when it holds no rondo store or holds a finished run
// (nothing would take the request); kStorage when the store cannot be written.
Result<QueuedAt> queue_command(const std::filesystem::path& data, const std::string& sentence,
                               const lang::Command& command, const TimeZone& zone);

}  // namespace rondo::app
