// A small arithmetic expression language for analytic source fields (--function):
//   numbers, variables, + - * / ^ (right-associative), unary minus, parentheses,
//   functions sin cos tan exp log sqrt abs atan, the constant pi.
// Example: "1e5 + 2e3*x - 50*sin(pi*y/0.1)".
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace tfmb::loads {

class Expression {
 public:
  // Parses `text`; throws std::invalid_argument naming the position of a syntax error or an
  // unknown variable (allowed names in `variables`).
  Expression(const std::string& text, const std::vector<std::string>& variables);
  ~Expression();
  Expression(Expression&&) noexcept;
  Expression& operator=(Expression&&) noexcept;

  // Values in the order of `variables` given to the constructor.
  double operator()(const std::vector<double>& values) const;
  const std::string& text() const { return text_; }

  struct Node;

 private:
  std::string text_;
  std::unique_ptr<Node> root_;
};

// "name=expr; name=expr" -> map name -> expression text; throws std::invalid_argument on a
// missing '=' or a name not in `allowed`.
std::map<std::string, std::string> parse_assignments(const std::string& text,
                                                     const std::vector<std::string>& allowed);

}  // namespace tfmb::loads
