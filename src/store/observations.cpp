#include "rondo/store/observations.h"

#include <fmt/format.h>

#include <cmath>

#include "store_access.h"

namespace rondo::store {

Result<std::int64_t> add_observation(Store& store, const Observation& observation) {
  if (!std::isfinite(observation.value)) {
    return Error::invalid(fmt::format("{}: observation '{}' at '{}': value must be a finite number",
                                      store.name(), observation.what, observation.where));
  }
  return guarded(store, "adding an observation", [&]() -> Result<std::int64_t> {
    const auto id = db::query_int64(connection(store),
                                    "INSERT INTO observations (what, place, time_ms, value, note, robot) "
                                    "VALUES ($1, $2, $3, $4, $5, $6) RETURNING id",
                                    {observation.what, observation.where, to_db(observation.when), observation.value,
                                     observation.text, observation.robot});
    return id.value_or(0);
  });
}

Result<std::vector<Observation>> find_observations(const Store& store, const ObservationQuery& query) {
  return guarded(store, "reading observations", [&]() -> Result<std::vector<Observation>> {
    std::string sql = "SELECT what, place, time_ms, value, note, robot FROM observations WHERE TRUE";
    db::Params params;
    const auto where = [&](std::string_view condition, db::Param value) {
      params.push_back(std::move(value));
      sql += fmt::format(" AND {} ${}", condition, params.size());
    };
    if (query.what) where("what =", *query.what);
    if (query.where) where("place =", *query.where);
    if (query.from) where("time_ms >=", to_db(*query.from));
    if (query.until) where("time_ms <", to_db(*query.until));
    sql += " ORDER BY time_ms, id";
    auto select = connection(store).query(sql, params);
    std::vector<Observation> out;
    while (select->next()) {
      Observation o;
      o.what = select->text(0);
      o.where = select->text(1);
      o.when = time_from_db(select->int64(2));
      o.value = select->real(3);
      if (!select->is_null(4)) o.text = select->text(4);
      o.robot = select->text(5);
      out.push_back(std::move(o));
    }
    return out;
  });
}

}  // namespace rondo::store
