#include "expression.hpp"

#include <cctype>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tfmb::loads {

struct Expression::Node {
  enum class Kind { number, variable, unary_minus, add, subtract, multiply, divide, power, call };
  Kind kind = Kind::number;
  double value = 0.0;
  std::size_t variable = 0;
  std::string function;
  std::unique_ptr<Node> left, right;

  double evaluate(const std::vector<double>& values) const {
    switch (kind) {
      case Kind::number: return value;
      case Kind::variable: return values.at(variable);
      case Kind::unary_minus: return -left->evaluate(values);
      case Kind::add: return left->evaluate(values) + right->evaluate(values);
      case Kind::subtract: return left->evaluate(values) - right->evaluate(values);
      case Kind::multiply: return left->evaluate(values) * right->evaluate(values);
      case Kind::divide: return left->evaluate(values) / right->evaluate(values);
      case Kind::power: return std::pow(left->evaluate(values), right->evaluate(values));
      case Kind::call: {
        const double a = left->evaluate(values);
        if (function == "sin") return std::sin(a);
        if (function == "cos") return std::cos(a);
        if (function == "tan") return std::tan(a);
        if (function == "exp") return std::exp(a);
        if (function == "log") return std::log(a);
        if (function == "sqrt") return std::sqrt(a);
        if (function == "abs") return std::abs(a);
        return std::atan(a);
      }
    }
    return 0.0;
  }
};

namespace {

using Node = Expression::Node;

class Parser {
 public:
  Parser(const std::string& text, const std::vector<std::string>& variables)
      : text_(text), variables_(variables) {}

  std::unique_ptr<Node> parse() {
    auto node = sum();
    skip();
    if (at_ < text_.size()) fail("unexpected '" + std::string(1, text_[at_]) + "'");
    return node;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument("expression \"" + text_ + "\": " + what + " at character " +
                                std::to_string(at_ + 1));
  }
  void skip() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
  }
  bool accept(char c) {
    skip();
    if (at_ < text_.size() && text_[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }
  static std::unique_ptr<Node> binary(Node::Kind kind, std::unique_ptr<Node> a, std::unique_ptr<Node> b) {
    auto node = std::make_unique<Node>();
    node->kind = kind;
    node->left = std::move(a);
    node->right = std::move(b);
    return node;
  }
  std::unique_ptr<Node> sum() {
    auto node = product();
    for (;;) {
      if (accept('+')) node = binary(Node::Kind::add, std::move(node), product());
      else if (accept('-')) node = binary(Node::Kind::subtract, std::move(node), product());
      else return node;
    }
  }
  std::unique_ptr<Node> product() {
    auto node = unary();
    for (;;) {
      if (accept('*')) node = binary(Node::Kind::multiply, std::move(node), unary());
      else if (accept('/')) node = binary(Node::Kind::divide, std::move(node), unary());
      else return node;
    }
  }
  std::unique_ptr<Node> unary() {
    if (accept('-')) {
      auto node = std::make_unique<Node>();
      node->kind = Node::Kind::unary_minus;
      node->left = unary();
      return node;
    }
    if (accept('+')) return unary();
    return power();
  }
  std::unique_ptr<Node> power() {
    auto base = primary();
    if (accept('^')) return binary(Node::Kind::power, std::move(base), unary());
    return base;
  }
  std::unique_ptr<Node> primary() {
    skip();
    if (at_ >= text_.size()) fail("unexpected end");
    if (accept('(')) {
      auto node = sum();
      if (!accept(')')) fail("missing ')'");
      return node;
    }
    const char c = text_[at_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      std::size_t used = 0;
      auto node = std::make_unique<Node>();
      try {
        node->value = std::stod(text_.substr(at_), &used);
      } catch (const std::exception&) {
        fail("bad number");
      }
      at_ += used;
      return node;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      const std::size_t start = at_;
      while (at_ < text_.size() &&
             (std::isalnum(static_cast<unsigned char>(text_[at_])) || text_[at_] == '_')) {
        ++at_;
      }
      const std::string name = text_.substr(start, at_ - start);
      if (name == "pi") {
        auto node = std::make_unique<Node>();
        node->value = std::numbers::pi;
        return node;
      }
      static const std::vector<std::string> functions = {"sin", "cos", "tan", "exp", "log",
                                                         "sqrt", "abs", "atan"};
      for (const std::string& f : functions) {
        if (name == f) {
          if (!accept('(')) fail("'(' expected after " + name);
          auto node = std::make_unique<Node>();
          node->kind = Node::Kind::call;
          node->function = name;
          node->left = sum();
          if (!accept(')')) fail("missing ')'");
          return node;
        }
      }
      for (std::size_t v = 0; v < variables_.size(); ++v) {
        if (name == variables_[v]) {
          auto node = std::make_unique<Node>();
          node->kind = Node::Kind::variable;
          node->variable = v;
          return node;
        }
      }
      at_ = start;
      std::string allowed;
      for (const auto& v : variables_) allowed += (allowed.empty() ? "" : ", ") + v;
      fail("unknown name '" + name + "' (variables: " + allowed + ", pi)");
    }
    fail("unexpected '" + std::string(1, c) + "'");
  }

  const std::string& text_;
  const std::vector<std::string>& variables_;
  std::size_t at_ = 0;
};

}  // namespace

Expression::Expression(const std::string& text, const std::vector<std::string>& variables)
    : text_(text) {
  root_ = Parser(text_, variables).parse();
}
Expression::~Expression() = default;
Expression::Expression(Expression&&) noexcept = default;
Expression& Expression::operator=(Expression&&) noexcept = default;

double Expression::operator()(const std::vector<double>& values) const {
  return root_->evaluate(values);
}

std::map<std::string, std::string> parse_assignments(const std::string& text,
                                                     const std::vector<std::string>& allowed) {
  std::map<std::string, std::string> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find(';', start);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(start, end - start);
    start = end + 1;
    if (item.find_first_not_of(" \t") == std::string::npos) continue;
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos) {
      throw std::invalid_argument("'" + item + "': expected name=expression");
    }
    std::string name = item.substr(0, eq);
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    bool known = false;
    for (const auto& a : allowed) known = known || a == name;
    if (!known) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw std::invalid_argument("'" + name + "' is not a field here (fields: " + list + ")");
    }
    out[name] = item.substr(eq + 1);
  }
  return out;
}

}  // namespace tfmb::loads
