// The standby's small server (standby_server.h), and the role's /metrics lines.
#include "rondo/service/standby_server.h"

#include <fmt/format.h>

#include <atomic>

#include "api.h"

namespace rondo::service {

std::string ServiceRole::prometheus() const {
  std::string out = fmt::format(
      "# HELP rondo_role 1 while this service is the active executive, 0 while it is a standby.\n"
      "# TYPE rondo_role gauge\nrondo_role {}\n"
      "# HELP rondo_lease_epoch The lease's epoch: this service's while active, the active's as a standby saw it.\n"
      "# TYPE rondo_lease_epoch gauge\nrondo_lease_epoch {}\n"
      "# HELP rondo_step_downs_total Times this service lost the lease and stepped down.\n"
      "# TYPE rondo_step_downs_total counter\nrondo_step_downs_total {}\n",
      active() ? 1 : 0, epoch(), step_downs());
  if (leased())
    out += fmt::format(
        "# HELP rondo_lease_age_seconds Seconds since the lease was last renewed.\n"
        "# TYPE rondo_lease_age_seconds gauge\nrondo_lease_age_seconds {:.3f}\n",
        lease_age_seconds());
  return out;
}

struct StandbyServer::Impl {
  Impl(const ServiceRole& r, StandbyOptions o) : role(r), options(std::move(o)) {}
  const ServiceRole& role;
  StandbyOptions options;
  httplib::Server http;
  std::atomic<bool> stopping{false};
};

namespace {

void send(httplib::Response& res, const Reply& reply) {
  res.status = reply.status;
  for (const auto& [k, v] : reply.headers) res.set_header(k, v);
  res.set_content(reply.body.dump() + "\n", "application/json");
}

}  // namespace

StandbyServer::StandbyServer(const ServiceRole& role, StandbyOptions options)
    : impl_(std::make_unique<Impl>(role, std::move(options))) {
  Impl& im = *impl_;
  im.http.set_tcp_nodelay(true);
  im.http.set_read_timeout(std::chrono::seconds(5));
  im.http.Get("/healthz", [&im](const httplib::Request&, httplib::Response& res) {
    Reply r;
    r.body = Json{{"status", "standby"},
                  {"deployment", im.options.deployment},
                  {"epoch", im.role.epoch()},
                  {"active", im.role.holder()},
                  {"lease_age_seconds", im.role.lease_age_seconds()}};
    send(res, r);
  });
  im.http.Get("/metrics", [&im](const httplib::Request&, httplib::Response& res) {
    res.set_content(im.role.prometheus(), "text/plain; version=0.0.4");
  });
  // Everything else, reads included: the standby holds no executive to answer from.
  const auto unavailable = [&im](const httplib::Request&, httplib::Response& res) {
    Reply r = error_reply(503, "standby",
                          fmt::format("this rondo serve is a standby (the active is {}, epoch {}); ask the active",
                                      im.role.holder(), im.role.epoch()));
    r.headers.emplace_back("Retry-After", std::to_string(im.options.retry_after_seconds));
    send(res, r);
  };
  for (const char* pattern : {R"(/.*)"}) {
    im.http.Get(pattern, unavailable);
    im.http.Post(pattern, unavailable);
    im.http.Put(pattern, unavailable);
    im.http.Patch(pattern, unavailable);
    im.http.Delete(pattern, unavailable);
  }
}

StandbyServer::~StandbyServer() = default;

Result<int> StandbyServer::bind() {
  Impl& im = *impl_;
  if (im.options.port == 0) {
    const int port = im.http.bind_to_any_port(im.options.host);
    if (port <= 0) return Error::io(fmt::format("cannot listen on {}", im.options.host));
    return port;
  }
  if (!im.http.bind_to_port(im.options.host, im.options.port))
    return Error::io(fmt::format("cannot listen on {}:{} (in use, or not an address of this machine)",
                                 im.options.host, im.options.port));
  return im.options.port;
}

void StandbyServer::run() {
  if (!impl_->stopping) impl_->http.listen_after_bind();
}

void StandbyServer::stop() {
  impl_->stopping = true;
  impl_->http.stop();
}

}  // namespace rondo::service
