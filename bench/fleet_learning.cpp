// What a fleet gains in learning (issue 38, "Learning from the whole fleet"): Table I's mean |e|
// of journey-time estimates from models fitted on the first N days of a lone robot's traversal
// log, against models fitted on the first N days of a fleet's log in the same building, scored on
// the same journeys: one robot's (the robot both runs have) in a later test window, of each run.
// Offline estimates (the models as fitted after N days: evaluate_travel's offline rows), per
// model family; the fleet's models are fitted in its standard time with the robots' learned paces
// (learn::RobotSpeeds), and the lone robot's log has one robot, so its paces are all 1.
//
//   build/bench/bench_fleet_learning MAP LONE.sqlite FLEET.sqlite START [ROBOT=r1] [DAYS=3,7]
//                                    [TEST_FROM=7] [TEST_TO=10] [ZONE=Europe/London]
//
// START is the runs' first local day (YYYY-MM-DD); the test window is [START + TEST_FROM days,
// START + TEST_TO days). bench/fleet-learning/run makes the two runs and calls this.
#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "rondo/core/timezone.h"
#include "rondo/map/map_loader.h"
#include "rondo/plan/travel_evaluation.h"
#include "rondo/store/store.h"
#include "rondo/store/traversal_log.h"

using namespace rondo;

namespace {

std::vector<Traversal> read_log(const std::string& path) {
  auto db = store::Store::open(path);
  if (!db) throw std::runtime_error(db.error().message);
  auto log = store::find_traversals(*db);
  if (!log) throw std::runtime_error(log.error().message);
  return std::move(*log);
}

std::vector<Traversal> of_robot(const std::vector<Traversal>& log, const std::string& robot) {
  std::vector<Traversal> out;
  for (const Traversal& t : log)
    if (t.robot == robot) out.push_back(t);
  return out;
}

std::vector<int> day_list(const std::string& text) {
  std::vector<int> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::stoi(item));
  return out;
}

std::chrono::year_month_day parse_day(const std::string& text) {
  int y = 0;
  unsigned m = 0, d = 0;
  if (std::sscanf(text.c_str(), "%d-%u-%u", &y, &m, &d) != 3)
    throw std::runtime_error("START: YYYY-MM-DD, not " + text);
  return std::chrono::year{y} / std::chrono::month{m} / std::chrono::day{d};
}

}  // namespace

int main(int argc, char** argv) try {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s MAP LONE.sqlite FLEET.sqlite START [ROBOT] [DAYS] [TEST_FROM] [TEST_TO] [ZONE]\n",
                 argv[0]);
    return 2;
  }
  const auto arg = [&](int i, const char* fallback) { return std::string(argc > i ? argv[i] : fallback); };
  auto map = map::load_map(argv[1]);
  if (!map) throw std::runtime_error(map.error().message);
  const std::string robot = arg(5, "r1");
  const std::vector<int> days = day_list(arg(6, "3,7"));
  const int test_from = std::stoi(arg(7, "7")), test_to = std::stoi(arg(8, "10"));
  auto zone = TimeZone::named(arg(9, "Europe/London"));
  if (!zone) throw std::runtime_error(zone.error().message);
  const Time start = zone->at(parse_day(argv[4]), Duration{0});
  const std::vector<Traversal> lone = read_log(argv[2]), fleet = read_log(argv[3]);
  const struct {
    const char* name;
    const std::vector<Traversal>* log;
  } sources[] = {{"lone", &lone}, {"fleet", &fleet}};

  fmt::print("training: the first N days of each run's whole log; test: {}'s journeys of days {}-{} of each run\n",
             robot, test_from + 1, test_to);
  fmt::print("{:<12} {:<6} {:>3} {:>9} {:>9} {:>9} {:>8}\n", "test", "train", "N", "static", "fremen", "episode",
             "journeys");
  for (const auto& test : sources) {
    const std::vector<Traversal> journeys = of_robot(*test.log, robot);
    for (const auto& train : sources) {
      for (const int n : days) {
        plan::TravelEvaluationOptions o;
        o.models.episode.episode.zone = *zone;
        o.trainings = {{fmt::format("{}d", n), start, start + hours(24 * n)}};
        o.test = {"test", start + hours(24 * test_from), start + hours(24 * test_to)};
        auto e = plan::evaluate_travel(*map, *train.log, journeys, o);
        if (!e) throw std::runtime_error(e.error().message);
        std::vector<double> mean_abs;
        for (const plan::TravelErrorRow& r : e->rows)
          if (r.protocol == "offline" && r.estimate == "route") mean_abs.push_back(r.errors.mean_abs);
        fmt::print("{:<12} {:<6} {:>3} {:>9.3f} {:>9.3f} {:>9.3f} {:>8}\n", fmt::format("{} {}", test.name, robot),
                   train.name, n, mean_abs.at(0), mean_abs.at(1), mean_abs.at(2), e->journeys);
      }
    }
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "bench_fleet_learning: %s\n", e.what());
  return 2;
}
