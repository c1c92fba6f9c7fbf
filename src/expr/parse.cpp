#include "gpfd/expr/parse.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <vector>

#include "gpfd/util/error.hpp"

namespace gpfd::expr {
namespace {

// Shared cursor over the text with line/column tracking and error reporting.
class Cursor {
 public:
  Cursor(std::string_view text, const SourcePlace& place) : text_(text), place_(place) {}

  void skipSpace() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool atEnd() {
    skipSpace();
    return pos_ >= text_.size();
  }
  char peek() {
    skipSpace();
    return pos_ < text_.size() ? text_[pos_] : '\0';
  }
  char peekAt(std::size_t offset) const {
    return pos_ + offset < text_.size() ? text_[pos_ + offset] : '\0';
  }
  std::size_t pos() const { return pos_; }
  void advance(std::size_t n = 1) { pos_ += n; }

  bool accept(char c) {
    if (peek() != c) return false;
    ++pos_;
    return true;
  }
  void expect(char c, std::string_view what) {
    if (!accept(c)) fail("expected " + std::string(what) + describeHere(), pos_);
  }

  std::string describeHere() {
    if (atEnd()) return " but the text ended";
    return std::string(" but found '") + text_[pos_] + "'";
  }

  [[noreturn]] void fail(const std::string& what, std::size_t at) const {
    int line = place_.line, column = 1;
    for (std::size_t i = 0; i < at && i < text_.size(); ++i) {
      if (text_[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw InputError(what, place_.name + ":" + std::to_string(line) + ":" + std::to_string(column));
  }

  std::string_view identifier() {
    skipSpace();
    const std::size_t start = pos_;
    while (pos_ < text_.size() &&
           (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) {
      ++pos_;
    }
    return text_.substr(start, pos_ - start);
  }

  // A number starting at the cursor (digits, '.', exponent); `negative` negates it.
  double number(bool negative, std::size_t errorAt) {
    skipSpace();
    double value = 0.0;
    const char* begin = text_.data() + pos_;
    const char* end = text_.data() + text_.size();
    auto [ptr, ec] = std::from_chars(begin, end, value, std::chars_format::general);
    if (ec == std::errc::result_out_of_range) fail("number out of range", errorAt);
    if (ec != std::errc() || ptr == begin) fail("malformed number", errorAt);
    pos_ += static_cast<std::size_t>(ptr - begin);
    if (pos_ < text_.size() &&
        (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) {
      fail("malformed number", errorAt);
    }
    return negative ? -value : value;
  }

  // A variable by name or as x[i], whose identifier `name` was just read at `at`.
  Node variable(std::string_view name, std::size_t at, const VariableNames& names) {
    // x[i] always means variable i, even when a variable is named x.
    if (name == "x" && peek() == '[') return indexedVariable(at, names);
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == name) return Node::variable(static_cast<int>(i));
    }
    if (opFromName(name)) {
      fail("operator '" + std::string(name) + "' used without arguments", at);
    }
    fail("unknown variable '" + std::string(name) + "'" + knownNames(names), at);
  }

 private:
  Node indexedVariable(std::size_t at, const VariableNames& names) {
    expect('[', "'['");
    skipSpace();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    if (start == pos_) fail("expected a variable index", start);
    long index = 0;
    std::from_chars(text_.data() + start, text_.data() + pos_, index);
    if (pos_ - start > 6 || index >= static_cast<long>(names.size())) {
      fail("variable index " + std::string(text_.substr(start, pos_ - start)) +
               " out of range (the problem has " + std::to_string(names.size()) + " variables)",
           at);
    }
    expect(']', "']'");
    return Node::variable(static_cast<int>(index));
  }

  static std::string knownNames(const VariableNames& names) {
    std::string list = " (variables:";
    for (const auto& n : names) list += " " + n;
    return list + ")";
  }

  std::string_view text_;
  SourcePlace place_;
  std::size_t pos_ = 0;
};

// A parsed subtree in prefix order with its depth (a leaf has depth 1).
struct Sub {
  Tree tree;
  int depth = 1;
};

// Builds trees within the depth and size limits, failing at the first node that crosses one, so
// that hostile input costs no more than the limits allow.
class Limits {
 public:
  Limits(Cursor& cursor, int maxDepth, int maxSize)
      : c_(cursor), maxDepth_(maxDepth), maxSize_(maxSize) {}

  // A leaf read at `at`.
  Sub leaf(Node node, std::size_t at) {
    count(at);
    return {Tree{node}, 1};
  }

  // op(children...), the operator read at `at`. Each child's nodes are copied once; a node is
  // copied once per level above it, so the work is at most size x depth.
  Sub apply(Op op, std::vector<Sub> children, std::size_t at) {
    count(at);
    Sub out{Tree{Node::function(op)}, 0};
    std::size_t size = 1;
    for (const auto& child : children) size += child.tree.size();
    out.tree.reserve(size);
    for (auto& child : children) {
      out.tree.insert(out.tree.end(), child.tree.begin(), child.tree.end());
      out.depth = std::max(out.depth, child.depth);
    }
    out.depth = checkDepth(out.depth + 1, at);
    return out;
  }

  // A left-associative chain t0 op1 t1 op2 t2 ...: its prefix form is op_k ... op1 t0 t1 ... tk,
  // built once at the end (no copying of the growing left tree at every operator).
  class Chain {
   public:
    Chain(Limits& limits, Sub first)
        : limits_(limits), first_(std::move(first)), depth_(first_.depth) {}
    void add(Op op, Sub operand, std::size_t at) {
      limits_.count(at);
      depth_ = limits_.checkDepth(std::max(depth_, operand.depth) + 1, at);
      size_ += 1 + operand.tree.size();
      ops_.push_back(op);
      rest_.push_back(std::move(operand));
    }
    Sub finish() {
      if (ops_.empty()) return std::move(first_);  // A lone operand: nothing allocated.
      Sub out{{}, depth_};
      out.tree.reserve(first_.tree.size() + size_);
      for (auto op = ops_.rbegin(); op != ops_.rend(); ++op)
        out.tree.push_back(Node::function(*op));
      out.tree.insert(out.tree.end(), first_.tree.begin(), first_.tree.end());
      for (const auto& operand : rest_) {
        out.tree.insert(out.tree.end(), operand.tree.begin(), operand.tree.end());
      }
      return out;
    }

   private:
    Limits& limits_;
    Sub first_;
    std::vector<Op> ops_;
    std::vector<Sub> rest_;
    std::size_t size_ = 0;  // Nodes of the operators and of rest_.
    int depth_ = 1;
  };

 private:
  void count(std::size_t at) {
    if (++nodes_ > maxSize_) {
      c_.fail("too large: more than the limit of " + std::to_string(maxSize_) + " nodes", at);
    }
  }
  int checkDepth(int depth, std::size_t at) {
    if (depth > maxDepth_) {
      c_.fail("too deep: depth exceeds the limit of " + std::to_string(maxDepth_), at);
    }
    return depth;
  }

  Cursor& c_;
  int maxDepth_;
  int maxSize_;
  int nodes_ = 0;
};

// Checks that nothing follows the expression and completes its subtree lengths.
Tree finish(Sub sub, Cursor& cursor) {
  if (!cursor.atEnd()) cursor.fail("unexpected text after the expression", cursor.pos());
  recomputeLengths(sub.tree);
  return std::move(sub.tree);
}

// Recursive-descent infix parser:
//   sum := product (('+' | '-') product)*      product := unary (('*' | '/') unary)*
//   unary := '-' unary | primary                primary := number | call | variable | '(' sum ')'
class InfixParser {
 public:
  InfixParser(Cursor& cursor, const VariableNames& names, int nestingLimit, Limits& limits)
      : c_(cursor), names_(names), nestingLimit_(nestingLimit), limits_(limits) {}

  Sub sum() {
    Limits::Chain chain(limits_, product());
    for (;;) {
      const std::size_t at = c_.pos();
      if (c_.accept('+')) {
        chain.add(Op::Add, product(), at);
      } else if (c_.peek() == '-') {
        c_.advance();
        chain.add(Op::Sub, product(), at);
      } else {
        return chain.finish();
      }
    }
  }

 private:
  Sub product() {
    Limits::Chain chain(limits_, unary());
    for (;;) {
      const std::size_t at = c_.pos();
      if (c_.accept('*')) {
        chain.add(Op::Mul, unary(), at);
      } else if (c_.accept('/')) {
        chain.add(Op::Div, unary(), at);
      } else {
        return chain.finish();
      }
    }
  }

  Sub unary() {
    const Nest nest(*this);
    if (c_.peek() == '-') {
      const std::size_t at = c_.pos();
      c_.advance();
      const char next = c_.peek();
      if (std::isdigit(static_cast<unsigned char>(next)) || next == '.') {
        return limits_.leaf(Node::constant(c_.number(true, at)), at);
      }
      std::vector<Sub> operand;
      operand.push_back(unary());
      return limits_.apply(Op::Neg, std::move(operand), at);
    }
    return primary();
  }

  Sub primary() {
    const char next = c_.peek();
    const std::size_t at = c_.pos();
    if (next == '\0')
      c_.fail("empty expression" + std::string(at > 0 ? " after operator" : ""), at);
    if (std::isdigit(static_cast<unsigned char>(next)) || next == '.') {
      return limits_.leaf(Node::constant(c_.number(false, at)), at);
    }
    if (c_.accept('(')) {
      Sub inner = sum();
      c_.expect(')', "')'");
      return inner;
    }
    if (std::isalpha(static_cast<unsigned char>(next)) || next == '_') {
      const std::string_view name = c_.identifier();
      if (c_.peek() == '(') return call(name, at);
      return limits_.leaf(c_.variable(name, at, names_), at);
    }
    c_.fail(std::string("unexpected '") + next + "'", at);
  }

  Sub call(std::string_view name, std::size_t at) {
    const auto op = opFromName(name);
    if (!op) c_.fail("unknown operator '" + std::string(name) + "'", at);
    c_.expect('(', "'('");
    std::vector<Sub> args;
    if (c_.peek() != ')') {
      do {
        args.push_back(sum());
      } while (c_.accept(','));
    }
    c_.expect(')', "')' or ','");
    checkArity(c_, *op, static_cast<int>(args.size()), at);
    return limits_.apply(*op, std::move(args), at);
  }

 public:
  static void checkArity(Cursor& c, Op op, int given, std::size_t at) {
    if (given != arity(op)) {
      c.fail("wrong arity: '" + std::string(info(op).name) + "' takes " +
                 std::to_string(arity(op)) + " argument" + (arity(op) == 1 ? "" : "s") + ", got " +
                 std::to_string(given),
             at);
    }
  }

 private:
  // Bounds the recursion so that hostile input cannot overflow the stack.
  struct Nest {
    explicit Nest(InfixParser& p) : parser(p) {
      if (++parser.nesting_ > parser.nestingLimit_) {
        parser.c_.fail(
            "too deep: nesting exceeds the limit of " + std::to_string(parser.nestingLimit_),
            parser.c_.pos());
      }
    }
    ~Nest() { --parser.nesting_; }
    InfixParser& parser;
  };

  Cursor& c_;
  const VariableNames& names_;
  int nestingLimit_;
  Limits& limits_;
  int nesting_ = 0;
};

class SexprParser {
 public:
  SexprParser(Cursor& cursor, const VariableNames& names, int nestingLimit, Limits& limits)
      : c_(cursor), names_(names), nestingLimit_(nestingLimit), limits_(limits) {}

  Sub expression(int nesting = 1) {
    const std::size_t at = c_.pos();
    if (nesting > nestingLimit_) {
      c_.fail("too deep: nesting exceeds the limit of " + std::to_string(nestingLimit_), at);
    }
    const char next = c_.peek();
    if (next == '\0') c_.fail("empty expression", at);
    if (c_.accept('(')) return list(nesting);
    if (next == ')') c_.fail("unexpected ')'", c_.pos());
    return atom();
  }

 private:
  Sub list(int nesting) {
    const std::size_t at = c_.pos();
    const std::string symbol = token();
    if (symbol.empty()) c_.fail("expected an operator after '('", at);
    const auto op = opFromName(symbol);
    if (!op) c_.fail("unknown operator '" + symbol + "'", at);
    std::vector<Sub> args;
    while (c_.peek() != ')' && c_.peek() != '\0') args.push_back(expression(nesting + 1));
    c_.expect(')', "')'");
    InfixParser::checkArity(c_, *op, static_cast<int>(args.size()), at);
    return limits_.apply(*op, std::move(args), at);
  }

  Sub atom() {
    const std::size_t at = c_.pos();
    const char first = c_.peek();
    const char second = c_.peekAt(1);
    const bool sign = first == '-' || first == '+';
    if (std::isdigit(static_cast<unsigned char>(first)) || first == '.' ||
        (sign && (std::isdigit(static_cast<unsigned char>(second)) || second == '.'))) {
      if (sign) c_.advance();
      return limits_.leaf(Node::constant(c_.number(first == '-', at)), at);
    }
    if (std::isalpha(static_cast<unsigned char>(first)) || first == '_') {
      const std::string_view name = c_.identifier();
      return limits_.leaf(c_.variable(name, at, names_), at);
    }
    c_.fail(std::string("unexpected '") + first + "'", at);
  }

  // An operator symbol or name: the run of characters up to whitespace or a parenthesis.
  std::string token() {
    c_.skipSpace();
    std::string out;
    for (char ch = c_.peekAt(0);
         ch != '\0' && ch != '(' && ch != ')' && !std::isspace(static_cast<unsigned char>(ch));
         ch = c_.peekAt(0)) {
      out += ch;
      c_.advance();
    }
    return out;
  }

  Cursor& c_;
  const VariableNames& names_;
  int nestingLimit_;
  Limits& limits_;
};

}  // namespace

Tree parseInfix(std::string_view text, const VariableNames& names, const SourcePlace& place,
                int maxDepth, int maxSize) {
  Cursor cursor(text, place);
  if (cursor.atEnd()) cursor.fail("empty expression", 0);
  Limits limits(cursor, maxDepth, maxSize);
  InfixParser parser(cursor, names, 2 * kMaxParseDepth, limits);
  return finish(parser.sum(), cursor);
}

Tree parseSexpr(std::string_view text, const VariableNames& names, const SourcePlace& place,
                int maxDepth, int maxSize) {
  Cursor cursor(text, place);
  if (cursor.atEnd()) cursor.fail("empty expression", 0);
  Limits limits(cursor, maxDepth, maxSize);
  SexprParser parser(cursor, names, kMaxParseDepth, limits);
  return finish(parser.expression(), cursor);
}

}  // namespace gpfd::expr
