// Submitting, listing, reading, cancelling and changing tasks through the API, and the
// Idempotency-Key (also across a restart on the same data folder).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <atomic>
#include <future>

#include "live_service.h"
#include "rondo/store/events.h"
#include "rondo/store/task_table.h"
#include "test_files.h"

namespace rondo::test {
namespace {

TEST(ApiTasks, SubmissionIsCommittedBeforeTheAnswerAndReadBackWithItsEvents) {
  const auto data = fresh_dir("rondo-service-test", "submit");
  LiveService s(data);
  auto cli = s.client();
  auto r = cli.Post("/api/v1/tasks", s.task_body("door-1"), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  Json j = body_of(r);
  ASSERT_EQ(j["tasks"].size(), 1u);
  EXPECT_EQ(j["tasks"][0]["id"], "door-1");
  EXPECT_EQ(j["tasks"][0]["source"], "api");
  // Another connection to the file sees it at once: the answer came after the commit.
  auto reader = store::Store::open(data / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  auto stored = store::get_task(*reader, "door-1");
  ASSERT_TRUE(stored.ok()) << stored.error().message;
  EXPECT_EQ(stored->source, "api");

  auto one = cli.Get("/api/v1/tasks/door-1");
  ASSERT_TRUE(one);
  ASSERT_EQ(one->status, 200);
  Json t = body_of(one);
  EXPECT_EQ(t["state"], "queued");
  ASSERT_FALSE(t["events"].empty());
  EXPECT_EQ(t["events"][0]["event"], "queued");
  EXPECT_TRUE(t["planned"]["start"].is_string()) << t.dump();  // scheduled with the others

  auto missing = cli.Get("/api/v1/tasks/no-such-task");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  EXPECT_EQ(body_of(missing)["error"]["code"], "not_found");
}

// A task written as a formula (issue 41): accepted with its spec and read back with it; outside
// the fragment, or naming a node the map lacks, refused with 422 naming the field, the position
// and the reason.
TEST(ApiTasks, ASpecTaskIsAcceptedAndABadFormulaIsRefusedWithItsPosition) {
  const auto data = fresh_dir("rondo-service-test", "spec");
  LiveService s(data);
  auto cli = s.client();
  const auto body = [&s](const std::string& id, const std::string& spec) {
    std::string b = s.task_body(id);
    const std::string place = R"("start_node": "WayPoint2")";
    return b.replace(b.find(place), place.size(), R"("spec": ")" + spec + R"(")");
  };
  auto ok = cli.Post("/api/v1/tasks", body("round", "F WayPoint13 & F WayPoint19"), "application/json");
  ASSERT_TRUE(ok);
  ASSERT_EQ(ok->status, 201) << ok->body;
  auto one = cli.Get("/api/v1/tasks/round");
  ASSERT_TRUE(one);
  EXPECT_EQ(body_of(one)["task"]["spec"], "F WayPoint13 & F WayPoint19") << one->body;
  auto g = cli.Post("/api/v1/tasks", body("always", "F WayPoint13 & G WayPoint19"), "application/json");
  ASSERT_TRUE(g);
  EXPECT_EQ(g->status, 422) << g->body;
  EXPECT_NE(g->body.find("tasks[0].spec: position 16: 'G' (always) is outside the co-safe fragment"), std::string::npos)
      << g->body;
  auto lab = cli.Post("/api/v1/tasks", body("lab", "F Lab"), "application/json");
  ASSERT_TRUE(lab);
  EXPECT_EQ(lab->status, 422) << lab->body;
  EXPECT_NE(lab->body.find("the formula names 'Lab', which is not on the map"), std::string::npos) << lab->body;
}

TEST(ApiTasks, ListFiltersByStateSourceAndWindowAndPages) {
  LiveService s(fresh_dir("rondo-service-test", "list"));
  auto cli = s.client();
  for (int i = 0; i < 5; ++i)
    ASSERT_EQ(cli.Post("/api/v1/tasks", s.task_body("t" + std::to_string(i), hours(1 + i)), "application/json")->status,
              201);
  ASSERT_EQ(cli.Post("/api/v1/tasks/t0/cancel", "", "application/json")->status, 200);

  Json all = body_of(cli.Get("/api/v1/tasks?source=api"));
  EXPECT_EQ(all["total"], 5);
  Json cancelled = body_of(cli.Get("/api/v1/tasks?state=cancelled"));
  ASSERT_EQ(cancelled["total"], 1);
  EXPECT_EQ(cancelled["tasks"][0]["id"], "t0");
  Json page = body_of(cli.Get("/api/v1/tasks?source=api&limit=2&offset=2"));
  EXPECT_EQ(page["total"], 5);
  ASSERT_EQ(page["tasks"].size(), 2u);
  EXPECT_EQ(page["tasks"][0]["id"], "t2");
  EXPECT_EQ(page["tasks"][1]["id"], "t3");
  // Windows that end after from and open before to: t3 opens at +4h, t4 at +5h.
  const std::string from = format_time(s.clock().now() + hours(4) + minutes(30));
  Json late = body_of(cli.Get(("/api/v1/tasks?source=api&from=" + from).c_str()));
  EXPECT_EQ(late["total"], 3) << late.dump();  // t2 (+3h..+5h), t3, t4
  Json none = body_of(cli.Get("/api/v1/tasks?source=nobody"));
  EXPECT_EQ(none["total"], 0);

  for (const char* bad : {"/api/v1/tasks?state=sleeping", "/api/v1/tasks?limit=0", "/api/v1/tasks?offset=x",
                          "/api/v1/tasks?from=yesterday"}) {
    auto r = cli.Get(bad);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 422) << bad;
    EXPECT_TRUE(body_of(r)["error"]["field"].is_string()) << bad;
  }
}

// A finished task leaves the executor's memory (forget_finished, as in rondo serve) and the API
// reads it from the store: one task, the list, the schedule, the metrics, a cancel or change is
// 409 and its id stays taken.
TEST(ApiTasks, AFinishedTaskIsReadFromTheStoreOnceItHasLeftMemory) {
  LiveService s(fresh_dir("rondo-service-test", "forgotten"));
  auto cli = s.client();
  ASSERT_EQ(cli.Post("/api/v1/tasks", s.task_body("f1", minutes(30)), "application/json")->status, 201);
  ASSERT_EQ(cli.Post("/api/v1/tasks/f1/cancel", R"({"reason": "no longer needed"})", "application/json")->status, 200);
  ASSERT_TRUE(eventually([&] {
    bool in_memory = true;
    s.on_clock([&] { in_memory = s.executor().tasks().contains("f1"); });
    return !in_memory;
  }));
  Json one = body_of(cli.Get("/api/v1/tasks/f1"));
  EXPECT_EQ(one["state"], "cancelled");
  EXPECT_EQ(one["code"], "cancelled");
  EXPECT_NE(one["reason"].get<std::string>().find("no longer needed"), std::string::npos) << one.dump();
  EXPECT_EQ(one["activity"], "look at the door");
  EXPECT_TRUE(one["actual"]["end"].is_string()) << one.dump();
  EXPECT_EQ(one["events"].back()["event"], "cancelled");
  Json listed = body_of(cli.Get("/api/v1/tasks?state=cancelled"));
  ASSERT_EQ(listed["total"], 1);
  EXPECT_EQ(listed["tasks"][0]["id"], "f1");
  EXPECT_EQ(listed["tasks"][0]["reason"], one["reason"]);
  Json day = body_of(cli.Get("/api/v1/schedule"));
  EXPECT_TRUE(std::any_of(day["tasks"].begin(), day["tasks"].end(), [](const Json& t) { return t["id"] == "f1"; }))
      << day.dump();
  EXPECT_NE(cli.Get("/metrics")->body.find("rondo_tasks{state=\"cancelled\"} 1"), std::string::npos);
  EXPECT_EQ(cli.Post("/api/v1/tasks/f1/cancel", "", "application/json")->status, 409);
  EXPECT_EQ(cli.Patch("/api/v1/tasks/f1", R"({"priority": 1})", "application/json")->status, 409);
  auto again = cli.Post("/api/v1/tasks", s.task_body("f1"), "application/json");
  EXPECT_EQ(again->status, 422);
  EXPECT_EQ(body_of(again)["error"]["code"], "invalid");
}

// A task that ran keeps its planned start and end once it has left memory: the one-task view and
// the schedule show it planned against actual (they were null before the store kept them).
TEST(ApiTasks, AFinishedTaskIsShownPlannedAgainstActualOnceItHasLeftMemory) {
  LiveService s(fresh_dir("rondo-service-test", "planned"), {.speed = 600});
  auto cli = s.client();
  const std::string here = body_of(cli.Get("/api/v1/robot"))["node"];
  const Time now = s.clock().now();
  const std::string body = fmt::format(
      R"({{"tasks": [{{"id": "p1", "activity": "look around", "start_node": "{}", "priority": 9,
          "window": {{"release": "{}", "deadline": "{}"}}, "duration": "2m"}}]}})",
      here, format_time(now), format_time(now + hours(6)));
  ASSERT_EQ(cli.Post("/api/v1/tasks", body, "application/json")->status, 201);
  ASSERT_TRUE(eventually(
      [&] {
        bool in_memory = true;
        s.on_clock([&] { in_memory = s.executor().tasks().contains("p1"); });
        return !in_memory;
      },
      seconds(120)));
  Json one = body_of(cli.Get("/api/v1/tasks/p1"));
  ASSERT_TRUE(one["state"] == "succeeded" || one["state"] == "failed") << one.dump();
  ASSERT_TRUE(one["planned"]["start"].is_string()) << one.dump();
  ASSERT_TRUE(one["planned"]["end"].is_string()) << one.dump();
  EXPECT_TRUE(one["actual"]["start"].is_string()) << one.dump();
  EXPECT_TRUE(one["actual"]["end"].is_string()) << one.dump();
  const Time planned_start = parse_time(one["planned"]["start"].get<std::string>()).value();
  EXPECT_GE(planned_start, now);
  EXPECT_LT(planned_start, parse_time(one["planned"]["end"].get<std::string>()).value());
  // The schedule of the day it was released on (the clock runs 600 times faster meanwhile).
  const std::string date = format_time(now).substr(0, 10);
  Json day = body_of(cli.Get(("/api/v1/schedule?date=" + date).c_str()));
  const auto it = std::find_if(day["tasks"].begin(), day["tasks"].end(), [](const Json& t) { return t["id"] == "p1"; });
  ASSERT_NE(it, day["tasks"].end()) << day.dump();
  EXPECT_EQ((*it)["planned"], one["planned"]);
  EXPECT_EQ((*it)["actual"], one["actual"]);
}

