// `rondo serve`: the executive live on the system clock (optionally X times faster), on the
// deployment's simulated robot and world, with its store in a data folder and the HTTP API of
// rondo::service. It runs until SIGTERM or SIGINT, then stops taking requests, lets the requests
// in progress (and so the commit in progress) finish, halts the robot and returns 0.
// On a PostgreSQL store several may run: the one that holds the lease is the active executive, the
// others are standbys that answer 503 until they take it (then they restore the executive from the
// store as a restart does). An active that loses the lease steps down and is a standby again.
//
//   ServeRequest r{.deployment = *load_deployment(file), .data = "rondo-data"};
//   Result<int> code = serve_deployment(r, std::cerr);
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

#include "deployment.h"
#include "rondo/core/result.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor.h"
#include "rondo/fleet/fleet.h"
#include "rondo/sim/request_generator.h"
#include "rondo/sim/rng.h"
#include "rondo/store/store.h"

namespace rondo::app {

struct ServeRequest {
  Deployment deployment;
  std::string host = "127.0.0.1";
  int port = 8080;
  std::filesystem::path data = "rondo-data";
  // The store: --store, else the deployment's `store:`, else data/rondo.sqlite.
  std::optional<store::StoreLocation> store;
  std::optional<std::filesystem::path> token_file;
  double speed = 1.0;
  int max_streams = 64;  // event streams open at once; each holds an HTTP thread, as many again answer
  // On PostgreSQL, the lease (store/lease.h; docs/operations.md, "Active and standby"), in wall
  // time: a standby tries to take it every `lease_poll`; the active renews it every `lease_renew`
  // and stops commanding the robot `lease_trust` after its last renewal was sent unless renewed
  // again; a holder not renewed for `lease_stale` (by the database's clock) is cut off.
  Duration lease_poll = std::chrono::milliseconds(500);
  Duration lease_renew = seconds(1);
  Duration lease_trust = seconds(2);
  Duration lease_stale = seconds(3);
};

// kInvalidInput (exit 2) for a bad deployment, token file, or a non-loopback host without a token;
// kIo when the address cannot be bound. Returns once a signal has stopped the service.
Status serve_deployment(const ServeRequest& request, std::ostream& log);

// The simulated people's requests from `from` to the end of its local day, each added to the
// fleet (source "request") when it falls due, as in `rondo run`; at the day's end the next day's
// are drawn, and so on. Precondition: everything outlives the clock's events.
void schedule_people(exec::Clock& clock, fleet::Fleet& fleet, sim::RequestGenerator& people, sim::Rng& rng,
                     const TimeZone& zone, Time from);

}  // namespace rondo::app
