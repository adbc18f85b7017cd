#include "sparql/limits.hpp"

#include <algorithm>
#include <chrono>
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

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

[[noreturn]] void steps_exceeded(uint64_t limit) {
  throw Error(std::string(kCode),
              "SPARQL evaluation stopped after " + std::to_string(limit) +
                  " steps (the command's step limit; a step is a matched triple, a node reached "
                  "by a path, a solution passed on or 64 bytes a string function reads): the "
                  "queries do too much work on this data; make them more selective or raise "
                  "the limit");
}

}  // namespace

Budget::Budget(const Limits& limits, Clock clock) : limits_(limits), clock_(std::move(clock)) {
  start_ = now();
  if (limits_.steps != 0 && limits_.steps < next_check_) next_check_ = limits_.steps + 1;
}

double Budget::now() const {
  ++clock_reads_;
  return clock_ ? clock_() : steady_seconds();
}

double Budget::elapsed() const {
  return now() - start_;
}

void Budget::check() {
  next_check_ = steps_ + kCheckEvery;
  if (limits_.steps != 0 && steps_ <= limits_.steps && limits_.steps < next_check_)
    next_check_ = limits_.steps + 1;
  if (limits_.steps != 0 && steps_ > limits_.steps) steps_exceeded(limits_.steps);
  if (limits_.seconds > 0) {
    const double spent = elapsed();
    if (spent > limits_.seconds) time_exceeded();
  }
}

double Budget::before_bulk(Bulk kind, uint64_t steps) {
  steps_ += steps;
  if (limits_.steps != 0 && steps_ > limits_.steps) steps_exceeded(limits_.steps);
  const double started = now();
  const double spent = started - start_;
  if (spent > limits_.seconds) time_exceeded();
  const double estimate = static_cast<double>(steps) * rate_[static_cast<size_t>(kind)];
  if (spent + estimate > limits_.seconds) {
    const char* what = kind == Bulk::Regex  ? "REGEX"
                       : kind == Bulk::Sort ? "sort"
                                            : "string function";
    throw Error(std::string(kCode), "SPARQL evaluation stopped after " + seconds_text(spent) +
                                        " s and " + std::to_string(steps_) + " steps: the next " +
                                        what + " (" + std::to_string(steps) + " steps, about " +
                                        seconds_text(estimate) +
                                        " s) would end past the command's time budget of " +
                                        seconds_text(limits_.seconds) +
                                        " s; make the queries more selective or raise the limit");
  }
  return started;
}

void Budget::after_bulk(Bulk kind, uint64_t steps, double started) {
  const double finished = now();
  double& rate = rate_[static_cast<size_t>(kind)];
  rate = std::max(rate, (finished - started) / static_cast<double>(steps));
  next_check_ = steps_ + kCheckEvery;
  if (limits_.steps != 0 && limits_.steps < next_check_) next_check_ = limits_.steps + 1;
  if (finished - start_ > limits_.seconds) time_exceeded();
}

void Budget::time_exceeded() const {
  throw Error(std::string(kCode),
              "SPARQL evaluation stopped after " + seconds_text(limits_.seconds) +
                  " s (the command's time budget) and " + std::to_string(steps_) +
                  " steps: the queries do too much work on this data; make "
                  "them more selective or raise the limit");
}

void Budget::rows_exceeded(size_t n) const {
  throw Error(std::string(kCode), "SPARQL evaluation stopped at " + std::to_string(n) +
                                      " result rows (its row limit is " +
                                      std::to_string(limits_.rows) +
                                      "): make the query more selective or raise the limit");
}

}  // namespace mospec::sparql
