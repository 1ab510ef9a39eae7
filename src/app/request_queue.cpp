#include "request_queue.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <optional>
#include <vector>

#include "rondo/core/task_codec.h"
#include "rondo/store/requests.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/store.h"
#include "rondo/store/task_table.h"

namespace rondo::app {

Json request_body(const lang::Command& command, const TimeZone& zone) {
  if (command.cancel) return lang::encode(*command.cancel);
  return encode(TaskFile{zone, command.tasks, command.routines});
}

Result<QueuedAt> queue_command(const std::filesystem::path& data, const std::string& sentence, lang::Command& command,
                               const TimeZone& zone) {
  const std::filesystem::path file = data / "rondo.sqlite";
  if (!std::filesystem::is_regular_file(file))
    return Error::invalid(fmt::format(
        "--data {}: no rondo store there ({} is missing): give a rondo run --out or rondo serve --data folder",
        data.string(), file.string()));
  return queue_command(store::StoreLocation::sqlite(file), sentence, command, zone);
}

Result<QueuedAt> queue_command(const store::StoreLocation& where, const std::string& sentence, lang::Command& command,
                               const TimeZone& zone) {
  RONDO_ASSIGN_OR_RETURN(store::Store db, store::Store::open(where, {.mode = store::OpenMode::kMustExist}));
  RONDO_ASSIGN_OR_RETURN(const auto meta, store::read_meta(db));
  if (meta.contains("run.finished"))
    return Error::invalid(fmt::format("{}: the run there is finished; nothing would take the request", db.name()));
  // The tasks the store holds under the command's ids: the same ones still to do are a repeat.
  std::optional<Error> unreadable;
  const auto task_held = [&](const Task& said) {
    auto row = store::get_task(db, said.id);
    if (!row) {
      if (row.error().code == ErrorCode::kNotFound) return lang::Held::kFree;
      unreadable = row.error();
      return lang::Held::kOther;
    }
    auto state = parse_task_state(row->state);
    return state && !is_final(*state) && row->task == encode(said) ? lang::Held::kSame : lang::Held::kOther;
  };
  RONDO_ASSIGN_OR_RETURN(const auto repeated,
                         lang::settle_ids(command, task_held, [](const Routine&) { return lang::Held::kFree; }));
  if (unreadable) return *unreadable;
  if (!repeated.empty()) return QueuedAt{0, db.name(), queued_what(command), repeated};
  const Time now = std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now());
  RONDO_ASSIGN_OR_RETURN(
      const std::int64_t id,
      store::queue_request(
          db, {.queued = now, .source = "words", .sentence = sentence, .body = request_body(command, zone)}));
  return QueuedAt{id, db.name(), queued_what(command), {}};
}

std::string queued_what(const lang::Command& command) {
  if (command.cancel) return "a cancellation";
  std::vector<std::string> names;
  for (const Task& t : command.tasks) names.push_back(t.id);
  for (const Routine& r : command.routines) names.push_back(r.name);
  return fmt::format("{} {}(s): {}", names.size(), command.routines.empty() ? "task" : "routine",
                     fmt::join(names, ", "));
}

}  // namespace rondo::app
