// The event stream: every event of the log in order, and a client that drops its connection and
// comes back with Last-Event-ID gets every event after the last it saw, none twice.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "live_service.h"
#include "rondo/store/events.h"
#include "test_files.h"

namespace rondo::test {
namespace {

// Reads the stream until `enough` of events are collected (or the deadline); returns their seqs.
std::vector<std::int64_t> read_stream(LiveService& s, const httplib::Headers& headers, std::size_t enough,
                                      const std::string& path = "/api/v1/events") {
  std::vector<std::int64_t> seqs;
  std::string buffer;
  auto cli = s.client();
  cli.set_read_timeout(std::chrono::seconds(30));
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  auto r = cli.Get(path.c_str(), headers, [&](const char* data, std::size_t n) {
    buffer.append(data, n);
    std::size_t at;
    while ((at = buffer.find("\n\n")) != std::string::npos) {
      const std::string message = buffer.substr(0, at);
      buffer.erase(0, at + 2);
      if (message.starts_with(":")) continue;  // keep-alive
      EXPECT_TRUE(message.starts_with("id: ")) << message;
      const std::size_t nl = message.find('\n');
      const std::int64_t id = std::stoll(message.substr(4, nl - 4));
      const Json data_json = Json::parse(message.substr(nl + 7), nullptr, false);  // "\ndata: "
      EXPECT_FALSE(data_json.is_discarded()) << message;
      EXPECT_EQ(data_json["seq"], id);
      seqs.push_back(id);
    }
    return seqs.size() < enough && std::chrono::steady_clock::now() < end;  // false: drop the connection
  });
  return seqs;
}

TEST(ApiEvents, AResumedStreamMissesNothingAndRepeatsNothing) {
  const auto data = fresh_dir("rondo-service-test", "events");
  LiveService s(data);
  auto cli = s.client();
  for (int i = 0; i < 3; ++i)
    ASSERT_EQ(cli.Post("/api/v1/tasks", s.task_body("e" + std::to_string(i), hours(1 + i)), "application/json")->status,
              201);
  auto reader = store::Store::open(data / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(reader.ok());
  const auto log_seqs = [&] {
    std::vector<std::int64_t> out;
    auto events = store::read_events(*reader);
    EXPECT_TRUE(events.ok());
    if (events.ok())
      for (const store::Event& e : *events) out.push_back(e.seq);
    return out;
  };
  const std::vector<std::int64_t> before = log_seqs();
  ASSERT_GE(before.size(), 4u);

  // First connection: read part of the log, then drop.
  std::vector<std::int64_t> first = read_stream(s, {}, 2);
  ASSERT_GE(first.size(), 2u);
  // More events while disconnected, then more during the second connection.
  for (int i = 3; i < 6; ++i)
    ASSERT_EQ(cli.Post("/api/v1/tasks", s.task_body("e" + std::to_string(i), hours(1 + i)), "application/json")->status,
              201);
  auto c2 = s.client();
  ASSERT_EQ(c2.Post("/api/v1/tasks/e5/cancel", "", "application/json")->status, 200);  // answered after its commit
  const std::int64_t resume = first.back();
  const std::vector<std::int64_t> all = log_seqs();
  std::size_t after = 0;
  for (auto q : all)
    if (q > resume) ++after;
  ASSERT_GT(after, 0u);
  const std::vector<std::int64_t> second = read_stream(s, {{"Last-Event-ID", std::to_string(resume)}}, after);

  std::vector<std::int64_t> seen(first.begin(), first.end());
  seen.insert(seen.end(), second.begin(), second.end());
  EXPECT_EQ(seen, all);  // in order, each once, none missing
  EXPECT_GT(all.size(), before.size());

  // ?after= is the same for clients that cannot set headers; a bad id is refused.
  std::vector<std::int64_t> tail = read_stream(s, {}, 1, "/api/v1/events?after=" + std::to_string(all.back() - 1));
  EXPECT_EQ(tail, std::vector<std::int64_t>{all.back()});
  EXPECT_EQ(cli.Get("/api/v1/events", {{"Last-Event-ID", "yesterday"}})->status, 422);
}

// Streams hold an HTTP thread each: past half of the threads they are refused, so requests are
// still answered.
TEST(ApiEvents, StreamsPastHalfTheThreadsAreRefusedAndRequestsStillAnswered) {
  LiveService s(fresh_dir("rondo-service-test", "stream-cap"), {.threads = 4});
  std::atomic<int> open{0};
  std::atomic<bool> done{false};
  std::vector<std::thread> streams;
  for (int i = 0; i < 2; ++i)
    streams.emplace_back([&] {
      auto c = s.client();
      bool counted = false;
      (void)c.Get("/api/v1/events", [&](const char*, std::size_t) {
        if (!counted) ++open;
        counted = true;
        return !done.load();
      });
    });
  ASSERT_TRUE(eventually([&] { return open.load() == 2; }));
  auto cli = s.client();
  auto third = cli.Get("/api/v1/events");
  ASSERT_TRUE(third);
  EXPECT_EQ(third->status, 503);
  EXPECT_EQ(cli.Get("/healthz")->status, 200);
  done = true;
  // The streams see keep-alives every second, and end at the next one.
  for (auto& t : streams) t.join();
}

}  // namespace
}  // namespace rondo::test
