// The grammar of docs/commands.md:
//   [urgent | important | please] VERB-PHRASE [TIME WORDS]
// where the verb phrase is a delivery (deliver/bring/take/carry OBJECT from PLACE to PLACE; put
// OBJECT on PLACE on PLACE), a visit (check/inspect PLACE, patrol PLACE, come/go to PLACE,
// visit PLACE) or a cancellation (cancel the delivery of OBJECT, cancel the VERB of PLACE,
// cancel task ID).
#include <algorithm>
#include <array>
#include <cctype>
#include <functional>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "build.h"
#include "rondo/core/utf8.h"
#include "rondo/lang/command.h"
#include "rondo/lang/words.h"
#include "rondo/ltl/task_formula.h"
#include "timing.h"
#include "tokens.h"

namespace rondo::lang {
namespace {

using detail::Job;
using detail::text_of;
using detail::Timing;
using detail::Tokens;

constexpr int kUrgent = 10;
constexpr int kImportant = 5;
constexpr Duration kLoadTime = minutes(1);

struct VisitVerb {
  std::string_view word;
  std::string_view action;
  Duration duration;
  bool needs_to;  // "come to PLACE"
};
constexpr std::array<VisitVerb, 7> kVisits = {{{"check", "check", minutes(2), false},
                                               {"inspect", "check", minutes(2), false},
                                               {"patrol", "patrol", minutes(2), false},
                                               {"visit", "visit", minutes(5), false},
                                               {"come", "visit", minutes(5), true},
                                               {"go", "visit", minutes(5), true},
                                               {"cancel", "", Duration{0}, false}}};
constexpr std::array<std::string_view, 5> kDeliveryVerbs = {"deliver", "bring", "take", "carry", "put"};

bool is_article(std::string_view w) {
  return w == "the" || w == "a" || w == "an";
}

std::vector<std::string> verb_words() {
  std::vector<std::string> out(kDeliveryVerbs.begin(), kDeliveryVerbs.end());
  for (const auto& v : kVisits) out.emplace_back(v.word);
  return out;
}

// An object as people describe it, lower case without a leading article: "red letter".
std::string object_of(const Tokens& t, std::size_t b, std::size_t e) {
  return normalise_object(text_of(t, b, e));
}

// One place of a list as it was said: "the emergency exits" in "check A-123 and the emergency exits".
struct SaidPlace {
  Place place;
  std::string text;
};

// The longest list of places read, and the most ways of reading it tried (a list of known names
// that contain "and" can be read in many ways; real ones take a handful). A group in the places
// file names more places at once.
constexpr std::size_t kMaxListPlaces = 40;
constexpr std::size_t kMaxListSteps = 2'000;

struct TwoPlaces {
  Place from;
  Place to;
  std::string from_text;
  std::string to_text;
};

class Parser {
 public:
  Parser(const CommandContext& ctx, Tokens tokens) : ctx_(ctx), t_(std::move(tokens)) {}

  Result<Command> run() {
    std::size_t i = 0;
    std::optional<int> priority;
    while (i < t_.size() && (t_[i].word == "please" || t_[i].word == "urgent" || t_[i].word == "important")) {
      if (t_[i].word != "please") {
        if (priority) return Error::invalid("give one of 'urgent' and 'important'");
        priority = t_[i].word == "urgent" ? kUrgent : kImportant;
      }
      ++i;
    }
    if (i == t_.size()) return Error::invalid("the command has no verb: start with " + verb_list());
    verb_ = i;
    body_end_ = t_.size();
    for (std::size_t j = i + 1; j < t_.size(); ++j) {
      if (detail::starts_timing(t_, j)) {
        body_end_ = j;
        break;
      }
    }
    RONDO_ASSIGN_OR_RETURN(timing_, detail::parse_timing(t_, body_end_));
    if (timing_.priority && priority) return Error::invalid("give the priority once ('urgent' or 'with priority N')");
    priority_ = timing_.priority.value_or(priority.value_or(0));
    const std::string_view verb = t_[verb_].word;
    if (verb == "cancel") {
      if (priority || timing_.any()) return Error::invalid("a cancellation takes no priority and no time words");
      return cancel();
    }
    if (std::find(kDeliveryVerbs.begin(), kDeliveryVerbs.end(), verb) != kDeliveryVerbs.end()) return delivery();
    for (const auto& v : kVisits) {
      if (v.word == verb) return visit(v);
    }
    return Error::invalid(fmt::format("I do not understand '{}': a command starts with {} (nearest: {})",
                                      t_[verb_].text, verb_list(), fmt::join(nearest(verb, verb_words(), 2), ", ")));
  }

