#include "run_folder.h"

#include <fmt/format.h>

#include <map>

#include "rondo/store/robot_state.h"

namespace rondo::app {
namespace {

constexpr const char* kFinished = "run.finished";
constexpr const char* kStart = "run.start";

// How each identity key reads in "DIR holds a run of seed 3, not 1".
std::string differs(const std::string& key, const std::string& stored, const std::string& wanted) {
  if (key == "run.days") return fmt::format("{} days, not {}", stored, wanted);
  if (key == "run.realtime")
    return stored == "true" ? "the system clock, not simulated time" : "simulated time, not the system clock";
  const std::string name = key == "run.deployment_file" ? "deployment file" : key.substr(4);
  return fmt::format("{} {}, not {}", name, stored, wanted);
}

// SQLite's companion files of a WAL database. A read-only connection cannot remove them when it
// closes; when they were not there before it opened (no other connection), they are removed so
// that a refused folder is left as it was. An empty -wal holds nothing.
std::filesystem::path companion(const std::filesystem::path& db, const char* suffix) {
  return std::filesystem::path(db.string() + suffix);
}

bool has_companions(const std::filesystem::path& db) {
  return std::filesystem::exists(companion(db, "-wal")) || std::filesystem::exists(companion(db, "-shm"));
}

void remove_companions(const std::filesystem::path& db) {
  std::error_code ec;
  if (std::filesystem::file_size(companion(db, "-wal"), ec) == 0 && !ec) {
    std::filesystem::remove(companion(db, "-wal"), ec);
    std::filesystem::remove(companion(db, "-shm"), ec);
  }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> run_identity(const RunRequest& request) {
  const Deployment& d = request.deployment;
  return {{"run.deployment", d.name},
          {"run.deployment_file", std::filesystem::absolute(d.file).lexically_normal().string()},
          {"run.seed", std::to_string(d.seed)},
          {"run.days", std::to_string(d.days)},
          {"run.realtime", request.realtime ? "true" : "false"}};
}

Result<RunFolder> open_run_folder(const RunRequest& request, Time start) {
  const std::filesystem::path db = request.out / "rondo.sqlite";
  const std::vector<std::pair<std::string, std::string>> identity = run_identity(request);
  std::map<std::string, std::string> meta;
  const bool existed = std::filesystem::exists(db);
  if (existed) {
    // Read-only first: a folder of another run (or a finished one) is not written to.
    const bool had_companions = has_companions(db);
    bool read = false;
    {
      auto read_only = store::Store::open(db, {.mode = store::OpenMode::kReadOnly});
      if (read_only) {
        RONDO_ASSIGN_OR_RETURN(meta, store::read_meta(*read_only));
        read = true;
      }
    }  // the read-only connection is closed here
    if (read) {
      if (!had_companions) remove_companions(db);
    } else {
      // A store a killed first start never finished making (no schema yet), or one of an older
      // schema: made or migrated now (a file that is not a rondo store is still refused).
      RONDO_ASSIGN_OR_RETURN(store::Store made, store::Store::open(db, {.sync_commits = request.realtime}));
      RONDO_ASSIGN_OR_RETURN(meta, store::read_meta(made));
    }
    std::vector<std::string> diffs;
    for (const auto& [key, wanted] : identity)
      if (const auto it = meta.find(key); it != meta.end() && it->second != wanted)
        diffs.push_back(differs(key, it->second, wanted));
    if (!diffs.empty()) {
      std::string list;
      for (const std::string& s : diffs) list += (list.empty() ? "" : "; ") + s;
      return Error::invalid(
          fmt::format("{} holds a run of {}: give the same deployment and options to resume it, or "
                      "another --out folder",
                      request.out.string(), list));
    }
  }
  if (const auto it = meta.find(kStart); it != meta.end()) {
    auto t = parse_time(it->second);
    if (!t) return Error::storage(fmt::format("{}: meta {}: {}", db.string(), kStart, t.error().message));
    start = *t;
  }
  if (meta.contains(kFinished))
    return RunFolder{.store = std::nullopt, .existed = true, .finished = true, .start = start};
  // Also in a folder whose store another command made (rondo task add --data queues in it).
  std::error_code ec;
  std::filesystem::create_directories(request.out / "days", ec);
  if (ec) return Error::io(fmt::format("{}: cannot create the run folder: {}", request.out.string(), ec.message()));
  RONDO_ASSIGN_OR_RETURN(store::Store store, store::Store::open(db, {.sync_commits = request.realtime}));
  // What run this store holds (in one transaction), so that a restart can tell its own store
  // from another's; keys that an interrupted first start did not write yet are written now.
  std::vector<std::pair<std::string, std::string>> missing;
  for (const auto& entry : identity)
    if (!meta.contains(entry.first)) missing.push_back(entry);
  if (!meta.contains(kStart)) missing.emplace_back(kStart, format_time(start));
  if (!missing.empty()) RONDO_RETURN_IF_ERROR(store::set_meta(store, missing));
  return RunFolder{
      .store = std::optional<store::Store>(std::move(store)), .existed = existed, .finished = false, .start = start};
}

Status mark_finished(store::Store& store) {
  return store::set_meta(store, kFinished, "true");
}

}  // namespace rondo::app
