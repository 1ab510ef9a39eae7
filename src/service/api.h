// Inside rondo::service: the pieces the route files share. Not a public header.
#pragma once

#include <httplib.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/service/server.h"

namespace rondo::service {

// A response: a JSON body (or text, for /metrics and the event stream) and its status.
struct Reply {
  int status = 200;
  Json body = Json::object();
  std::string text{};  // used instead of body when content_type is not JSON
  std::string content_type = "application/json";
  std::vector<std::pair<std::string, std::string>> headers{};
};

// The error body {"error": {"code", "message", "field"}}; the field is null when none is known.
Reply error_reply(int status, std::string code, std::string message, std::string field = "");
// The reply for a library error: kInvalidInput 422, kNotFound 404, kConflict 409, else 500. The
// field path is read from the message ("request:3: tasks[0].window.deadline: ...").
Reply error_reply(const Error& error);
// The field path an error message names after its source and line, or "" when it names none.
std::string field_of(const std::string& message);

// Request latency and counts, by route, for /metrics. Thread-safe.
class RequestMetrics {
 public:
  void record(const std::string& route, int status, double seconds);
  std::string prometheus() const;

 private:
  struct PathMetrics {
    std::map<int, long> by_status;
    double seconds = 0;
    long count = 0;
    std::vector<long> buckets;  // cumulative counts at kBounds
  };
  mutable std::mutex mutex_;
  std::map<std::string, PathMetrics> routes_;
};

// Wakes the event streams when something may have been committed: the clock's thread tells after
// every request it carried out, so a stream sends a request's events at once rather than at its
// next look (the executor's own events are still found by looking every stream_poll). Thread-safe.
class News {
 public:
  std::uint64_t count() const {
    std::lock_guard lock(mutex_);
    return count_;
  }
  void tell() {
    {
      std::lock_guard lock(mutex_);
      ++count_;
    }
    changed_.notify_all();
  }
  // Until something is told after `seen` (a count()), or `timeout` passed.
  template <class Rep, class Period>
  void wait(std::uint64_t seen, std::chrono::duration<Rep, Period> timeout) const {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return count_ != seen; });
  }

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::uint64_t count_ = 0;
};

struct Api {
  ServiceContext ctx;
  ServerOptions options;
  RequestMetrics metrics;
  std::atomic<bool> stopping{false};
  std::atomic<int> streams{0};
  std::atomic<std::size_t> http_threads{0};  // running now (HttpPool)
  // The callbacks posted to the clock's thread hold what they need (the news, the group below),
  // never the Api: one that runs after the server has gone (its requests withdrawn, the clock
  // run on) reaches nothing of the server's.
  std::shared_ptr<News> news = std::make_shared<News>();

  // Runs `work` on the clock's thread and waits for its reply (503 when it does not come within
  // the answer timeout, e.g. while shutting down).
  Reply on_clock(std::function<Reply()> work);
  // As on_clock, for a write that commits its own store::Batch (a submission). The writes that
  // wait for the clock's thread together run inside one outer Batch and are answered after its
  // one synced commit (group commit: a burst of submissions costs one sync, not one each; each
  // is still answered only once its commit is on disk). If that commit fails, each is answered
  // with its error.
  Reply on_clock_grouped(std::function<Reply()> work);

  struct Grouped;  // a write waiting for the clock's thread
  struct Group {
    std::mutex mutex;
    std::vector<std::shared_ptr<Grouped>> waiting;  // guarded by mutex
  };
  std::shared_ptr<Group> group = std::make_shared<Group>();
  // On the clock's thread: the writes waiting now, in one commit on `store`.
  static void run_group(Group& group, store::Store& store, News& news);
};

using Handler = std::function<Reply(Api&, const httplib::Request&)>;
struct Endpoint {
  std::string method;  // GET, POST, PATCH, DELETE
  std::string path;    // OpenAPI form: /api/v1/tasks/{id}
  bool write = false;  // needs the token when there is one
  Handler handler;
  bool stream = false;  // the event stream: answered by event_stream() itself
};

void add_task_endpoints(std::vector<Endpoint>& routes);
void add_command_endpoints(std::vector<Endpoint>& routes);  // commands in words (rondo::lang)
void add_robot_endpoints(std::vector<Endpoint>& routes);
void add_observation_endpoints(std::vector<Endpoint>& routes);  // the building's sensors
void add_meta_endpoints(std::vector<Endpoint>& routes);  // health, metrics, OpenAPI
void add_dashboard_endpoints(std::vector<Endpoint>& routes);

// On the clock's thread: adds the routines to the running executor and stores each before the
// answer (201 with the routines, or the first error; robot_routes.cpp). POST /api/v1/routines
// and a repeated command in words (POST /api/v1/commands) both come here.
Reply add_routines_now(Api& api, std::vector<Routine> list);

// The event stream (GET /api/v1/events): sets a chunked provider on `res`.
void event_stream(Api& api, const httplib::Request& req, httplib::Response& res);

// A request's body as a JSON object, read as every JSON document is (rondo::Document: a key given
// twice in one object is refused, as YAML refuses it). Nothing when `body` holds it; else the reply
// that refuses it: 400 when the body is not JSON or not an object, 422 naming the field when an
// object in it gives a key twice ("request body:3: tasks[0].duration: duplicate key 'duration'").
std::optional<Reply> read_json_object(const httplib::Request& req, Json& body);

// The body of a task file as text, with the deployment's time zone when it names none.
std::string with_default_zone(Json body, const TimeZone& zone);

// JSON views (json_views.cpp)
Json time_json(std::optional<Time> t);
Json task_json(const exec::TaskRecord& record);
Json event_json(const store::Event& event);
// A query parameter as a time ("2026-11-23T09:00:00Z"); an error names the parameter.
Result<std::optional<Time>> query_time(const httplib::Request& req, const char* name);
Result<std::optional<long>> query_int(const httplib::Request& req, const char* name, long min, long max);

}  // namespace rondo::service