// A load confirmed through the API ends the simulated robot's action before the simulated person
// would have (4 hours), as done; a task that is not loading is a conflict.
TEST(ApiTasks, ConfirmEndsTheRunningLoadAsDone) {
  LiveService s(fresh_dir("rondo-service-test", "confirm"), {.speed = 600});
  auto cli = s.client();
  const std::string here = body_of(cli.Get("/api/v1/robot"))["node"];
  const Time now = s.clock().now();
  const std::string body = fmt::format(
      R"({{"tasks": [{{"id": "ld", "activity": "take the parcel", "start_node": "{}", "priority": 9,
          "window": {{"release": "{}", "deadline": "{}"}}, "duration": "4h",
          "actions": [{{"name": "load", "args": {{"object": "parcel"}}}}]}}]}})",
      here, format_time(now), format_time(now + hours(12)));
  ASSERT_EQ(cli.Post("/api/v1/tasks", body, "application/json")->status, 201);
  ASSERT_EQ(cli.Post("/api/v1/tasks", s.task_body("later", hours(20)), "application/json")->status, 201);
  auto early = cli.Post("/api/v1/tasks/later/confirm", "", "application/json");
  EXPECT_EQ(early->status, 409);
  EXPECT_EQ(body_of(early)["error"]["code"], "conflict");
  EXPECT_EQ(cli.Post("/api/v1/tasks/nobody/confirm", "", "application/json")->status, 404);
  EXPECT_EQ(cli.Post("/api/v1/tasks/ld/confirm", R"({"who": "me"})", "application/json")->status, 422);
  ASSERT_TRUE(eventually([&] { return body_of(cli.Get("/api/v1/tasks/ld"))["state"] == "acting"; }, seconds(120)));
  auto ok = cli.Post("/api/v1/tasks/ld/confirm", R"({"by": "Sam at the front desk"})", "application/json");
  ASSERT_EQ(ok->status, 200) << ok->body;
  ASSERT_TRUE(eventually([&] { return body_of(cli.Get("/api/v1/tasks/ld"))["state"] == "succeeded"; }));
  Json done = body_of(cli.Get("/api/v1/tasks/ld"));
  const Json& events = done["events"];
  EXPECT_TRUE(std::any_of(events.begin(), events.end(), [](const Json& e) {
    return e["event"] == "confirmed" && e["reason"] == "load confirmed by Sam at the front desk";
  })) << events.dump();
  // Well before the 4 hours the simulated person takes.
  const Time acted = parse_time(done["actual"]["end"].get<std::string>()).value();
  EXPECT_LT(acted - parse_time(done["actual"]["start"].get<std::string>()).value(), hours(2)) << done.dump();
  EXPECT_EQ(cli.Post("/api/v1/tasks/ld/confirm", "", "application/json")->status, 409);
}

