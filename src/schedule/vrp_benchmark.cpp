#include "rondo/schedule/vrp_benchmark.h"

#include <charconv>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "rondo/core/document.h"
#include "rondo/core/utf8.h"

namespace rondo::schedule {

namespace {

// Limits before work (docs/hardening.md): the file's size, the number of sites (the travel
// matrix grows with its square), and every number's size.
constexpr std::size_t kMaxVrpBytes = 16u << 20;
constexpr std::size_t kMaxSites = 2001;
constexpr double kMaxValue = 1e7;

struct Line {
  int number = 0;
  std::vector<std::string_view> tokens{};
};

std::vector<Line> split_lines(std::string_view text) {
  std::vector<Line> lines;
  int number = 0;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    std::string_view line = text.substr(at, end - at);
    ++number;
    Line out{.number = number};
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
      if (j > i) out.tokens.push_back(line.substr(i, j - i));
      i = j;
    }
    if (!out.tokens.empty()) lines.push_back(std::move(out));
    at = end + 1;
  }
  return lines;
}

struct Site {
  std::string id;
  double x = 0, y = 0, demand = 0, ready = 0, due = 0, service = 0, pickup = 0, delivery = 0;
  int line = 0;
};

class VrpReader {
 public:
  explicit VrpReader(std::string source) : source_(std::move(source)) {}

  Error error(int line, std::string_view what) const { return Error::invalid(fmt::format("{}:{}: {}", source_, line, what)); }

  Result<std::vector<double>> numbers(const Line& line, std::size_t count, std::string_view what) const {
    if (line.tokens.size() != count)
      return error(line.number, fmt::format("{}: expected {} numbers, found {}", what, count, line.tokens.size()));
    std::vector<double> out;
    for (std::string_view t : line.tokens) {
      double v = 0;
      auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
      if (ec != std::errc{} || ptr != t.data() + t.size() || !std::isfinite(v))
        return error(line.number, fmt::format("{}: '{}' is not a number", what, quote_for_message(t)));
      if (std::abs(v) > kMaxValue)
        return error(line.number, fmt::format("{}: {} is out of range (at most {:g})", what, quote_for_message(t), kMaxValue));
      out.push_back(v);
    }
    return out;
  }

  Result<std::int64_t> whole(const Line& line, double v, std::string_view what, double low) const {
    if (v != std::floor(v) || v < low)
      return error(line.number, fmt::format("{}: expected a whole number of at least {:g}, found {:g}", what, low, v));
    return static_cast<std::int64_t>(v);
  }

  Result<Site> site(const Line& line, std::size_t count) const {
    auto v = numbers(line, count, count == 7 ? "customer row" : "task row");
    if (!v) return v.error();
    Site s{.id = std::string(line.tokens[0]), .x = (*v)[1], .y = (*v)[2], .demand = (*v)[3], .ready = (*v)[4],
           .due = (*v)[5], .service = (*v)[6], .line = line.number};
    if (count == 9) {
      s.pickup = (*v)[7];
      s.delivery = (*v)[8];
    }
    if (auto id = whole(line, (*v)[0], "id", 0); !id) return id.error();
    if (s.due < s.ready) return error(line.number, fmt::format("customer {}: due time {:g} before ready time {:g}", s.id, s.due, s.ready));
    if (s.service < 0) return error(line.number, fmt::format("customer {}: negative service time", s.id));
    return s;
  }

 private:
  std::string source_;
};

Time at(double units) { return Time{} + Duration{std::llround(units * static_cast<double>(kVrpUnit.count()))}; }

