#include "rondo/exec/building.h"

#include <utility>

#include "door_models.h"
#include "found_blocked.h"
#include "loading_times.h"
#include "rondo/learn/weekly_memory.h"
#include "scheduling.h"
#include "spec_tasks.h"

namespace rondo::exec {

Building::Building(Clock& clock_in, const map::TopoMap& map_in, store::Store& store_in, const TimeZone& zone_in,
                   const ExecutorOptions& options_in, std::shared_ptr<plan::LearnedEdgeModels> models_in)
    : clock(clock_in),
      options(options_in),
      map(map_in),
      store(store_in),
      zone(zone_in),
      models(models_in ? std::move(models_in)
                       : std::make_shared<plan::LearnedEdgeModels>(map_in, nullptr, plan::DistancePriorOptions{},
                                                                   options.online_model
                                                                       ? plan::LearnedEdgeModels::Reading::kOnline
                                                                       : plan::LearnedEdgeModels::Reading::kOffline)),
      planner(map_in, models, planner_options(options.slot_width)),
      travel(map_in, models, planner, options.slot_width, options.route_threshold),
      offline_models(std::make_shared<plan::LearnedEdgeModels>(map_in, nullptr)),
      offline_planner(map_in, offline_models, planner_options(options.slot_width)),
      offline_travel(map_in, offline_models, offline_planner, options.slot_width, options.route_threshold),
      book(store_in, clock_in),
      loading(std::make_unique<LoadingTimes>()),
      found_blocked(std::make_unique<FoundBlocked>()),
      door_models(std::make_unique<DoorModels>(zone)),
      spec_tasks(std::make_unique<SpecTasks>(map_in, models, options.slot_width)) {}

Building::~Building() = default;

}  // namespace rondo::exec