TEST(ApiTasks, CancelEndsAQueuedTaskAndAFinalOneIsAConflict) {
  LiveService s(fresh_dir("rondo-service-test", "cancel"));
  auto cli = s.client();
  ASSERT_EQ(cli.Post("/api/v1/tasks", s.task_body("c1"), "application/json")->status, 201);
  auto r = cli.Post("/api/v1/tasks/c1/cancel", R"({"reason": "not needed today"})", "application/json");
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(body_of(r)["state"], "cancelled");
  EXPECT_NE(body_of(r)["reason"].get<std::string>().find("not needed today"), std::string::npos);
  auto again = cli.Post("/api/v1/tasks/c1/cancel", "", "application/json");
  EXPECT_EQ(again->status, 409);
  EXPECT_EQ(body_of(again)["error"]["code"], "conflict");
  EXPECT_EQ(cli.Post("/api/v1/tasks/nobody/cancel", "", "application/json")->status, 404);
  EXPECT_EQ(cli.Post("/api/v1/tasks/c1/cancel", "{", "application/json")->status, 400);
  auto odd = cli.Post("/api/v1/tasks/c1/cancel", R"({"why": "x"})", "application/json");
  EXPECT_EQ(odd->status, 422);
  EXPECT_EQ(body_of(odd)["error"]["field"], "why");
}