 private:
  static std::string verb_list() { return fmt::format("{}", fmt::join(verb_words(), ", ")); }

  Result<Place> place(std::size_t b, std::size_t e, bool suggest = true) const {
    if (b >= e) return Error::invalid(fmt::format("'{}' needs a place", text_of(t_, verb_, b)));
    return ctx_.places->resolve(text_of(t_, b, e), suggest);
  }

  // The places of [b, e): one place, or a list of them ("A-110 and A-111", "A-110, A-111 and the
  // kitchen"). A list may go on after a comma and at "and". Every way of cutting the words there
  // whose parts all resolve is a reading, except one in which some run of its parts, taken
  // together as said, is itself a known place: a known name is never cut ("Tom and Anna's
  // office", when the places file has it, is that place, not Tom and Anna's). The readings left
  // must name the same nodes; two that do not are an error showing both.
  Result<std::vector<SaidPlace>> place_list(std::size_t b, std::size_t e) const {
    using Span = std::pair<std::size_t, std::size_t>;
    std::vector<Span> cuts;  // {where a part ends, where the next one starts}
    for (std::size_t k = b + 1; k < e; ++k) {
      if (t_[k].word == "and") {
        if (k + 1 < e) cuts.emplace_back(k, k + 1);
      } else if (t_[k - 1].comma) {
        cuts.emplace_back(k, k);
      }
    }
    if (cuts.empty()) {
      RONDO_ASSIGN_OR_RETURN(auto one, place(b, e));
      return std::vector<SaidPlace>{{std::move(one), text_of(t_, b, e)}};
    }
    if (cuts.size() >= kMaxListPlaces) {
      return Error::invalid(fmt::format("a list of more than {} places is too long: name a group of them in the "
                                        "places file",
                                        kMaxListPlaces));
    }
    std::map<Span, std::optional<Place>> resolved;
    // A run of words across a comma is one place only when that place's own name holds a comma:
    // otherwise the comma ends a part of the list ("meeting room, table in A-111" read, without its
    // comma, as the known "meeting room table in A-111", and the meeting room was dropped).
    const auto across_a_comma = [&](std::size_t x, std::size_t y) {
      for (std::size_t k = x + 1; k < y; ++k)
        if (t_[k - 1].comma) return true;
      return false;
    };
    const auto lookup = [&](std::size_t x, std::size_t y) -> const std::optional<Place>& {
      auto [it, fresh] = resolved.try_emplace(Span{x, y});
      if (fresh) {
        auto p = place(x, y, false);
        if (p && (!across_a_comma(x, y) || p->name.find(',') != std::string::npos)) it->second = std::move(*p);
      }
      return it->second;
    };
    std::vector<std::vector<Span>> readings;
    std::vector<Span> parts;
    std::size_t steps = 0;
    const std::function<void(std::size_t)> extend = [&](std::size_t from) {
      if (++steps > kMaxListSteps) return;
      if (lookup(from, e)) {
        parts.emplace_back(from, e);
        readings.push_back(parts);
        parts.pop_back();
      }
      for (const auto& [end, next] : cuts) {
        if (end <= from || !lookup(from, end)) continue;
        parts.emplace_back(from, end);
        extend(next);
        parts.pop_back();
      }
    };
    extend(b);
    if (steps > kMaxListSteps) {
      return Error::invalid(
          fmt::format("'{}' can be read as too many different lists of places: name fewer at once", text_of(t_, b, e)));
    }
    const auto cuts_a_known_name = [&](const std::vector<Span>& r) {
      for (std::size_t i = 0; i + 1 < r.size(); ++i)
        for (std::size_t j = i + 1; j < r.size(); ++j)
          if (lookup(r[i].first, r[j].second)) return true;
      return false;
    };
    std::erase_if(readings, cuts_a_known_name);
    if (readings.empty()) {
      // Cut everywhere, the first part that is not a place is the one to name (with the nearest).
      std::size_t from = b;
      for (const auto& [end, next] : cuts) {
        if (end <= from) continue;
        if (!lookup(from, end)) return place(from, end).error();
        from = next;
      }
      return place(from, e).error();
    }
    const auto nodes_of = [&](const std::vector<Span>& r) {
      std::vector<std::string> nodes;
      for (const Span& p : r) nodes.insert(nodes.end(), lookup(p.first, p.second)->nodes.begin(),
                                           lookup(p.first, p.second)->nodes.end());
      return nodes;
    };
    const auto said = [&](const std::vector<Span>& r) {
      std::vector<std::string> texts;
      for (const Span& p : r) texts.push_back("'" + text_of(t_, p.first, p.second) + "'");
      return fmt::format("{}", fmt::join(texts, " and "));
    };
    for (const auto& r : readings) {
      if (nodes_of(r) != nodes_of(readings.front())) {
        return Error::invalid(fmt::format("'{}' can be read two ways: {}, or {}", text_of(t_, b, e),
                                          said(readings.front()), said(r)));
      }
    }
    std::vector<SaidPlace> out;
    std::vector<std::string> seen;
    for (const Span& p : readings.front()) {
      const Place& where = *lookup(p.first, p.second);
      for (const auto& node : where.nodes) {
        if (std::find(seen.begin(), seen.end(), node) != seen.end()) {
          return Error::invalid(fmt::format("the command names the place '{}' twice", node));
        }
        seen.push_back(node);
      }
      out.push_back({where, text_of(t_, p.first, p.second)});
    }
    return out;
  }

