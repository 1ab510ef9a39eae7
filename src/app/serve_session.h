// `rondo serve`: the executive live on the system clock (optionally X times faster), on the
// deployment's simulated robot and world, with its store in a data folder and the HTTP API of
// rondo::service. It runs until SIGTERM or SIGINT, then stops taking requests, lets the requests
// in progress (and so the commit in progress) finish, halts the robot and returns 0.
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

namespace rondo::app {

struct ServeRequest {
  Deployment deployment;
  std::string host = "127.0.0.1";
  int port = 8080;
  std::filesystem::path data = "rondo-data";
  std::optional<std::filesystem::path> token_file;
  double speed = 1.0;
};

// kInvalidInput (exit 2) for a bad deployment, token file, or a non-loopback host without a token;
// kIo when the address cannot be bound. Returns once a signal has stopped the service.
Status serve_deployment(const ServeRequest& request, std::ostream& log);

}  // namespace rondo::app
