#include "rondo/sim/request_generator.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <set>
#include <string>

#include "sim_test_util.h"

namespace rondo::sim {
namespace {

using namespace rondo::sim::testing;

RequestGenerator g4s_people() {
  auto people = RequestGenerator::load("examples/g4s/requests.yaml", g4s_map(), london());
  EXPECT_TRUE(people.ok()) << (people.ok() ? "" : people.error().message);
  return std::move(people).value();
}

// Many requests a day from the one place "Hall", for the small map.
RequestSpec busy_hall(double per_day) {
  Task task;
  task.duration = minutes(1);
  task.actions = {Action{"talk", {}}};
  return RequestSpec{.per_day = per_day, .templates = {{.name = "t", .places = {"Hall"}, .task = task}}};
}

bool in_office_hours(Time t) {
  const auto wd = london().day_of_week(t);
  const auto tod = london().time_of_day(t);
  return wd != std::chrono::Saturday && wd != std::chrono::Sunday && tod >= hours(9) && tod < hours(17);
}

TEST(RequestGenerator, OnlyInOfficeHoursWithUniqueValidIds) {
  const auto people = g4s_people();
  Rng rng(1);
  // Four weeks across the October clock change: office hours stay 09:00-17:00 local.
  const Time from = local("2026-10-12T00:00");
  const Time to = local("2026-11-09T00:00");
  const auto requests = people.between(from, to, rng);
  // 20 office days at 4 a day on average.
  EXPECT_GT(requests.size(), 50u);
  EXPECT_LT(requests.size(), 120u);
  std::set<std::string> ids;
  Time previous = from;
  for (const Request& r : requests) {
    EXPECT_TRUE(in_office_hours(r.at)) << london().format_local(r.at);
    EXPECT_GE(r.at, previous);
    previous = r.at;
    EXPECT_TRUE(ids.insert(r.task.id).second) << r.task.id;
    EXPECT_EQ(r.task.kind, TaskKind::kOnDemand);
    EXPECT_TRUE(validate(r.task).ok());
    EXPECT_TRUE(g4s_map().find_node(r.task.start_node).has_value());
    EXPECT_FALSE(r.task.actions.empty());
  }
  EXPECT_EQ(requests.front().task.id.rfind("req-2026-10-", 0), 0u) << requests.front().task.id;
}

TEST(RequestGenerator, SameRngStateSameRequests) {
  const auto people = g4s_people();
  const Time from = local("2026-11-23T00:00");
  Rng a(5), b(5), c(6);
  const auto ra = people.between(from, from + std::chrono::days(7), a);
  const auto rb = people.between(from, from + std::chrono::days(7), b);
  const auto rc = people.between(from, from + std::chrono::days(7), c);
  ASSERT_EQ(ra.size(), rb.size());
  for (std::size_t i = 0; i < ra.size(); ++i) {
    EXPECT_EQ(ra[i].at, rb[i].at);
    EXPECT_EQ(ra[i].task, rb[i].task);
  }
  bool differs = ra.size() != rc.size();
  for (std::size_t i = 0; !differs && i < ra.size(); ++i) differs = ra[i].at != rc[i].at;
  EXPECT_TRUE(differs);
}

TEST(RequestGenerator, TheIdNamesTheLocalDateAndTime) {
  RequestGenerator people(busy_hall(2000), london());
  Rng rng(2);
  const auto requests = people.between(local("2026-07-01T10:00"), local("2026-07-01T10:05"), rng);
  ASSERT_FALSE(requests.empty());
  const Request& r = requests.front();
  const auto tod = std::chrono::duration_cast<std::chrono::seconds>(london().time_of_day(r.at)).count();
  char expected[64];
  std::snprintf(expected, sizeof expected, "req-2026-07-01-%02lld%02lld%02lld", static_cast<long long>(tod / 3600),
                static_cast<long long>(tod / 60 % 60), static_cast<long long>(tod % 60));
  EXPECT_EQ(r.task.id, expected);
  EXPECT_EQ(r.task.id.substr(0, 17), "req-2026-07-01-10");  // 10:0x local (BST), 09:0x UTC
}

// Splitting an interval into pieces never gives two requests one id, and all stay inside.
RC_GTEST_PROP(RequestGenerator, DisjointCallsNeverRepeatAnId, (std::uint64_t seed)) {
  RequestGenerator people(busy_hall(300), london());
  Rng rng(seed);
  std::set<std::string> ids;
  Time t = local("2026-11-23T08:00");
  const auto cuts = *rc::gen::container<std::vector<std::uint32_t>>(rc::gen::inRange<std::uint32_t>(1, 7200));
  for (std::uint32_t cut : cuts) {
    const Time next = t + seconds(cut);
    for (const Request& r : people.between(t, next, rng)) {
      RC_ASSERT(r.at >= t);
      RC_ASSERT(r.at < next);
      RC_ASSERT(ids.insert(r.task.id).second);
    }
    t = next;
  }
}

struct BadRequests {
  const char* text;
  const char* message;
};

class RequestErrors : public ::testing::TestWithParam<BadRequests> {};

TEST_P(RequestErrors, NameTheFileLineAndField) {
  auto doc = Document::parse(GetParam().text, DocumentFormat::kYaml, "requests.yaml");
  ASSERT_TRUE(doc.ok());
  auto people = RequestGenerator::decode(*doc, small_map(), london());
  ASSERT_FALSE(people.ok());
  EXPECT_NE(people.error().message.find(GetParam().message), std::string::npos) << people.error().message;
}

INSTANTIATE_TEST_SUITE_P(
    Table, RequestErrors,
    ::testing::Values(
        BadRequests{"per_day: 3\n", "templates"},
        BadRequests{"from: \"17:00\"\nto: \"09:00\"\ntemplates: []\n", "requests.yaml:2: to: office hours must end"},
        BadRequests{"templates:\n  - name: t\n    places: [Hall, Attic]\n", "requests.yaml:3: templates[0].places[1]: map 'small' has no node 'Attic'"},
        BadRequests{"templates:\n  - name: t\n    places: [Hall]\n    colour: red\n", "colour"},
        BadRequests{"days: [someday]\ntemplates: []\n", "requests.yaml:1: days[0]: unknown day"},
        BadRequests{"per_day: -1\ntemplates: []\n", "requests.yaml:1: per_day: must be from 0"}));

}  // namespace
}  // namespace rondo::sim
