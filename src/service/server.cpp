// The HTTP server: routes from the route table, the host and token checks before any route, JSON
// errors for whatever httplib refuses itself (unknown routes, bodies past the limit), and the hand
// over of every request to the clock's thread.
#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <future>
#include <regex>

#include "api.h"
#include "http_pool.h"
#include "rondo/store/batch.h"

namespace rondo::service {
namespace {

// "/api/v1/tasks/{id}" -> "/api/v1/tasks/([^/]+)"
std::string path_regex(const std::string& path) {
  static const std::regex param(R"(\{[a-z_]+\})");
  return std::regex_replace(path, param, "([^/]+)");
}

// Compares in time that depends only on the lengths, not on where the texts differ.
bool same_secret(const std::string& a, const std::string& b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  const std::size_t n = std::max(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char x = i < a.size() ? static_cast<unsigned char>(a[i]) : 0;
    const unsigned char y = i < b.size() ? static_cast<unsigned char>(b[i]) : 0;
    diff |= static_cast<unsigned char>(x ^ y);
  }
  return diff == 0;
}

bool is_write(const std::string& method) {
  return method != "GET" && method != "HEAD" && method != "OPTIONS";
}

void send(httplib::Response& res, const Reply& reply) {
  res.status = reply.status;
  for (const auto& [k, v] : reply.headers) res.set_header(k, v);
  if (reply.content_type == "application/json")
    res.set_content(reply.body.dump() + "\n", "application/json");
  else
    res.set_content(reply.text, reply.content_type.c_str());
}

}  // namespace

// A request the clock's thread has not started within the answer timeout is withdrawn (503: it
// was not carried out); one it has started is waited for to the end, so a 503 never hides a commit.
Reply Api::on_clock(std::function<Reply()> work) {
  if (stopping) return error_reply(503, "unavailable", "the service is shutting down");
  enum : int { kPending, kStarted, kWithdrawn };
  auto promise = std::make_shared<std::promise<Reply>>();
  auto stage = std::make_shared<std::atomic<int>>(kPending);
  std::future<Reply> answer = promise->get_future();
  ctx.clock.post([news = news, promise, stage, work = std::move(work)] {
    int expected = kPending;
    if (!stage->compare_exchange_strong(expected, kStarted)) return;  // withdrawn: the client has its 503
    try {
      promise->set_value(work());
    } catch (const std::exception& e) {
      promise->set_value(error_reply(500, "internal", fmt::format("internal error: {}", e.what())));
    }
    news->tell();  // its commits, if any, are done: the event streams look now
  });
  if (answer.wait_for(options.answer_timeout) != std::future_status::ready) {
    int expected = kPending;
    if (stage->compare_exchange_strong(expected, kWithdrawn))
      return error_reply(503, "unavailable", "the executive did not take the request in time; it was not carried out");
  }
  return answer.get();
}

struct Api::Grouped {
  std::function<Reply()> work;
  std::promise<Reply> promise;
  std::atomic<int> stage{0};  // 0 pending, 1 started, 2 withdrawn (as in on_clock)
};

Reply Api::on_clock_grouped(std::function<Reply()> work) {
  if (stopping) return error_reply(503, "unavailable", "the service is shutting down");
  enum : int { kPending, kStarted, kWithdrawn };
  auto item = std::make_shared<Grouped>();
  item->work = std::move(work);
  std::future<Reply> answer = item->promise.get_future();
  bool first = false;
  {
    std::lock_guard lock(group->mutex);
    first = group->waiting.empty();
    group->waiting.push_back(item);
  }
  // The first of a group asks the clock's thread to run it; the ones that come before it runs join.
  if (first) ctx.clock.post([group = group, &store = ctx.store, news = news] { run_group(*group, store, *news); });
  if (answer.wait_for(options.answer_timeout) != std::future_status::ready) {
    int expected = kPending;
    if (item->stage.compare_exchange_strong(expected, kWithdrawn))
      return error_reply(503, "unavailable", "the executive did not take the request in time; it was not carried out");
  }
  return answer.get();
}

void Api::run_group(Group& group, store::Store& store, News& news) {
  std::vector<std::shared_ptr<Grouped>> items;
  {
    std::lock_guard lock(group.mutex);
    items.swap(group.waiting);
  }
  std::vector<std::pair<std::shared_ptr<Grouped>, Reply>> done;
  {
    store::Batch batch(store);  // each write's own Batch is a savepoint in it
    for (const std::shared_ptr<Grouped>& item : items) {
      int expected = 0;
      if (!item->stage.compare_exchange_strong(expected, 1)) continue;  // withdrawn: answered 503
      try {
        done.emplace_back(item, item->work());
      } catch (const std::exception& e) {
        done.emplace_back(item, error_reply(500, "internal", fmt::format("internal error: {}", e.what())));
      }
    }
    if (Status ok = batch.commit(); !ok)
      for (auto& [item, reply] : done) reply = error_reply(ok.error());  // none of them is stored
  }
  for (auto& [item, reply] : done) item->promise.set_value(std::move(reply));
  news.tell();  // the commit is done: the event streams look now
}

struct Server::Impl {
  Impl(ServiceContext c, ServerOptions o) : api{std::move(c), std::move(o), {}, {false}, {0}, {0}} {}
  Api api;
  httplib::Server http;
  std::vector<Endpoint> endpoints;
  int port = 0;
  std::vector<std::string> hosts;  // accepted Host header values