Result<FleetProblem> build(const VrpReader& reader, const std::vector<Site>& sites, std::int64_t vehicles,
                           std::int64_t capacity, double speed) {
  const std::size_t n = sites.size();
  FleetProblem p;
  p.objective = FleetObjective::kVehiclesThenDistance;
  p.costs.drop_seconds = 1e9;
  p.distance.resize(n * n);
  std::vector<Duration> travel(n * n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      const double d = std::hypot(sites[a].x - sites[b].x, sites[a].y - sites[b].y);
      p.distance[a * n + b] = d;
      travel[a * n + b] = Duration{static_cast<std::int64_t>(std::ceil(d * static_cast<double>(kVrpUnit.count())))};
    }
  p.travel = std::make_shared<MatrixTravel>(MatrixTravel::create(n, std::move(travel)).value());
  const Site& depot = sites.front();
  for (std::int64_t k = 0; k < vehicles; ++k)
    p.robots.push_back({.name = fmt::format("vehicle {}", k + 1), .location = 0, .free_from = at(depot.ready),
                        .end = ReturnTo{0, at(depot.due)}, .capacity = capacity, .speed_factor = speed});
  for (std::size_t k = 1; k < n; ++k) {
    const Site& s = sites[k];
    FleetTask f;
    f.task = {.id = s.id, .release = at(s.ready), .deadline = at(s.due), .deadline_on = DeadlineOn::kStart,
              .duration = at(s.service) - Time{}, .start_location = k, .end_location = k};
    if (auto d = reader.whole(Line{.number = s.line}, std::abs(s.demand), "demand", 0); !d) return d.error();
    f.demand = static_cast<std::int64_t>(s.demand);
    p.tasks.push_back(std::move(f));
  }
  return p;
}

Result<std::string> read(const std::filesystem::path& file) { return read_text_file(file, kMaxVrpBytes); }

}  // namespace

Result<FleetProblem> parse_vrptw(std::string_view text, const std::string& source) {
  const VrpReader reader(source);
  const std::vector<Line> lines = split_lines(text);
  std::size_t k = 0;
  auto find = [&](std::string_view word) {
    while (k < lines.size() && lines[k].tokens.front() != word) ++k;
    return k < lines.size();
  };
  const int last = lines.empty() ? 1 : lines.back().number;
  if (!find("VEHICLE")) return reader.error(last, "no VEHICLE section");
  if (++k >= lines.size() || lines[k].tokens.front() != "NUMBER")
    return reader.error(k < lines.size() ? lines[k].number : last, "VEHICLE: expected the header 'NUMBER CAPACITY'");
  if (++k >= lines.size()) return reader.error(last, "VEHICLE: missing the vehicles' number and capacity");
  auto fleet = reader.numbers(lines[k], 2, "VEHICLE");
  if (!fleet) return fleet.error();
  auto vehicles = reader.whole(lines[k], (*fleet)[0], "VEHICLE: NUMBER", 1);
  if (!vehicles) return vehicles.error();
  auto capacity = reader.whole(lines[k], (*fleet)[1], "VEHICLE: CAPACITY", 1);
  if (!capacity) return capacity.error();
  if (*vehicles > 10000) return reader.error(lines[k].number, "VEHICLE: NUMBER: at most 10000 vehicles");
  if (!find("CUSTOMER")) return reader.error(last, "no CUSTOMER section");
  if (++k >= lines.size() || lines[k].tokens.front() != "CUST")
    return reader.error(k < lines.size() ? lines[k].number : last, "CUSTOMER: expected the header 'CUST NO. XCOORD. ...'");
  std::vector<Site> sites;
  std::map<std::string, int> ids;
  for (++k; k < lines.size(); ++k) {
    if (sites.size() >= kMaxSites) return reader.error(lines[k].number, fmt::format("more than {} rows", kMaxSites));
    auto s = reader.site(lines[k], 7);
    if (!s) return s.error();
    if (s->demand < 0) return reader.error(s->line, fmt::format("customer {}: negative demand", s->id));
    if (!ids.emplace(s->id, s->line).second)
      return reader.error(s->line, fmt::format("customer {} is listed twice (first on line {})", s->id, ids[s->id]));
    sites.push_back(std::move(s).value());
  }
  if (sites.empty()) return reader.error(last, "CUSTOMER: no depot row");
  return build(reader, sites, *vehicles, *capacity, 1.0);
}