TEST(ApiTasks, ChangingWindowOrPriorityReschedulesAndIsStored) {
  const auto data = fresh_dir("rondo-service-test", "change");
  LiveService s(data);
  auto cli = s.client();
  ASSERT_EQ(cli.Post("/api/v1/tasks", s.task_body("p1", hours(1)), "application/json")->status, 201);
  const Time release = s.clock().now() + hours(6);
  const std::string window = fmt::format(R"({{"window": {{"release": "{}", "deadline": "{}"}}, "priority": 7}})",
                                         format_time(release), format_time(release + hours(1)));
  auto r = cli.Patch("/api/v1/tasks/p1", window, "application/json");
  ASSERT_EQ(r->status, 200) << r->body;
  Json t = body_of(r);
  EXPECT_EQ(t["priority"], 7);
  EXPECT_EQ(t["window"]["release"], format_time(release));
  // Planned inside the new window.
  ASSERT_TRUE(t["planned"]["start"].is_string()) << t.dump();
  EXPECT_GE(*parse_time(t["planned"]["start"].get<std::string>()), release);
  auto reader = store::Store::open(data / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  auto stored = store::get_task(*reader, "p1");
  ASSERT_TRUE(stored.ok());
  EXPECT_EQ(stored->task["priority"], 7);
  auto events = store::read_events_of(*reader, "p1");
  ASSERT_TRUE(events.ok());
  EXPECT_TRUE(std::any_of(events->begin(), events->end(), [](const store::Event& e) { return e.event == "changed"; }));

  const std::string backwards = fmt::format(R"({{"window": {{"release": "{}", "deadline": "{}"}}}})",
                                            format_time(release), format_time(release - hours(1)));
  auto bad = cli.Patch("/api/v1/tasks/p1", backwards, "application/json");
  EXPECT_EQ(bad->status, 422) << bad->body;
  EXPECT_EQ(body_of(bad)["error"]["field"], "window");
  auto wrong_type = cli.Patch("/api/v1/tasks/p1", R"({"priority": "high"})", "application/json");
  EXPECT_EQ(wrong_type->status, 422);
  EXPECT_EQ(body_of(wrong_type)["error"]["field"], "priority");
  EXPECT_EQ(cli.Patch("/api/v1/tasks/p1", "[1,", "application/json")->status, 400);
  EXPECT_EQ(cli.Patch("/api/v1/tasks/nobody", R"({"priority": 1})", "application/json")->status, 404);
  ASSERT_EQ(cli.Post("/api/v1/tasks/p1/cancel", "", "application/json")->status, 200);
  EXPECT_EQ(cli.Patch("/api/v1/tasks/p1", R"({"priority": 1})", "application/json")->status, 409);
}

TEST(ApiTasks, AnIdempotencyKeyReturnsTheFirstAnswerEvenAfterARestart) {
  const auto data = fresh_dir("rondo-service-test", "idempotent");
  std::string first_body;
  std::string body;
  {
    LiveService s(data);
    auto cli = s.client();
    body = s.task_body("once", hours(3));
    const httplib::Headers key{{"Idempotency-Key", "k-123"}};
    auto first = cli.Post("/api/v1/tasks", key, body, "application/json");
    ASSERT_EQ(first->status, 201) << first->body;
    first_body = first->body;
    auto second = cli.Post("/api/v1/tasks", key, body, "application/json");
    ASSERT_EQ(second->status, 201) << second->body;
    EXPECT_EQ(body_of(second), body_of(first));
    EXPECT_EQ(body_of(cli.Get("/api/v1/tasks?source=api"))["total"], 1);
    // The same key for another request is refused, naming the header.
    auto other = cli.Post("/api/v1/tasks", key, s.task_body("twice"), "application/json");
    EXPECT_EQ(other->status, 422);
    EXPECT_EQ(body_of(other)["error"]["field"], "Idempotency-Key");
    // Without the key the same ids are refused: never a second task.
    EXPECT_EQ(cli.Post("/api/v1/tasks", body, "application/json")->status, 422);
  }
  LiveService again(data);
  auto cli = again.client();
  auto retried = cli.Post("/api/v1/tasks", {{"Idempotency-Key", "k-123"}}, body, "application/json");
  ASSERT_EQ(retried->status, 201) << retried->body;
  EXPECT_EQ(body_of(retried), Json::parse(first_body));
  auto reader = store::Store::open(data / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  auto all = store::list_tasks(*reader);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(std::count_if(all->begin(), all->end(), [](const store::TaskRow& t) { return t.id == "once"; }), 1);
}

// A submission the executive's thread cannot take in time is withdrawn: 503, and never carried
// out later behind the client's back.
TEST(ApiTasks, ASubmissionNotTakenInTimeIsWithdrawnNotDoneLater) {
  const auto data = fresh_dir("rondo-service-test", "withdrawn");
  LiveService s(data, {.answer_timeout = std::chrono::milliseconds(200)});
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> blocked{false};
  s.clock().post([&blocked, released] {  // the executive is busy until the test says so
    blocked = true;
    released.wait();
  });
  ASSERT_TRUE(eventually([&] { return blocked.load(); }));
  auto cli = s.client();
  auto r = cli.Post("/api/v1/tasks", s.task_body("late"), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 503) << r->body;
  release.set_value();
  // Once the executive is free again, the withdrawn request has not been carried out.
  EXPECT_EQ(cli.Get("/healthz")->status, 200);
  EXPECT_EQ(cli.Get("/api/v1/tasks/late")->status, 404);
  auto reader = store::Store::open(data / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(reader.ok());
  EXPECT_FALSE(store::get_task(*reader, "late").ok());
}

}  // namespace
}  // namespace rondo::test
