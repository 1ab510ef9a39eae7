// The executive as a service (`rondo serve`): an HTTP server with a JSON API under /api/v1, a
// server-sent event stream of the event log, /healthz and /metrics (docs/api.md).
//
//   service::Server server(context, {.host = "127.0.0.1", .port = 0});   // 0: an ephemeral port
//   Result<int> port = server.bind();          // kInvalidInput: a non-loopback host without a token
//   std::thread http([&] { server.run(); });   // serves until stop()
//   clock.run_until(...);                      // the executor's thread runs every request
//   server.stop(); http.join();
//
// Threads: the HTTP threads never touch the executor, its robot or its store connection. Every
// request that reads or changes them is handed to the clock's thread with Clock::post(), and the
// HTTP thread waits for the answer, so a submission is answered 201 only after its commit. Each
// event stream reads the log through a read-only store connection of its own.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/core/timezone.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor.h"
#include "rondo/exec/robot.h"
#include "rondo/fleet/fleet.h"
#include "rondo/lang/places.h"
#include "rondo/map/topo_map.h"
#include "rondo/service/service_role.h"
#include "rondo/store/store.h"

namespace rondo::service {

// What the service serves. Precondition: everything outlives the server; the fleet, its robots and
// the store are used only on the clock's thread.
struct ServiceContext {
  exec::Clock& clock;
  fleet::Fleet& fleet;
  exec::Executor& executor;  // the fleet's robot, for the robot's views
  exec::Robot& robot;
  store::Store& store;  // the executor's connection
  const map::TopoMap& map;
  TimeZone zone;
  std::string deployment;  // its name, for /healthz and /metrics
  // The places of commands in words (rooms, aliases, people); nothing: the map's node names.
  const lang::Places* places = nullptr;
  // Active or standby, the epoch and the lease's age, for /healthz and /metrics (service_role.h);
  // nothing: no lease (an SQLite store).
  const ServiceRole* role = nullptr;
};

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: an ephemeral port (tests)
  // With a token, every write needs "Authorization: Bearer <token>"; without one only a loopback
  // host may be bound.
  std::optional<std::string> token;
  std::size_t body_limit = 1 << 20;                       // bytes; larger bodies get 413
  Duration read_timeout = seconds(5);                     // a client that stalls longer is disconnected
  Duration answer_timeout = seconds(30);                  // the executor's thread did not answer: 503
  Duration stream_poll = std::chrono::milliseconds(100);  // how often an event stream looks for news
  Duration stream_keepalive = seconds(15);
  // HTTP threads. An event stream holds one for as long as it is open, so at most half of them
  // stream (more streams get 503) and the rest always answer requests.
  int threads = 64;
  // They are started when a connection finds none idle, and one idle this long ends: the service
  // holds the threads its recent load needed, not all of them (src/service/http_pool.h).
  Duration thread_idle_exit = seconds(30);
};

// One endpoint of the API: its method and OpenAPI path ("/api/v1/tasks/{id}").
struct EndpointInfo {
  std::string method;
  std::string path;
};

class Server {
 public:
  Server(ServiceContext context, ServerOptions options);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Binds the listening socket; returns the port. kInvalidInput for a non-loopback host without a
  // token, kIo when the address cannot be bound.
  Result<int> bind();
  // Serves until stop(). Precondition: bind() succeeded.
  void run();
  // Thread-safe: stops taking requests, ends the event streams, and makes run() return once the
  // requests in progress are answered.
  void stop();
  // Every endpoint the server answers (the OpenAPI document must list exactly these).
  std::vector<EndpointInfo> endpoints() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// True for 127.0.0.0/8, ::1 and "localhost".
bool is_loopback_host(const std::string& host);
// Reads a token file: the token is its content without surrounding white space. kInvalidInput when
// the file can be read by its group or others, or holds no token; kNotFound/kIo when unreadable.
Result<std::string> load_token_file(const std::filesystem::path& file);
// The OpenAPI 3 document of the API.
std::string openapi_document();

}  // namespace rondo::service
