#include "store/pg_cluster.h"

#include <fcntl.h>
#include <libpq-fe.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace rondo::store::testing {
namespace {

constexpr const char* kSuperuser = "rondo_test";

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Runs `command` through the shell, as the postgres user when asked; its exit status (0: success).
int run(const std::string& command, bool as_postgres_user) {
  // From "/": the postgres user may not enter the folder the tests run in.
  const std::string in_root = "cd / && " + command;
  const std::string full = as_postgres_user ? "runuser -u postgres -- sh -c " + quoted(in_root) : in_root;
  const int status = std::system(full.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A port on 127.0.0.1 that nothing listens on now (the kernel's choice for port 0).
int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw std::runtime_error("cannot open a socket to find a free port");
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof addr;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    ::close(fd);
    throw std::runtime_error("cannot bind 127.0.0.1:0 to find a free port");
  }
  ::close(fd);
  return ntohs(addr.sin_port);
}

std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string url_over_socket(const std::filesystem::path& folder, int port, const std::string& database) {
  return "postgresql:///" + database + "?host=" + folder.string() + "&port=" + std::to_string(port) +
         "&user=" + kSuperuser;
}

class StopClusterAtExit : public ::testing::Environment {
 public:
  void TearDown() override { PgCluster::stop_if_started(); }
};
const auto* const kEnvironment = ::testing::AddGlobalTestEnvironment(new StopClusterAtExit);

std::unique_ptr<PgCluster>& the_cluster() {
  static std::unique_ptr<PgCluster> cluster;
  return cluster;
}

// Why the cluster could not start, once known: every later test fails at once with it.
std::string& start_failure() {
  static std::string why;
  return why;
}

}  // namespace

PgCluster& PgCluster::get() {
  auto& cluster = the_cluster();
  if (!cluster) {
    if (!start_failure().empty()) throw std::runtime_error(start_failure());
    std::unique_ptr<PgCluster> made(new PgCluster());
    try {
      made->start();
    } catch (const std::exception& e) {
      start_failure() = e.what();
      throw;  // `made` goes: its watchdog stops what started and removes the folder
    }
    cluster = std::move(made);
  }
  return *cluster;
}

void PgCluster::stop_if_started() {
  the_cluster().reset();
}

PgCluster::~PgCluster() {
  stop();
}

void PgCluster::start() {
  const char* env_bin = std::getenv("RONDO_PG_BIN");
  bin_ = env_bin ? env_bin : "/usr/lib/postgresql/15/bin";
  for (const char* tool : {"initdb", "pg_ctl", "postgres"}) {
    if (!std::filesystem::exists(bin_ / tool))
      throw std::runtime_error("PostgreSQL server binaries not found: no " + (bin_ / tool).string() +
                               " (install postgresql-15, as scripts/setup does, or set RONDO_PG_BIN); the "
                               "PostgreSQL store tests need them");
  }
  as_postgres_user_ = ::geteuid() == 0;
  std::string pattern = (std::filesystem::temp_directory_path() / "rondo-pg-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot make a temporary folder for PostgreSQL");
  folder_ = pattern;
  start_watchdog();  // from here on the folder goes, whatever happens
  std::filesystem::permissions(folder_, std::filesystem::perms::owner_all | std::filesystem::perms::group_exec |
                                            std::filesystem::perms::others_exec);
  if (as_postgres_user_ && run("chown postgres " + quoted(folder_.string()), false) != 0)
    throw std::runtime_error("cannot give " + folder_.string() + " to the postgres user (does it exist?)");
  const std::string init = (bin_ / "initdb").string() + " -D " + quoted((folder_ / "data").string()) + " -U " +
                           kSuperuser + " --auth-local=trust --auth-host=scram-sha-256 -E UTF8 --locale=C --no-sync > " +
                           quoted((folder_ / "initdb.log").string()) + " 2>&1";
  if (run(init, as_postgres_user_) != 0)
    throw std::runtime_error("initdb failed: " + read_file(folder_ / "initdb.log"));
  start_server();
}

// A child that waits for this process to close the pipe (at its end, or at its death: a crash, a
// ctest timeout) and then stops the server and removes the folder.
void PgCluster::start_watchdog() {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("cannot make the watchdog's pipe");
  ::fcntl(fds[1], F_SETFD, FD_CLOEXEC);
  watchdog_ = ::fork();
  if (watchdog_ == 0) {
    ::close(fds[1]);
    char byte = 0;
    while (::read(fds[0], &byte, 1) > 0) {
    }
    if (std::filesystem::exists(folder_ / "data" / "postmaster.pid")) {
      run((bin_ / "pg_ctl").string() + " -D " + quoted((folder_ / "data").string()) +
              " -m immediate -w stop > /dev/null 2>&1",
          as_postgres_user_);
    }
    std::error_code ec;
    std::filesystem::remove_all(folder_, ec);
    ::_exit(0);
  }
  ::close(fds[0]);
  if (watchdog_ < 0) {
    ::close(fds[1]);
    throw std::runtime_error("cannot start the watchdog process");
  }
  watchdog_pipe_ = fds[1];
}

// A port can be taken between free_port() and the server's bind: a few tries.
void PgCluster::start_server() {
  for (int attempt = 0; attempt < 5 && !running_; ++attempt) {
    port_ = free_port();
    const std::string options = "-k " + folder_.string() + " -h 127.0.0.1 -p " + std::to_string(port_) + " -F";
    const std::string start = (bin_ / "pg_ctl").string() + " -D " + quoted((folder_ / "data").string()) + " -l " +
                              quoted((folder_ / "server.log").string()) + " -o " + quoted(options) +
                              " -w -t 60 start > /dev/null 2>&1";
    running_ = run(start, as_postgres_user_) == 0;
  }
  if (!running_) throw std::runtime_error("the PostgreSQL server did not start: " + read_file(folder_ / "server.log"));
}

void PgCluster::stop() {
  if (watchdog_pipe_ >= 0) {
    ::close(watchdog_pipe_);  // the watchdog stops the server and removes the folder
    watchdog_pipe_ = -1;
    int status = 0;
    ::waitpid(watchdog_, &status, 0);
  }
  running_ = false;
}

std::string PgCluster::create_database() {
  const std::string name = "rondo_test_" + std::to_string(++databases_);
  const std::string error = run_sql(url_over_socket(folder_, port_, "postgres"), "CREATE DATABASE " + name);
  if (!error.empty()) throw std::runtime_error("CREATE DATABASE " + name + ": " + error);
  return url_over_socket(folder_, port_, name);
}

std::string PgCluster::tcp_url(const std::string& database, const std::string& user) const {
  return "postgresql://" + user + "@127.0.0.1:" + std::to_string(port_) + "/" + database;
}

std::string PgCluster::socket_url(const std::string& database) const {
  return url_over_socket(folder_, port_, database);
}

std::string run_sql(const std::string& url, const std::string& sql) {
  PGconn* conn = PQconnectdb(url.c_str());
  std::string error;
  if (PQstatus(conn) != CONNECTION_OK) {
    error = PQerrorMessage(conn);
  } else {
    PGresult* r = PQexec(conn, sql.c_str());
    const ExecStatusType status = PQresultStatus(r);
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) error = PQresultErrorMessage(r);
    PQclear(r);
  }
  PQfinish(conn);
  if (error.empty() == false && error.back() == '\n') error.pop_back();
  return error;
}

}  // namespace rondo::store::testing
