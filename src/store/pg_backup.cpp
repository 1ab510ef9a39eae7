// backup_store on a PostgreSQL store: PostgreSQL's own pg_dump (custom format) into FILE.part, read
// back by pg_restore --list, then renamed to FILE (backup.h). pg_dump takes one consistent snapshot
// of a live database without blocking its writers.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "pg_backup.h"

extern char** environ;  // NOLINT(readability-redundant-declaration): POSIX, for posix_spawnp

namespace rondo::store {
namespace {

// The environment of the tools: ours, and the store's password (from its password_file) as
// PGPASSWORD, never on their command line.
std::vector<std::string> tool_environment(const StoreLocation& location) {
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e) env.emplace_back(*e);
  if (location.password_file) {
    std::ifstream in(*location.password_file);
    std::string line;
    std::getline(in, line);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty()) env.push_back("PGPASSWORD=" + line);
  }
  return env;
}

// Runs `args` (args[0] found on PATH) with its output to `log`; its exit status, or -1.
int run_tool(const std::vector<std::string>& args, const std::vector<std::string>& env,
             const std::filesystem::path& log) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));  // NOLINT: posix_spawn's type
  argv.push_back(nullptr);
  std::vector<char*> envp;
  for (const std::string& e : env) envp.push_back(const_cast<char*>(e.c_str()));  // NOLINT
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = -1;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string first_line_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line.empty() ? "no message" : line;
}

}  // namespace

Result<BackupReport> pg_dump_store(const StoreLocation& location, const std::filesystem::path& file) {
  std::error_code ec;
  std::filesystem::path part = file;
  part += ".part";
  std::filesystem::path log = file;
  log += ".log";
  std::filesystem::remove(part, ec);  // left by an interrupted backup
  const auto env = tool_environment(location);
  const int dumped = run_tool({"pg_dump", "--format=custom", "--file=" + part.string(), "--dbname=" + location.url},
                              env, log);
  if (dumped != 0) {
    const std::string why = dumped < 0 ? "cannot run pg_dump (install postgresql-client-15)" : first_line_of(log);
    std::filesystem::remove(part, ec);
    std::filesystem::remove(log, ec);
    return Error::storage(fmt::format("{}: pg_dump failed: {}", location.name(), why));
  }
  // The archive's table of contents reads back: the file is a whole pg_dump archive.
  if (run_tool({"pg_restore", "--list", part.string()}, env, log) != 0) {
    const std::string why = first_line_of(log);
    std::filesystem::remove(part, ec);
    std::filesystem::remove(log, ec);
    return Error::storage(fmt::format("{}: the dump does not read back: {}", part.string(), why));
  }
  std::filesystem::remove(log, ec);
  std::filesystem::rename(part, file, ec);
  if (ec) return Error::io(fmt::format("{}: cannot rename the finished backup: {}", file.string(), ec.message()));
  BackupReport report{.file = file};
  report.bytes = std::filesystem::file_size(file, ec);
  return report;
}

}  // namespace rondo::store
