#include "rondo/store/robot_state.h"

#include <SQLiteCpp/Statement.h>
#include "write_tx.h"

#include <fmt/format.h>

#include <cmath>

#include "sqlite_error.h"

namespace rondo::store {
namespace {

void bind_optional(SQLite::Statement& s, int index, const std::optional<double>& v) {
  if (v)
    s.bind(index, *v);
  else
    s.bind(index);
}

std::optional<double> optional_real(const SQLite::Column& c) {
  return c.isNull() ? std::nullopt : std::optional<double>(c.getDouble());
}

}  // namespace

Status save_robot_state(Store& store, const RobotState& st) {
  if (st.robot.empty() || st.node.empty())
    return Error::invalid(fmt::format("{}: a robot state needs a robot and a node", store.file().string()));
  if (st.battery && !(*st.battery >= 0 && *st.battery <= 1))
    return Error::invalid(fmt::format("{}: robot {}: battery {} is not in [0, 1]", store.file().string(), st.robot,
                                      *st.battery));
  for (const auto& v : {st.x, st.y, st.yaw})
    if (v && !std::isfinite(*v))
      return Error::invalid(fmt::format("{}: robot {}: a pose that is not finite", store.file().string(), st.robot));
  return guarded(store, fmt::format("saving the state of robot '{}'", st.robot), [&]() -> Status {
    SQLite::Statement put(connection(store),
                          "INSERT INTO robot_state (robot, node, x, y, yaw, battery, on_board, fault, updated_ms) "
                          "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?) ON CONFLICT (robot) DO UPDATE SET node = excluded.node, "
                          "x = excluded.x, y = excluded.y, yaw = excluded.yaw, battery = excluded.battery, "
                          "on_board = excluded.on_board, fault = excluded.fault, updated_ms = excluded.updated_ms");
    put.bind(1, st.robot);
    put.bind(2, st.node);
    bind_optional(put, 3, st.x);
    bind_optional(put, 4, st.y);
    bind_optional(put, 5, st.yaw);
    bind_optional(put, 6, st.battery);
    put.bind(7, st.on_board.dump());
    if (st.fault)
      put.bind(8, *st.fault);
    else
      put.bind(8);
    put.bind(9, to_db(st.updated));
    put.exec();
    return {};
  });
}

Result<std::optional<RobotState>> load_robot_state(const Store& store, std::string_view robot) {
  return guarded(store, fmt::format("reading the state of robot '{}'", robot),
                 [&]() -> Result<std::optional<RobotState>> {
                   SQLite::Statement q(connection(store),
                                       "SELECT robot, node, x, y, yaw, battery, on_board, fault, updated_ms "
                                       "FROM robot_state WHERE robot = ?");
                   q.bind(1, std::string(robot));
                   if (!q.executeStep()) return std::optional<RobotState>{};
                   RobotState st;
                   st.robot = q.getColumn(0).getString();
                   st.node = q.getColumn(1).getString();
                   st.x = optional_real(q.getColumn(2));
                   st.y = optional_real(q.getColumn(3));
                   st.yaw = optional_real(q.getColumn(4));
                   st.battery = optional_real(q.getColumn(5));
                   st.on_board = Json::parse(q.getColumn(6).getString(), nullptr, /*allow_exceptions=*/false);
                   if (st.on_board.is_discarded())
                     return Error::storage(fmt::format("{}: robot '{}': what is on board does not parse",
                                                       store.file().string(), st.robot));
                   if (!q.getColumn(7).isNull()) st.fault = q.getColumn(7).getString();
                   st.updated = time_from_db(q.getColumn(8).getInt64());
                   return std::optional<RobotState>(std::move(st));
                 });
}

Status set_meta(Store& store, std::string_view key, std::string_view value) {
  return guarded(store, fmt::format("setting '{}'", key), [&]() -> Status {
    SQLite::Statement put(connection(store),
                          "INSERT INTO meta (key, value) VALUES (?, ?) ON CONFLICT (key) DO UPDATE SET value = excluded.value");
    put.bind(1, std::string(key));
    put.bind(2, std::string(value));
    put.exec();
    return {};
  });
}

Result<std::optional<std::string>> get_meta(const Store& store, std::string_view key) {
  return guarded(store, fmt::format("reading '{}'", key), [&]() -> Result<std::optional<std::string>> {
    SQLite::Statement q(connection(store), "SELECT value FROM meta WHERE key = ?");
    q.bind(1, std::string(key));
    if (!q.executeStep()) return std::optional<std::string>{};
    return std::optional<std::string>(q.getColumn(0).getString());
  });
}

Status set_meta(Store& store, const std::vector<std::pair<std::string, std::string>>& entries) {
  return guarded(store, "setting the store's identity", [&]() -> Status {
    WriteTx tx(connection(store));
    SQLite::Statement put(
        connection(store),
        "INSERT INTO meta (key, value) VALUES (?, ?) ON CONFLICT (key) DO UPDATE SET value = excluded.value");
    for (const auto& [key, value] : entries) {
      put.bind(1, key);
      put.bind(2, value);
      put.exec();
      put.reset();
    }
    tx.commit();
    return {};
  });
}

Result<std::map<std::string, std::string>> read_meta(const Store& store) {
  return guarded(store, "reading the store's identity", [&]() -> Result<std::map<std::string, std::string>> {
    SQLite::Statement q(connection(store), "SELECT key, value FROM meta");
    std::map<std::string, std::string> out;
    while (q.executeStep()) out.emplace(q.getColumn(0).getString(), q.getColumn(1).getString());
    return out;
  });
}

}  // namespace rondo::store
