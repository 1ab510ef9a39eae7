// What a standby `rondo serve` answers while another process holds the lease (docs/operations.md,
// "Active and standby"): /healthz says "standby" (status 200, with the epoch and the active's
// name), /metrics gives the role and the lease, and every other request gets 503 with Retry-After,
// so that a client or a load balancer tries the active instead.
//
//   StandbyServer standby(role, {.host = "127.0.0.1", .port = 0, .deployment = "g4s"});
//   Result<int> port = standby.bind();
//   std::thread t([&] { standby.run(); });   // until stop()
//   ...; standby.stop(); t.join();           // the active's Server binds the same port after it
#pragma once

#include <memory>
#include <string>

#include "rondo/core/result.h"
#include "rondo/service/service_role.h"

namespace rondo::service {

struct StandbyOptions {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: an ephemeral port
  std::string deployment;
  int retry_after_seconds = 1;
};

class StandbyServer {
 public:
  StandbyServer(const ServiceRole& role, StandbyOptions options);
  ~StandbyServer();
  StandbyServer(const StandbyServer&) = delete;
  StandbyServer& operator=(const StandbyServer&) = delete;

  // The port bound; kIo when the address cannot be bound.
  Result<int> bind();
  // Serves until stop(). Precondition: bind() succeeded.
  void run();
  // Thread-safe; run() returns once the requests in progress are answered.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rondo::service