  bool host_ok(const httplib::Request& req) const {
    if (hosts.empty()) return true;  // a wildcard address with a token: any name of this machine
    const std::string host = req.get_header_value("Host");
    for (const std::string& h : hosts)
      if (host == h) return true;
    return false;
  }
  void add(const Endpoint& route);
};

void Server::Impl::add(const Endpoint& route) {
  const std::string name = route.method + " " + route.path;
  httplib::Server::Handler handler;
  if (route.stream) {
    handler = [this](const httplib::Request& req, httplib::Response& res) { event_stream(api, req, res); };
  } else {
    handler = [this, name, h = route.handler](const httplib::Request& req, httplib::Response& res) {
      const auto start = std::chrono::steady_clock::now();
      Reply reply;
      try {
        reply = h(api, req);
      } catch (const std::exception& e) {
        reply = error_reply(500, "internal", fmt::format("internal error: {}", e.what()));
      }
      send(res, reply);
      api.metrics.record(name, reply.status,
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    };
  }
  const std::string pattern = path_regex(route.path);
  if (route.method == "GET")
    http.Get(pattern, handler);
  else if (route.method == "POST")
    http.Post(pattern, handler);
  else if (route.method == "PATCH")
    http.Patch(pattern, handler);
  else if (route.method == "DELETE")
    http.Delete(pattern, handler);
}

Server::Server(ServiceContext context, ServerOptions options)
    : impl_(std::make_unique<Impl>(std::move(context), std::move(options))) {
  add_meta_endpoints(impl_->endpoints);
  add_task_endpoints(impl_->endpoints);
  add_command_endpoints(impl_->endpoints);
  add_robot_endpoints(impl_->endpoints);
  add_observation_endpoints(impl_->endpoints);
  add_dashboard_endpoints(impl_->endpoints);
  for (const Endpoint& r : impl_->endpoints) impl_->add(r);
  Impl& im = *impl_;
  const ServerOptions& o = im.api.options;
  // Threads started as connections need them and ended when idle, up to o.threads (http_pool.h).
  im.http.new_task_queue = [&im, threads = o.threads, idle = o.thread_idle_exit] {
    return new HttpPool(static_cast<std::size_t>(threads), idle, &im.api.http_threads);
  };
  // Answers are small and written in pieces (headers, then the body): without TCP_NODELAY a
  // piece can wait for the client's delayed ACK, about 40 ms on Linux (the VDA 5050 broker had the
  // same trouble, docs/vda5050.md).
  im.http.set_tcp_nodelay(true);
  im.http.set_payload_max_length(o.body_limit);
  im.http.set_read_timeout(std::chrono::duration_cast<std::chrono::microseconds>(o.read_timeout));
  im.http.set_write_timeout(std::chrono::duration_cast<std::chrono::microseconds>(o.read_timeout));
  im.http.set_keep_alive_timeout(
      std::max<time_t>(1, std::chrono::duration_cast<std::chrono::seconds>(o.read_timeout).count()));
  im.http.set_pre_routing_handler([&im](const httplib::Request& req, httplib::Response& res) {
    if (!im.host_ok(req)) {
      send(res, error_reply(403, "host", fmt::format("Host '{}' is not this service's", req.get_header_value("Host"))));
      return httplib::Server::HandlerResponse::Handled;
    }
    if (im.api.options.token && is_write(req.method)) {
      const std::string auth = req.get_header_value("Authorization");
      if (auth.empty()) {
        send(res, error_reply(401, "unauthorized", "this write needs 'Authorization: Bearer <token>'"));
        res.set_header("WWW-Authenticate", "Bearer");
        return httplib::Server::HandlerResponse::Handled;
      }
      const std::string prefix = "Bearer ";
      if (auth.rfind(prefix, 0) != 0 || !same_secret(auth.substr(prefix.size()), *im.api.options.token)) {
        send(res, error_reply(403, "forbidden", "the token is not this service's"));
        return httplib::Server::HandlerResponse::Handled;
      }
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  im.http.set_error_handler(
      httplib::Server::HandlerWithResponse([](const httplib::Request& req, httplib::Response& res) {
        if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
        Reply r;
        switch (res.status) {
          case 404:
            r = error_reply(404, "not_found", fmt::format("no route {} {}", req.method, req.path));
            break;
          case 413:
            r = error_reply(413, "too_large", "the request body is larger than the service accepts");
            break;
          case 400:
            r = error_reply(400, "malformed", "the request is not valid HTTP");
            break;
          default:
            r = error_reply(res.status, "error", fmt::format("HTTP {}", res.status));
            break;
        }
        send(res, r);
        return httplib::Server::HandlerResponse::Handled;
      }));
}

Server::~Server() {
  stop();
}

Result<int> Server::bind() {
  Impl& im = *impl_;
  const ServerOptions& o = im.api.options;
  if (!is_loopback_host(o.host) && !o.token)
    return Error::invalid(fmt::format("--listen {}: a host other than loopback needs --token-file", o.host));
  const std::string host = o.host == "localhost" ? "127.0.0.1" : (o.host == "[::1]" ? "::1" : o.host);
  int port = o.port;
  if (port == 0) {
    port = im.http.bind_to_any_port(host);
    if (port <= 0) return Error::io(fmt::format("cannot listen on {}", host));
  } else if (!im.http.bind_to_port(host, port)) {
    return Error::io(fmt::format("cannot listen on {}:{} (in use, or not an address of this machine)", host, port));
  }
  im.port = port;
  if (host == "0.0.0.0" || host == "::") return port;
  const std::string shown = host.find(':') != std::string::npos ? "[" + host + "]" : host;
  for (const std::string& h : {shown, std::string("localhost"), std::string("127.0.0.1"), std::string("[::1]")}) {
    if (h != shown && !is_loopback_host(o.host)) continue;  // a public host: only its own name
    im.hosts.push_back(fmt::format("{}:{}", h, port));
    if (port == 80) im.hosts.push_back(h);
  }
  return port;
}

void Server::run() {
  if (!impl_->api.stopping) impl_->http.listen_after_bind();
}

void Server::stop() {
  impl_->api.stopping = true;
  impl_->api.news->tell();  // the event streams end now, not at their next look
  impl_->http.stop();
}

std::vector<EndpointInfo> Server::endpoints() const {
  std::vector<EndpointInfo> out;
  for (const Endpoint& r : impl_->endpoints) out.push_back({r.method, r.path});
  return out;
}

}  // namespace rondo::service
