// Real peers for the VDA 5050 integration tests: a mosquitto broker on a free loopback port with
// its own configuration, and child processes (the virtual vehicle) that are always stopped.
//
//   auto broker = Broker::start();          // nullopt (with why()) only if mosquitto is absent
//   ChildProcess agv({"node", "tests/vda5050/peer/virtual_agv.js", ...}, "/tmp/agv.log");
//   // ... both are stopped (SIGTERM, then SIGKILL) when they go out of scope
//
// Waiting is always for a condition with a deadline (wait_until), never a fixed sleep.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rondo::vda5050::testing {

// Polls `condition` every few milliseconds until it holds or `deadline` passes.
bool wait_until(const std::function<bool()>& condition, std::chrono::milliseconds deadline);

// The first of `candidates` that is an executable file, or "".
std::string find_program(const std::vector<std::string>& candidates);

class ChildProcess {
 public:
  // Starts argv[0] (a path) with stdout and stderr appended to `log`.
  ChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& log);
  ~ChildProcess();  // stop()
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool running();
  void kill_hard();  // SIGKILL and reap
  void stop();       // SIGTERM, then SIGKILL after a grace period; reaps
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
};

class Broker {
 public:
  // A mosquitto on 127.0.0.1 at a free port: listener on loopback only, no persistence,
  // anonymous clients allowed. Nothing (and `why`) when mosquitto is not installed or fails.
  static std::unique_ptr<Broker> start(std::string& why);
  // The same broker again on the same port (after stop()).
  bool restart();
  void stop();

  int port() const { return port_; }
  pid_t pid() const { return process_ ? process_->pid() : -1; }  // -1 when stopped
  std::string url() const { return "mqtt://127.0.0.1:" + std::to_string(port_); }
  const std::filesystem::path& dir() const { return dir_; }

 private:
  Broker() = default;
  bool launch();
  std::string program_;
  std::filesystem::path dir_;
  int port_ = 0;
  std::unique_ptr<ChildProcess> process_;
};

// A fresh temporary folder for one test's files.
std::filesystem::path make_temp_dir(const std::string& stem);
// A TCP port on 127.0.0.1 that was free a moment ago.
int free_port();
// True when something accepts TCP connections on 127.0.0.1:port.
bool port_open(int port);

}  // namespace rondo::vda5050::testing
