// Test helper: one throwaway PostgreSQL 15 cluster per test binary, started the first time a test
// asks for it and stopped when the binary ends (a gtest Environment), or by a watchdog process if
// the binary dies first (a crash, a ctest timeout): nothing is left running either way.
//
// The cluster lives in a fresh folder under the system temp folder: `initdb` (trust
// authentication, fsync off: nothing here must survive a power cut), its Unix socket in that
// folder, and a free port of its own on 127.0.0.1 only. PostgreSQL refuses to run as root, so as
// root (CI) the server runs as the `postgres` system user (runuser); otherwise as the caller.
//
//   PgCluster& pg = PgCluster::get();      // a test failure (not a skip) if it cannot start
//   std::string url = pg.create_database(); // "postgresql:///rondo_test_3?host=/tmp/...&port=..."
//
// Over the socket every role is trusted; over TCP a password is asked (scram-sha-256), so tests can
// check how rondo finds it.
//
// Missing server binaries make every PostgreSQL test fail with a message that says what to install;
// RONDO_PG_BIN names another folder of them.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>

namespace rondo::store::testing {

class PgCluster {
 public:
  // The cluster, started on the first call. Throws std::runtime_error, naming what failed (and
  // the server's log), if it cannot be started.
  static PgCluster& get();
  // Stops the cluster if one was started (the environment's TearDown).
  static void stop_if_started();

  // A new, empty database and a libpq URL of it over the Unix socket.
  std::string create_database();
  // A database over TCP on 127.0.0.1, as `user` (a role with a password: run_sql CREATE ROLE).
  std::string tcp_url(const std::string& database, const std::string& user) const;
  // The superuser's URL of a database over the socket.
  std::string socket_url(const std::string& database) const;
  int port() const { return port_; }
  const std::filesystem::path& folder() const { return folder_; }

  PgCluster(const PgCluster&) = delete;
  PgCluster& operator=(const PgCluster&) = delete;
  ~PgCluster();

 private:
  PgCluster() = default;
  void start();
  void start_watchdog();
  void start_server();
  void stop();

  std::filesystem::path bin_;
  std::filesystem::path folder_;  // data/, the socket, server.log
  int port_ = 0;
  bool as_postgres_user_ = false;
  bool running_ = false;
  int watchdog_pipe_ = -1;  // the write end; the watchdog stops the cluster when it closes
  pid_t watchdog_ = -1;
  int databases_ = 0;
};

// The URL of the cluster's maintenance database, and a raw statement run on a database as the
// cluster's superuser (tests that check what the database itself refuses). Returns the error text,
// empty on success.
std::string run_sql(const std::string& url, const std::string& sql);

}  // namespace rondo::store::testing
