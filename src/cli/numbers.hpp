// Range checks for numeric command-line flags. CLI11's Range lets NaN through
// (every comparison with NaN is false) and says nothing about units; these
// validators refuse NaN, infinities and anything outside the documented range,
// naming the accepted range (the flag's name is prefixed by CLI11:
// "--duration: nan is not a finite number; expected (0, 86400] s").
#pragma once

#include <CLI/CLI.hpp>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "support/diagnostics.hpp"

namespace mospec::cli {

// Seeds are integers 0 … 2^53 everywhere (world files hold them as JSON
// numbers, exact up to 2^53).
inline constexpr std::uint64_t kMaxSeed = std::uint64_t{1} << 53;

// A finite number in [lo, hi], or (lo, hi] when `lo_open`; `unit` is appended
// to the range in messages ("s").
inline CLI::Validator finite_number(double lo, double hi, bool lo_open, const std::string& unit) {
  auto shortest = [](double x) {
    char buffer[32];
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
    return ec == std::errc() ? std::string(buffer, end) : exact_number(x);
  };
  const std::string range = std::string(lo_open ? "(" : "[") + shortest(lo) + ", " + shortest(hi) +
                            "]" + (unit.empty() ? "" : " " + unit);
  return CLI::Validator(
      [lo, hi, lo_open, range](std::string& text) -> std::string {
        errno = 0;
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size()) {
          return "'" + text + "' is not a number; expected " + range;
        }
        if (!std::isfinite(x) || errno == ERANGE) {
          return text + " is not a finite number; expected " + range;
        }
        if (x < lo || (lo_open && x == lo) || x > hi) {
          return text + " is outside the accepted range " + range;
        }
        return {};
      },
      "NUMBER in " + range);
}

// An unsigned integer in [lo, hi], written in decimal digits only (no sign,
// no exponent, no hexadecimal).
inline CLI::Validator integer_in(std::uint64_t lo, std::uint64_t hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        if (text.empty() || text.size() > 20 ||
            text.find_first_not_of("0123456789") != std::string::npos) {
          return "'" + text + "' is not a non-negative integer; expected " + range;
        }
        errno = 0;
        const unsigned long long x = std::strtoull(text.c_str(), nullptr, 10);
        if (errno == ERANGE || x < lo || x > hi) {
          return text + " is outside the accepted range " + range;
        }
        return {};
      },
      "INTEGER in " + range);
}

}  // namespace mospec::cli