  // Splits [b, e) at one of `separators` into two places that both resolve. Exactly one way of
  // splitting may work; none or two different ones are errors.
  Result<TwoPlaces> two_places(std::size_t b, std::size_t e, const std::vector<std::string_view>& separators,
                               std::string_view usage) const {
    std::vector<TwoPlaces> readings;
    // The phrase to blame: the failing side of a split whose other side resolved, else the left
    // side of the first split. It is resolved again, with suggestions, only if nothing works.
    std::optional<std::pair<std::size_t, std::size_t>> blame;
    bool blame_is_half = false;
    for (std::size_t k = b + 1; k + 1 < e; ++k) {
      if (std::find(separators.begin(), separators.end(), t_[k].word) == separators.end()) continue;
      auto left = place(b, k, false);
      auto right = place(k + 1, e, false);
      if (left && right) {
        readings.push_back({*left, *right, text_of(t_, b, k), text_of(t_, k + 1, e)});
        continue;
      }
      const bool half = left.ok() != right.ok();
      if (!blame || (half && !blame_is_half)) {
        blame = left ? std::pair{k + 1, e} : std::pair{b, k};
        blame_is_half = half;
      }
    }
    if (readings.empty()) {
      if (blame) return place(blame->first, blame->second).error();
      return Error::invalid(fmt::format("I do not understand '{}': say {}", text_of(t_, verb_, body_end_), usage));
    }
    for (const auto& r : readings) {
      if (r.from.nodes != readings.front().from.nodes || r.to.nodes != readings.front().to.nodes) {
        return Error::invalid(fmt::format("'{}' can be read two ways: from '{}' to '{}', or from '{}' to '{}'",
                                          text_of(t_, b, e), readings.front().from_text, readings.front().to_text,
                                          r.from_text, r.to_text));
      }
    }
    return readings.front();
  }

