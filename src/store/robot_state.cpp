#include "rondo/store/robot_state.h"


#include <fmt/format.h>

#include <cmath>

#include "store_access.h"
#include "write_tx.h"

namespace rondo::store {
namespace {

constexpr std::string_view kPutMeta =
    "INSERT INTO meta (key, value) VALUES ($1, $2) ON CONFLICT (key) DO UPDATE SET value = excluded.value";

std::optional<double> optional_real(const db::Rows& row, int column) {
  return row.is_null(column) ? std::nullopt : std::optional<double>(row.real(column));
}

}  // namespace

Status save_robot_state(Store& store, const RobotState& st) {
  if (st.robot.empty() || st.node.empty())
    return Error::invalid(fmt::format("{}: a robot state needs a robot and a node", store.name()));
  if (st.battery && !(*st.battery >= 0 && *st.battery <= 1))
    return Error::invalid(fmt::format("{}: robot {}: battery {} is not in [0, 1]", store.name(), st.robot,
                                      *st.battery));
  for (const auto& v : {st.x, st.y, st.yaw})
    if (v && !std::isfinite(*v))
      return Error::invalid(fmt::format("{}: robot {}: a pose that is not finite", store.name(), st.robot));
  return guarded(store, fmt::format("saving the state of robot '{}'", st.robot), [&]() -> Status {
    connection(store).exec(
        "INSERT INTO robot_state (robot, node, x, y, yaw, battery, on_board, fault, updated_ms) "
        "VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9) ON CONFLICT (robot) DO UPDATE SET node = excluded.node, "
        "x = excluded.x, y = excluded.y, yaw = excluded.yaw, battery = excluded.battery, "
        "on_board = excluded.on_board, fault = excluded.fault, updated_ms = excluded.updated_ms",
        {st.robot, st.node, st.x, st.y, st.yaw, st.battery, st.on_board.dump(), st.fault, to_db(st.updated)});
    return {};
  });
}

Result<std::optional<RobotState>> load_robot_state(const Store& store, std::string_view robot) {
  return guarded(store, fmt::format("reading the state of robot '{}'", robot),
                 [&]() -> Result<std::optional<RobotState>> {
                   auto q = connection(store).query(
                       "SELECT robot, node, x, y, yaw, battery, on_board, fault, updated_ms "
                       "FROM robot_state WHERE robot = $1",
                       {robot});
                   if (!q->next()) return std::optional<RobotState>{};
                   RobotState st;
                   st.robot = q->text(0);
                   st.node = q->text(1);
                   st.x = optional_real(*q, 2);
                   st.y = optional_real(*q, 3);
                   st.yaw = optional_real(*q, 4);
                   st.battery = optional_real(*q, 5);
                   st.on_board = Json::parse(q->text(6), nullptr, /*allow_exceptions=*/false);
                   if (st.on_board.is_discarded())
                     return Error::storage(fmt::format("{}: robot '{}': what is on board does not parse",
                                                       store.name(), st.robot));
                   if (!q->is_null(7)) st.fault = q->text(7);
                   st.updated = time_from_db(q->int64(8));
                   return std::optional<RobotState>(std::move(st));
                 });
}

Status set_meta(Store& store, std::string_view key, std::string_view value) {
  return guarded(store, fmt::format("setting '{}'", key), [&]() -> Status {
    connection(store).exec(kPutMeta, {key, value});
    return {};
  });
}

Result<std::optional<std::string>> get_meta(const Store& store, std::string_view key) {
  return guarded(store, fmt::format("reading '{}'", key), [&]() -> Result<std::optional<std::string>> {
    auto q = connection(store).query("SELECT value FROM meta WHERE key = $1", {key});
    if (!q->next()) return std::optional<std::string>{};
    return std::optional<std::string>(q->text(0));
  });
}

Result<std::optional<std::string>> claim_meta(Store& store, std::string_view key, std::string_view value) {
  return guarded(store, fmt::format("claiming '{}'", key), [&]() -> Result<std::optional<std::string>> {
    db::Connection& db = connection(store);
    if (db.exec("INSERT INTO meta (key, value) VALUES ($1, $2) ON CONFLICT (key) DO NOTHING", {key, value}) == 1)
      return std::optional<std::string>{};
    return db::query_text(db, "SELECT value FROM meta WHERE key = $1", {key});
  });
}

Status set_meta(Store& store, const std::vector<std::pair<std::string, std::string>>& entries) {
  return guarded(store, "setting the store's identity", [&]() -> Status {
    WriteTx tx(connection(store));
    for (const auto& [key, value] : entries) connection(store).exec(kPutMeta, {key, value});
    tx.commit();
    return {};
  });
}

Result<std::map<std::string, std::string>> read_meta(const Store& store) {
  return guarded(store, "reading the store's identity", [&]() -> Result<std::map<std::string, std::string>> {
    auto q = connection(store).query("SELECT key, value FROM meta");
    std::map<std::string, std::string> out;
    while (q->next()) out.emplace(q->text(0), q->text(1));
    return out;
  });
}

}  // namespace rondo::store
