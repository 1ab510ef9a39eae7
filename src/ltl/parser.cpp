// Recursive descent over the tokens of lexer.h, one function per precedence level.
#include "rondo/ltl/parser.h"

#include <fmt/format.h>

#include <utility>
#include <vector>

#include "lexer.h"
#include "rondo/core/utf8.h"

namespace rondo::ltl {

namespace {

std::string describe(const Token& t) {
  switch (t.kind) {
    case TokenKind::kName: return fmt::format("node '{}'", quote_for_message(t.text));
    case TokenKind::kEnd: return "the end of the formula";
    default: return fmt::format("'{}'", t.text);
  }
}

// Why an operator outside the fragment is refused.
std::string outside_reason(const std::string& spelling) {
  if (spelling == "G")
    return "'G' (always) is outside the co-safe fragment: a task must be done after finitely many moves, and "
           "'always' never is; to keep away from a node until a goal, write '!node U goal'";
  if (spelling == "R") return "'R' (release) is outside the co-safe fragment: it can hold forever; use 'U'";
  if (spelling == "W") return "'W' (weak until) is outside the co-safe fragment: it can hold forever; use 'U'";
  if (spelling == "M") return "'M' (strong release) is not supported: write 'b U (a & b)' for 'a M b'";
  return "'<->' is outside the co-safe fragment: an equivalence negates both of its sides";
}

// Why '!' cannot apply to `f` (anything but a node or a constant).
std::string negation_reason(const Formula& f) {
  switch (f.op()) {
    case Op::kNotAt: return "'!' applies to a node only, here to a negated node: write the node itself";
    case Op::kNext: return "'!' applies to a node only, here to an 'X' formula: put the '!' on the node inside";
    case Op::kEventually:
      return "'!' applies to a node only, here to an 'F' formula: 'not eventually' is 'always not' (G), "
             "outside the co-safe fragment; to avoid a node until a goal, write '!node U goal'";
    case Op::kUntil:
      return "'!' applies to a node only, here to a 'U' formula: its negation can hold forever, outside the "
             "co-safe fragment";
    case Op::kAnd: return "'!' applies to a node only, here to a '&' formula: push it inwards (!(a & b) is !a | !b)";
    default: return "'!' applies to a node only, here to a '|' formula: push it inwards (!(a | b) is !a & !b)";
  }
}

class Parser {
 public:
  Parser(std::string_view text, std::vector<Token> tokens, const ParseOptions& options)
      : text_(text), tokens_(std::move(tokens)), options_(options) {}

  Result<Formula> parse() {
    RONDO_ASSIGN_OR_RETURN(Formula f, implication());
    if (peek().kind != TokenKind::kEnd)
      return error(peek(), "expected an operator or the end of the formula, found " + describe(peek()));
    return f;
  }

 private:
  // Counts one level of nesting while alive; the parser refuses input nested deeper than the limit.
  struct Nesting {
    explicit Nesting(std::size_t& depth) : depth_(depth) { ++depth_; }
    ~Nesting() { --depth_; }
    Nesting(const Nesting&) = delete;
    Nesting& operator=(const Nesting&) = delete;
    std::size_t& depth_;
  };

  const Token& peek() const { return tokens_[next_]; }
  const Token& take() { return tokens_[next_++]; }
  Error error(const Token& at, const std::string& what) const { return syntax_error(text_, at.offset, what); }
  Status check_depth(const Token& at) const {
    if (depth_ > options_.max_depth)
      return error(at, fmt::format("the formula nests deeper than {} levels", options_.max_depth));
    return {};
  }

  // implication := disjunction [ '->' implication ]
  Result<Formula> implication() {
    RONDO_ASSIGN_OR_RETURN(Formula left, disjunction());
    if (peek().kind != TokenKind::kImplies) return left;
    const Token& arrow = take();
    if (left.op() != Op::kAt && left.op() != Op::kNotAt)
      return error(arrow, "the left side of '->' must be a node or a negated node: '->' negates its left side, and "
                          "the negation of this one is outside the co-safe fragment");
    Nesting nesting(depth_);
    RONDO_RETURN_IF_ERROR(check_depth(arrow));
    RONDO_ASSIGN_OR_RETURN(Formula right, implication());
    Formula negated = left.op() == Op::kAt ? Formula::not_at(left.node()) : Formula::at(left.node());
    return Formula::any_of({std::move(negated), std::move(right)});
  }

