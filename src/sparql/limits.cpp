#include "sparql/limits.hpp"

#include <cstdio>

#include "support/diagnostics.hpp"

namespace mospec::sparql {

namespace {

constexpr std::string_view kCode = "sparql-limit";

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", s);
  return buf;
}

}  // namespace

Budget::Budget(const Limits& limits) : limits_(limits), start_(std::chrono::steady_clock::now()) {
  if (limits_.steps != 0 && limits_.steps < next_check_) next_check_ = limits_.steps + 1;
}

void Budget::check() {
  next_check_ = steps_ + kCheckEvery;
  if (limits_.steps != 0 && steps_ <= limits_.steps && limits_.steps < next_check_)
    next_check_ = limits_.steps + 1;
  if (limits_.steps != 0 && steps_ > limits_.steps) {
    throw Error(std::string(kCode),
                "SPARQL evaluation stopped after " + std::to_string(limits_.steps) +
                    " steps (its step limit; a step is a matched triple, a node reached by a "
                    "path or a solution passed on): the query does too much work on this data; "
                    "make it more selective or raise the limit");
  }
  if (limits_.seconds > 0) {
    const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - start_;
    if (spent.count() > limits_.seconds) {
      throw Error(std::string(kCode),
                  "SPARQL evaluation stopped after " + seconds_text(limits_.seconds) +
                      " s (its time budget) and " + std::to_string(steps_) +
                      " steps: the query does too much work on this data; make it more "
                      "selective or raise the limit");
    }
  }
}

void Budget::rows_exceeded(size_t n) const {
  throw Error(std::string(kCode), "SPARQL evaluation stopped at " + std::to_string(n) +
                                      " result rows (its row limit is " +
                                      std::to_string(limits_.rows) +
                                      "): make the query more selective or raise the limit");
}

}  // namespace mospec::sparql
