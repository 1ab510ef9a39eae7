#include "rondo/learn/model_json.h"

#include "json_util.h"
#include "rondo/learn/episode_model.h"
#include "rondo/learn/fremen.h"
#include "rondo/learn/static_model.h"

namespace rondo::learn {
namespace {

Result<std::string> type_of(const Json& j) {
  if (!j.is_object() || !j.contains("type") || !j["type"].is_string()) {
    return Error::invalid("model: expected an object with a string 'type'");
  }
  return j["type"].get<std::string>();
}

}  // namespace

Result<BinaryModelPtr> binary_model_from_json(const Json& j) {
  auto type = type_of(j);
  if (!type) return type.error();
  if (*type == "static") {
    auto mean = json_number(j, "mean");
    if (!mean) return mean.error();
    if (*mean < 0 || *mean > 1) return Error::invalid("model: a static probability must be in [0, 1]");
    return BinaryModelPtr(std::make_shared<const StaticBinaryModel>(*mean));
  }
  if (*type == "fremen") {
    auto c = FremenComponents::from_json(j);
    if (!c) return c.error();
    return BinaryModelPtr(std::make_shared<const FremenBinaryModel>(std::move(*c)));
  }
  if (*type == "episode") {
    if (!j.contains("priors") || !j.contains("edge")) return Error::invalid("model: episode needs 'priors' and 'edge'");
    auto priors = EpisodePriors::from_json(j["priors"]);
    if (!priors) return priors.error();
    auto edge = EpisodeEdgeModel::from_json(j["edge"], std::make_shared<const EpisodePriors>(std::move(*priors)));
    if (!edge) return edge.error();
    return BinaryModelPtr(
        std::make_shared<const EpisodeBinaryModel>(std::make_shared<const EpisodeEdgeModel>(std::move(*edge))));
  }
  return Error::invalid("model: unknown binary model type '" + *type + "'");
}

Result<DurationModelPtr> duration_model_from_json(const Json& j) {
  auto type = type_of(j);
  if (!type) return type.error();
  if (*type == "static" || *type == "fremen") {
    if (!j.contains("quantiles") && !j.contains("residual_quantiles")) {
      return Error::invalid("model: a duration model needs its quantile table");
    }
  }
  if (*type == "static") {
    auto mean = json_number(j, "mean");
    if (!mean) return mean.error();
    auto q = QuantileTable::from_json(j["quantiles"]);
    if (!q) return q.error();
    return DurationModelPtr(std::make_shared<const StaticDurationModel>(*mean, std::move(*q)));
  }
  if (*type == "fremen") {
    auto c = FremenComponents::from_json(j);
    if (!c) return c.error();
    auto q = QuantileTable::from_json(j["residual_quantiles"]);
    if (!q) return q.error();
    return DurationModelPtr(std::make_shared<const FremenDurationModel>(std::move(*c), std::move(*q)));
  }
  return Error::invalid("model: unknown duration model type '" + *type + "'");
}

}  // namespace rondo::learn
