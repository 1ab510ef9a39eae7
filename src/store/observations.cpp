#include "rondo/store/observations.h"

#include <SQLiteCpp/Statement.h>

#include <fmt/format.h>

#include <cmath>

#include "sqlite_error.h"

namespace rondo::store {

Result<std::int64_t> add_observation(Store& store, const Observation& observation) {
  if (!std::isfinite(observation.value)) {
    return Error::invalid(fmt::format("{}: observation '{}' at '{}': value must be a finite number",
                                      store.file().string(), observation.what, observation.where));
  }
  return guarded(store, "adding an observation", [&]() -> Result<std::int64_t> {
    SQLite::Database& db = connection(store);
    SQLite::Statement insert(db, "INSERT INTO observations (what, place, time_ms, value, note, robot) VALUES (?, ?, ?, ?, ?, ?)");
    insert.bind(1, observation.what);
    insert.bind(2, observation.where);
    insert.bind(3, to_db(observation.when));
    insert.bind(4, observation.value);
    if (observation.text) {
      insert.bind(5, *observation.text);
    } else {
      insert.bind(5);
    }
    insert.bind(6, observation.robot);
    insert.exec();
    return db.getLastInsertRowid();
  });
}

Result<std::vector<Observation>> find_observations(const Store& store, const ObservationQuery& query) {
  return guarded(store, "reading observations", [&]() -> Result<std::vector<Observation>> {
    std::string sql = "SELECT what, place, time_ms, value, note, robot FROM observations WHERE 1";
    if (query.what) sql += " AND what = :what";
    if (query.where) sql += " AND place = :place";
    if (query.from) sql += " AND time_ms >= :from";
    if (query.until) sql += " AND time_ms < :until";
    sql += " ORDER BY time_ms, id";
    SQLite::Statement select(connection(store), sql);
    if (query.what) select.bind(":what", *query.what);
    if (query.where) select.bind(":place", *query.where);
    if (query.from) select.bind(":from", to_db(*query.from));
    if (query.until) select.bind(":until", to_db(*query.until));
    std::vector<Observation> out;
    while (select.executeStep()) {
      Observation o;
      o.what = select.getColumn(0).getString();
      o.where = select.getColumn(1).getString();
      o.when = time_from_db(select.getColumn(2).getInt64());
      o.value = select.getColumn(3).getDouble();
      if (!select.isColumnNull(4)) o.text = select.getColumn(4).getString();
      o.robot = select.getColumn(5).getString();
      out.push_back(std::move(o));
    }
    return out;
  });
}

}  // namespace rondo::store
