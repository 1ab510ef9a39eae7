#include "battery_memory.h"

#include <fmt/format.h>

#include "rondo/core/document.h"

namespace rondo::exec {
namespace {

constexpr std::size_t kN = BatteryEstimator::kRates;

Result<BatteryEstimator::Vector> vector_of(const Field& f) {
  RONDO_ASSIGN_OR_RETURN(const std::vector<Field> items, f.items());
  if (items.size() != kN) return f.error(fmt::format("must hold {} numbers, not {}", kN, items.size()));
  BatteryEstimator::Vector v{};
  for (std::size_t i = 0; i < kN; ++i) {
    RONDO_ASSIGN_OR_RETURN(v[i], items[i].as_number());
  }
  return v;
}

}  // namespace

std::string battery_meta_key(std::string_view robot) { return fmt::format("exec.battery.{}", robot); }

std::string encode_battery_state(const BatteryEstimator::State& s) {
  Json a = Json::array();
  for (const BatteryEstimator::Vector& row : s.a) a.push_back(Json(row));
  Json j;
  j["version"] = kBatteryStateVersion;
  j["n"] = s.n;
  j["a"] = std::move(a);
  j["b"] = Json(s.b);
  j["yy"] = s.yy;
  j["noise_ss"] = s.noise_ss;
  j["noise_weight"] = s.noise_weight;
  return j.dump();
}

Result<BatteryEstimator::State> decode_battery_state(std::string_view text) {
  RONDO_ASSIGN_OR_RETURN(const Document doc, Document::parse(text, DocumentFormat::kJson, "the battery estimate"));
  const Field root = doc.root();
  if (!root.is_object()) return root.error("must be an object");
  RONDO_ASSIGN_OR_RETURN(const Field version, root.required("version"));
  RONDO_ASSIGN_OR_RETURN(const std::int64_t v, version.as_int());
  if (v != kBatteryStateVersion)
    return version.error(fmt::format("version {} is not one this rondo reads ({})", v, kBatteryStateVersion));
  RONDO_RETURN_IF_ERROR(root.expect_keys({"version", "n", "a", "b", "yy", "noise_ss", "noise_weight"}));
  BatteryEstimator::State s;
  RONDO_ASSIGN_OR_RETURN(const Field n, root.required("n"));
  RONDO_ASSIGN_OR_RETURN(const std::int64_t count, n.as_int());
  if (count < 0) return n.error("must not be negative");
  s.n = static_cast<std::size_t>(count);
  RONDO_ASSIGN_OR_RETURN(const Field a, root.required("a"));
  RONDO_ASSIGN_OR_RETURN(const std::vector<Field> rows, a.items());
  if (rows.size() != kN) return a.error(fmt::format("must hold {} rows, not {}", kN, rows.size()));
  for (std::size_t i = 0; i < kN; ++i) {
    RONDO_ASSIGN_OR_RETURN(s.a[i], vector_of(rows[i]));
  }
  RONDO_ASSIGN_OR_RETURN(const Field b, root.required("b"));
  RONDO_ASSIGN_OR_RETURN(s.b, vector_of(b));
  for (auto [key, value] : {std::pair{"yy", &s.yy}, std::pair{"noise_ss", &s.noise_ss},
                            std::pair{"noise_weight", &s.noise_weight}}) {
    RONDO_ASSIGN_OR_RETURN(const Field f, root.required(key));
    RONDO_ASSIGN_OR_RETURN(*value, f.as_number());
  }
  return s;
}

}  // namespace rondo::exec