  Result<Command> delivery() {
    const bool put = t_[verb_].word == "put";
    const std::vector<std::string_view> ends =
        put ? std::vector<std::string_view>{"on", "at", "from"} : std::vector<std::string_view>{"from", "to"};
    std::size_t k = verb_ + 1;
    while (k < body_end_ && std::find(ends.begin(), ends.end(), t_[k].word) == ends.end()) ++k;
    const std::string usage = put ? "'put OBJECT on PLACE on PLACE'" : "'deliver OBJECT from PLACE to PLACE'";
    const std::string object = object_of(t_, verb_ + 1, k);
    if (object.empty()) return Error::invalid(fmt::format("'{}' needs an object: say {}", t_[verb_].text, usage));
    if (k == body_end_ || (!put && t_[k].word != "from")) {
      return Error::invalid(fmt::format("'{}' needs the place to pick '{}' up from: say {}",
                                        text_of(t_, verb_, body_end_), object, usage));
    }
    const std::vector<std::string_view> separators =
        put ? std::vector<std::string_view>{"on", "onto", "to", "into", "at"} : std::vector<std::string_view>{"to"};
    RONDO_ASSIGN_OR_RETURN(auto places, two_places(k + 1, body_end_, separators, usage));
    for (const auto* p : {&places.from, &places.to}) {
      if (p->nodes.size() != 1) {
        return Error::invalid(fmt::format("'{}' is {} places; a delivery goes from one place to one place",
                                          p == &places.from ? places.from_text : places.to_text, p->nodes.size()));
      }
    }
    if (places.from.nodes == places.to.nodes) {
      return Error::invalid(fmt::format("'{}' and '{}' are the same place", places.from_text, places.to_text));
    }
    if (timing_.recurring()) {
      return Error::invalid("a delivery cannot repeat ('every ...'): routines make single tasks, not delivery jobs");
    }
    const std::string tag = object_tag(object);
    const Duration each = timing_.duration.value_or(kLoadTime);
    Task pickup;
    pickup.id = "pickup-" + tag;
    pickup.activity = fmt::format("pick up the {} at {}", object, places.from_text);
    pickup.duration = each;
    pickup.priority = priority_;
    pickup.start_node = places.from.nodes.front();
    pickup.actions = {Action{"load", {{"object", object}}}};
    pickup.delivery = Delivery{tag, DeliveryRole::kPickup, object, object, 1};
    Task drop = pickup;
    drop.id = "drop-" + tag;
    drop.activity = fmt::format("drop the {} at {}", object, places.to_text);
    drop.start_node = places.to.nodes.front();
    drop.actions = {Action{"unload", {{"object", object}}}};
    drop.delivery->role = DeliveryRole::kDrop;
    drop.after = {pickup.id};
    RONDO_RETURN_IF_ERROR(detail::apply_one_off(timing_, ctx_, pickup));
    // Both halves share the window: the object is picked up and dropped inside it.
    RONDO_RETURN_IF_ERROR(detail::apply_one_off(timing_, ctx_, drop));
    if (pickup.window && drop.window && drop.window->width() < pickup.duration + drop.duration) {
      return Error::invalid(
          fmt::format("the window is too short for a pickup and a drop of {} each", format_duration(each)));
    }
    Command c;
    c.tasks = {std::move(pickup), std::move(drop)};
    return check(std::move(c));
  }

  std::string object_tag(const std::string& object) const { return slug(object) + "@" + detail::id_tag(ctx_); }

  // A node's name as a formula reads it: bare when it can be, else quoted (docs/ltl.md, grammar).
  static std::string formula_name(const std::string& node) {
    static const std::array<std::string_view, 9> kReserved = {"X", "F", "U", "G", "R", "W", "M", "true", "false"};
    const bool bare = !node.empty() && (std::isalpha(static_cast<unsigned char>(node[0])) || node[0] == '_') &&
                      std::all_of(node.begin(), node.end(),
                                  [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }) &&
                      std::find(kReserved.begin(), kReserved.end(), node) == kReserved.end();
    if (bare) return node;
    std::string q = "\"";
    for (char c : node) {
      if (c == '"' || c == '\\') q += '\\';
      q += c;
    }
    return q + "\"";
  }

  // The places of [b, e) joined by "or": any node of any of them.
  Result<std::string> alternatives(std::size_t b, std::size_t e) const {
    std::vector<std::string> names;
    std::size_t from = b;
    for (std::size_t k = b; k <= e; ++k) {
      if (k < e && t_[k].word != "or") continue;
      RONDO_ASSIGN_OR_RETURN(const auto list, place_list(from, k));
      for (const auto& said : list)
        for (const auto& node : said.place.nodes) names.push_back(formula_name(node));
      from = k + 1;
    }
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    if (names.size() == 1) return names.front();
    return "(" + fmt::format("{}", fmt::join(names, " | ")) + ")";
  }

