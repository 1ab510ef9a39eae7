// GET /api/v1/events: the event log as server-sent events. Each event's id is its sequence number
// in the log, so a client that reconnects with Last-Event-ID (or ?after=) gets exactly the events
// after the last one it saw. The stream reads through a read-only store connection of its own,
// never the executor's, and looks for new events when the clock's thread has carried out a request (Api::news), else
// every stream_poll.
#include <fmt/format.h>

#include <chrono>
#include <thread>

#include "api.h"
#include "rondo/store/events.h"

namespace rondo::service {
namespace {

constexpr std::int64_t kBatch = 256;

struct Stream {
  store::Store store;
  std::int64_t last = 0;
  std::chrono::steady_clock::time_point last_write = std::chrono::steady_clock::now();
};

// Where a stream starts: after Last-Event-ID (a reconnecting client), ?after=N, or the last
// ?tail=N events of the log (a page that shows only the recent ones); else the whole log.
Result<std::int64_t> resume_point(const httplib::Request& req, const store::Store& db) {
  std::string text;
  if (req.has_header("Last-Event-ID")) {
    text = req.get_header_value("Last-Event-ID");
  } else if (req.has_param("after")) {
    text = req.get_param_value("after");
  } else if (req.has_param("tail")) {
    auto tail = query_int(req, "tail", 0, 100000);
    if (!tail) return tail.error();
    RONDO_ASSIGN_OR_RETURN(const store::LogEnd end, store::log_end(db));
    return std::max<std::int64_t>(0, end.seq - **tail);
  } else {
    return std::int64_t{0};
  }
  std::int64_t v = -1;
  std::size_t used = 0;
  try {
    v = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || v < 0)
    return Error::invalid(fmt::format("Last-Event-ID: expected an event sequence number, found '{}'", text));
  return v;
}

}  // namespace

void event_stream(Api& api, const httplib::Request& req, httplib::Response& res) {
  if (api.streams.load() >= api.options.threads / 2) {
    const Reply r = error_reply(503, "unavailable", "too many event streams are open; try again later");
    res.status = r.status;
    res.set_header("Retry-After", "5");
    res.set_content(r.body.dump() + "\n", "application/json");
    return;
  }
  auto db = store::Store::open(api.ctx.store.location(), {.mode = store::OpenMode::kReadOnly});
  if (!db) {
    const Reply r = error_reply(500, "internal", db.error().message);
    res.status = r.status;
    res.set_content(r.body.dump() + "\n", "application/json");
    return;
  }
  auto after = resume_point(req, *db);
  if (!after) {
    const Reply r =
        error_reply(422, "invalid", after.error().message,
                    req.has_header("Last-Event-ID") ? "Last-Event-ID" : (req.has_param("after") ? "after" : "tail"));
    res.status = r.status;
    res.set_content(r.body.dump() + "\n", "application/json");
    return;
  }
  auto stream = std::make_shared<Stream>(Stream{std::move(*db), *after});
  ++api.streams;
  res.set_header("Cache-Control", "no-cache");
  res.set_header("X-Accel-Buffering", "no");
  res.set_chunked_content_provider(
      "text/event-stream",
      [&api, stream](std::size_t, httplib::DataSink& sink) {
        while (!api.stopping && sink.is_writable()) {
          const std::uint64_t seen = api.news->count();
          auto events = store::read_events(stream->store, stream->last, kBatch);
          if (!events) return false;
          if (!events->empty()) {
            std::string chunk;
            for (const store::Event& e : *events)
              chunk += fmt::format("id: {}\ndata: {}\n\n", e.seq, event_json(e).dump());
            if (!sink.write(chunk.data(), chunk.size())) return false;
            stream->last = events->back().seq;
            stream->last_write = std::chrono::steady_clock::now();
            return true;
          }
          if (std::chrono::steady_clock::now() - stream->last_write >= api.options.stream_keepalive) {
            static constexpr char kKeepAlive[] = ": keep-alive\n\n";
            if (!sink.write(kKeepAlive, sizeof kKeepAlive - 1)) return false;
            stream->last_write = std::chrono::steady_clock::now();
            return true;
          }
          api.news->wait(seen, api.options.stream_poll);  // waiting for news, not for a test
        }
        sink.done();
        return true;
      },
      [&api](bool) { --api.streams; });
}

}  // namespace rondo::service