  // disjunction := conjunction { '|' conjunction }
  Result<Formula> disjunction() {
    std::vector<Formula> operands;
    do {
      RONDO_ASSIGN_OR_RETURN(Formula f, conjunction());
      operands.push_back(std::move(f));
    } while (peek().kind == TokenKind::kOr && (take(), true));
    return Formula::any_of(std::move(operands));
  }

  // conjunction := until { '&' until }
  Result<Formula> conjunction() {
    std::vector<Formula> operands;
    do {
      RONDO_ASSIGN_OR_RETURN(Formula f, until());
      operands.push_back(std::move(f));
    } while (peek().kind == TokenKind::kAnd && (take(), true));
    return Formula::all_of(std::move(operands));
  }

  // until := unary [ 'U' until ]
  Result<Formula> until() {
    RONDO_ASSIGN_OR_RETURN(Formula left, unary());
    if (peek().kind == TokenKind::kOutside) return error(peek(), outside_reason(peek().text));
    if (peek().kind != TokenKind::kUntil) return left;
    const Token& u = take();
    Nesting nesting(depth_);
    RONDO_RETURN_IF_ERROR(check_depth(u));
    RONDO_ASSIGN_OR_RETURN(Formula right, until());
    return Formula::until(std::move(left), std::move(right));
  }

  // unary := ('!' | 'X' | 'F') unary | primary
  Result<Formula> unary() {
    const Token& t = peek();
    if (t.kind != TokenKind::kNot && t.kind != TokenKind::kNext && t.kind != TokenKind::kEventually)
      return primary();
    take();
    Nesting nesting(depth_);
    RONDO_RETURN_IF_ERROR(check_depth(t));
    RONDO_ASSIGN_OR_RETURN(Formula operand, unary());
    if (t.kind == TokenKind::kNext) return Formula::next(std::move(operand));
    if (t.kind == TokenKind::kEventually) return Formula::eventually(std::move(operand));
    switch (operand.op()) {
      case Op::kAt: return Formula::not_at(operand.node());
      case Op::kTrue: return Formula::falsity();
      case Op::kFalse: return Formula::truth();
      default: return error(t, negation_reason(operand));
    }
  }

  // primary := 'true' | 'false' | NAME | '(' implication ')'
  Result<Formula> primary() {
    const Token& t = take();
    switch (t.kind) {
      case TokenKind::kTrue: return Formula::truth();
      case TokenKind::kFalse: return Formula::falsity();
      case TokenKind::kName: return Formula::at(t.text);
      case TokenKind::kOutside: return error(t, outside_reason(t.text));
      case TokenKind::kOpen: break;
      default:
        return error(t, "expected a node, 'true', 'false', '(', '!', 'X' or 'F', found " + describe(t));
    }
    Nesting nesting(depth_);
    RONDO_RETURN_IF_ERROR(check_depth(t));
    RONDO_ASSIGN_OR_RETURN(Formula inner, implication());
    if (peek().kind != TokenKind::kClose)
      return error(peek(), fmt::format("expected ')' to close the '(' at position {}, found {}",
                                       character_position(text_, t.offset), describe(peek())));
    take();
    return inner;
  }

  std::string_view text_;
  std::vector<Token> tokens_;
  ParseOptions options_;
  std::size_t next_ = 0;
  std::size_t depth_ = 0;
};

}  // namespace

Result<Formula> parse_formula(std::string_view text, const ParseOptions& options) {
  if (text.size() > options.max_bytes)
    return Error::invalid(fmt::format("the formula is {} bytes long, more than the limit of {}", text.size(),
                                      options.max_bytes));
  if (auto bad = first_invalid_utf8(text))
    return syntax_error(text, *bad, "the formula is not valid UTF-8 here");
  RONDO_ASSIGN_OR_RETURN(std::vector<Token> tokens, tokenize(text));
  return Parser(text, std::move(tokens), options).parse();
}

}  // namespace rondo::ltl