  // The sentence forms of a task written as a formula (docs/commands.md, docs/ltl.md): "A then B
  // or C", "A and B in any order", "... without passing D" / "... avoiding D and E". Nothing when
  // [b, e) has none of their words.
  Result<std::optional<std::string>> spec_of(std::size_t b, std::size_t e) const {
    std::size_t body = e;
    std::optional<std::string> avoid;
    for (std::size_t k = b; k < e; ++k) {
      const bool without = t_[k].word == "without" && k + 1 < e && t_[k + 1].word == "passing";
      if (!without && t_[k].word != "avoiding") continue;
      std::vector<std::string> names;
      RONDO_ASSIGN_OR_RETURN(const auto list, place_list(k + (without ? 2 : 1), e));
      for (const auto& said : list)
        for (const auto& node : said.place.nodes) names.push_back("!" + formula_name(node));
      avoid = names.size() == 1 ? names.front() : "(" + fmt::format("{}", fmt::join(names, " & ")) + ")";
      body = k;
      break;
    }
    bool any_order = false;
    if (body >= b + 3 && t_[body - 3].word == "in" && t_[body - 2].word == "any" && t_[body - 1].word == "order") {
      any_order = true;
      body -= 3;
    }
    std::vector<std::pair<std::size_t, std::size_t>> steps;
    std::size_t from = b;
    bool has_or = false;
    for (std::size_t k = b; k <= body; ++k) {
      if (k < body && t_[k].word == "or") has_or = true;
      if (k < body && t_[k].word != "then") continue;
      steps.emplace_back(from, k);
      from = k + 1;
    }
    if (!avoid && !any_order && !has_or && steps.size() == 1) return std::optional<std::string>{};
    const auto reach = [&](const std::string& goal) { return avoid ? *avoid + " U " + goal : "F " + goal; };
    if (any_order) {
      if (steps.size() > 1) return Error::invalid("say either 'then' or 'in any order', not both");
      RONDO_ASSIGN_OR_RETURN(const auto list, place_list(b, body));
      std::vector<std::string> parts;
      for (const auto& said : list) {
        std::vector<std::string> names;
        for (const auto& node : said.place.nodes) names.push_back(formula_name(node));
        const std::string goal =
            names.size() == 1 ? names.front() : "(" + fmt::format("{}", fmt::join(names, " | ")) + ")";
        parts.push_back(avoid ? "(" + reach(goal) + ")" : reach(goal));
      }
      return std::optional<std::string>{fmt::format("{}", fmt::join(parts, " & "))};
    }
    // The last step first: reach(s1 & reach(s2 & ... reach(sn))).
    std::string formula;
    for (std::size_t i = steps.size(); i-- > 0;) {
      RONDO_ASSIGN_OR_RETURN(std::string goal, alternatives(steps[i].first, steps[i].second));
      formula = formula.empty() ? reach(goal) : reach("(" + goal + " & (" + formula + "))");
    }
    return std::optional<std::string>{formula};
  }

  Result<Command> visit(const VisitVerb& v) {
    std::size_t b = verb_ + 1;
    if (v.needs_to) {
      if (b >= body_end_ || t_[b].word != "to") {
        return Error::invalid(fmt::format("say '{} to PLACE'", t_[verb_].text));
      }
      ++b;
    }
    RONDO_ASSIGN_OR_RETURN(const std::optional<std::string> spec, spec_of(b, body_end_));
    if (spec) {
      if (auto ok = ltl::check_task_formula(*spec); !ok)
        return Error::invalid(fmt::format("'{}' means the formula {}, which is refused: {}", text_of(t_, b, body_end_),
                                          *spec, ok.error().message));
      // "spec": the routine's name ("check-spec"); its task has no start node but the formula.
      Job job{std::string(v.action), fmt::format("{} {}", t_[verb_].word, text_of(t_, b, body_end_)), "spec",
              v.duration};
      Command c;
      if (timing_.recurring()) {
        RONDO_ASSIGN_OR_RETURN(auto r, detail::make_routine(timing_, ctx_, job, priority_));
        r.task.start_node.clear();
        r.task.spec = *spec;
        c.routines.push_back(std::move(r));
        return check(std::move(c));
      }
      Task task;
      task.id = job.verb + "-spec@" + detail::id_tag(ctx_);
      task.activity = job.activity;
      task.duration = timing_.duration.value_or(job.duration);
      task.priority = priority_;
      task.spec = *spec;
      task.actions = {Action{job.verb, {}}};
      RONDO_RETURN_IF_ERROR(detail::apply_one_off(timing_, ctx_, task));
      c.tasks.push_back(std::move(task));
      return check(std::move(c));
    }
    // One task (or, repeated, one routine) per node of each place named.
    RONDO_ASSIGN_OR_RETURN(const auto list, place_list(b, body_end_));
    Command c;
    for (const auto& [where, said] : list) {
      for (const auto& node : where.nodes) {
        Job job{std::string(v.action),
                where.nodes.size() > 1 ? fmt::format("{} {} ({})", t_[verb_].word, said, node)
                                       : fmt::format("{} {}{}", t_[verb_].word, v.needs_to ? "to " : "", said),
                node, v.duration};
        if (timing_.recurring()) {
          RONDO_ASSIGN_OR_RETURN(auto r, detail::make_routine(timing_, ctx_, job, priority_));
          c.routines.push_back(std::move(r));
          continue;
        }
        Task task;
        task.id = job.verb + "-" + slug(node) + "@" + detail::id_tag(ctx_);
        task.activity = job.activity;
        task.duration = timing_.duration.value_or(job.duration);
        task.priority = priority_;
        task.start_node = node;
        task.actions = {Action{job.verb, {}}};
        RONDO_RETURN_IF_ERROR(detail::apply_one_off(timing_, ctx_, task));
        c.tasks.push_back(std::move(task));
      }
    }
    return check(std::move(c));
  }

