#pragma once
// Errors and invariant checks shared by every part.
#include <sstream>
#include <stdexcept>
#include <string>

namespace rad {

/// Bad user input: the message says where, what was expected and what was found,
/// e.g. "scene.json: surfaces[3].polygon: expected at least 3 vertices, found 2".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Builds "<where>: expected <expected>, found <found>".
inline InputError inputError(const std::string& where, const std::string& expected,
                             const std::string& found) {
  return InputError(where + ": expected " + expected + ", found " + found);
}

/// A broken internal invariant (a bug, never bad input).
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

namespace detail {
template <class A, class B>
[[noreturn]] void checkFailed(const char* file, int line, const char* expr, const A& a,
                              const B& b) {
  std::ostringstream s;
  s << file << ":" << line << ": check failed: " << expr << " (" << a << " vs " << b << ")";
  throw InternalError(s.str());
}
}  // namespace detail

}  // namespace rad

/// Internal invariant checks that print both values; never use them for user input.
#define RAD_CHECK_OP(a, op, b)                                              \
  do {                                                                      \
    const auto& rad_a_ = (a);                                               \
    const auto& rad_b_ = (b);                                               \
    if (!(rad_a_ op rad_b_))                                                \
      ::rad::detail::checkFailed(__FILE__, __LINE__, #a " " #op " " #b, rad_a_, rad_b_); \
  } while (0)
#define RAD_CHECK_EQ(a, b) RAD_CHECK_OP(a, ==, b)
#define RAD_CHECK_LE(a, b) RAD_CHECK_OP(a, <=, b)
#define RAD_CHECK_LT(a, b) RAD_CHECK_OP(a, <, b)
#define RAD_CHECK(cond) RAD_CHECK_OP(static_cast<bool>(cond), ==, true)