Result<FleetProblem> parse_pdptw(std::string_view text, const std::string& source) {
  const VrpReader reader(source);
  const std::vector<Line> lines = split_lines(text);
  if (lines.empty()) return reader.error(1, "empty file: expected 'vehicles capacity speed'");
  auto head = reader.numbers(lines[0], 3, "first line (vehicles capacity speed)");
  if (!head) return head.error();
  auto vehicles = reader.whole(lines[0], (*head)[0], "vehicles", 1);
  if (!vehicles) return vehicles.error();
  auto capacity = reader.whole(lines[0], (*head)[1], "capacity", 1);
  if (!capacity) return capacity.error();
  if (*vehicles > 10000) return reader.error(lines[0].number, "vehicles: at most 10000");
  // The third number, the format's speed, is not used: the published best known values take
  // travel time = distance, and several of the original files hold 0 there.
  if ((*head)[2] < 0) return reader.error(lines[0].number, "speed: must not be negative");
  std::vector<Site> sites;
  std::map<std::string, std::size_t> index;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    if (sites.size() >= kMaxSites) return reader.error(lines[k].number, fmt::format("more than {} rows", kMaxSites));
    auto s = reader.site(lines[k], 9);
    if (!s) return s.error();
    if (!index.emplace(s->id, sites.size()).second)
      return reader.error(s->line, fmt::format("task {} is listed twice", s->id));
    sites.push_back(std::move(s).value());
  }
  if (sites.empty()) return reader.error(lines[0].number, "no depot row");
  auto problem = build(reader, sites, *vehicles, *capacity, 1.0);
  if (!problem) return problem.error();
  // Pair the rows: a pickup names its delivery, the delivery names the pickup back.
  for (std::size_t k = 1; k < sites.size(); ++k) {
    const Site& s = sites[k];
    const bool pickup = s.pickup == 0 && s.delivery > 0;
    const bool delivery = s.pickup > 0 && s.delivery == 0;
    if (!pickup && !delivery)
      return reader.error(s.line, fmt::format("task {}: exactly one of pickup and delivery must name another task", s.id));
    const std::string other = fmt::format("{:g}", pickup ? s.delivery : s.pickup);
    const auto it = index.find(other);
    if (it == index.end() || it->second == 0)
      return reader.error(s.line, fmt::format("task {}: its {} {} does not exist", s.id, pickup ? "delivery" : "pickup", other));
    const Site& o = sites[it->second];
    if ((pickup ? o.pickup : o.delivery) != std::stod(s.id))
      return reader.error(s.line, fmt::format("task {}: task {} does not name it back", s.id, other));
    if (pickup ? s.demand < 0 : s.demand > 0)
      return reader.error(s.line, fmt::format("task {}: a {} with demand {:g}", s.id, pickup ? "pickup" : "delivery", s.demand));
    FleetTask& f = problem->tasks[k - 1];
    f.demand = 0;
    f.task.transfer = ItemTransfer{.job = pickup ? s.id : other,
                                   .action = pickup ? ItemAction::kPickup : ItemAction::kDrop,
                                   .load = static_cast<std::int64_t>(std::abs(s.demand))};
  }
  return problem;
}

Result<FleetProblem> load_vrptw(const std::filesystem::path& file) {
  auto text = read(file);
  if (!text) return text.error();
  return parse_vrptw(*text, printable_path(file));
}

Result<FleetProblem> load_pdptw(const std::filesystem::path& file) {
  auto text = read(file);
  if (!text) return text.error();
  return parse_pdptw(*text, printable_path(file));
}

std::string format_routes(const FleetProblem& problem, const FleetPlan& plan) {
  std::string out;
  int number = 0;
  for (const auto& route : plan.routes) {
    if (route.empty()) continue;
    out += fmt::format("Route {}:", ++number);
    for (const ScheduledTask& e : route) out += " " + problem.tasks[e.task].task.id;
    out += "\n";
  }
  return out;
}

}  // namespace rondo::schedule