  Result<Command> cancel() {
    std::size_t b = verb_ + 1;
    const std::size_t e = body_end_;
    const std::string usage =
        "say 'cancel the delivery of OBJECT', 'cancel the check of PLACE' (or patrol, visit) or 'cancel task ID'";
    if (b < e && t_[b].word == "task") {
      if (e - b != 2) return Error::invalid(fmt::format("'cancel task' needs one task id; {}", usage));
      return Command{{}, {}, Cancellation{Cancellation::What::kTask, {}, {}, {}, t_[b + 1].text}};
    }
    while (b < e && is_article(t_[b].word)) ++b;
    if (b < e && (t_[b].word == "delivery" || t_[b].word == "deliveries") && b + 1 < e && t_[b + 1].word == "of") {
      const std::string object = object_of(t_, b + 2, e);
      if (object.empty()) return Error::invalid(fmt::format("'cancel the delivery of' needs an object; {}", usage));
      return Command{{}, {}, Cancellation{Cancellation::What::kDelivery, object, {}, {}, {}}};
    }
    if (e > b + 1 && t_[e - 1].word == "delivery") {
      return Command{{}, {}, Cancellation{Cancellation::What::kDelivery, object_of(t_, b, e - 1), {}, {}, {}}};
    }
    if (b + 2 < e && t_[b + 1].word == "of") {
      for (const auto& v : kVisits) {
        if (v.word == t_[b].word && !v.action.empty()) {
          RONDO_ASSIGN_OR_RETURN(const auto list, place_list(b + 2, e));
          std::vector<std::string> nodes;
          for (const auto& said : list) nodes.insert(nodes.end(), said.place.nodes.begin(), said.place.nodes.end());
          return Command{{}, {}, Cancellation{Cancellation::What::kActivity, {}, std::string(v.action), nodes, {}}};
        }
      }
    }
    return Error::invalid(fmt::format("I do not understand '{}'; {}", text_of(t_, verb_, t_.size()), usage));
  }

  // Every value handed out passes core's checks, as a task file's would.
  static Result<Command> check(Command c) {
    if (auto ok = validate(c.tasks, "tasks"); !ok)
      return Error::internal("the command made bad tasks: " + ok.error().message);
    std::vector<std::string> names;
    for (const auto& r : c.routines) {
      if (std::find(names.begin(), names.end(), r.name) != names.end()) {
        return Error::invalid(fmt::format("the command names the place '{}' twice", r.task.start_node));
      }
      names.push_back(r.name);
    }
    return c;
  }

  const CommandContext& ctx_;
  Tokens t_;
  std::size_t verb_ = 0;
  std::size_t body_end_ = 0;
  Timing timing_;
  int priority_ = 0;
};

}  // namespace

Result<Command> parse_command(std::string_view sentence, const CommandContext& ctx) {
  if (ctx.places == nullptr) return Error::internal("parse_command: no places given");
  if (sentence.size() > kMaxSentence) {
    return Error::invalid(
        fmt::format("the command is {} bytes long; the most read is {}", sentence.size(), kMaxSentence));
  }
  // Every word may end up in a task file (an object, an id), which must be UTF-8 and plain text.
  if (auto at = first_invalid_utf8(sentence)) {
    return Error::invalid(fmt::format("the command is not UTF-8 text (byte {})", *at));
  }
  for (std::size_t i = 0; i < sentence.size(); ++i) {
    const auto c = static_cast<unsigned char>(sentence[i]);
    if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7F) {
      return Error::invalid(fmt::format("the command holds a control character (byte {})", i));
    }
  }
  auto tokens = detail::tokenize(sentence);
  if (tokens.empty()) return Error::invalid("the command is empty");
  return Parser(ctx, std::move(tokens)).run();
}

}  // namespace rondo::lang
