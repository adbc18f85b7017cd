// Bounds on the work of one SPARQL evaluation or one property-path
// evaluation, so that a hostile or careless query (a join of every triple with
// every other, `rdf:rest*/rdf:rest*` over a long list, nested `*` paths) ends
// with an error instead of running for hours.
//
// Work is counted in steps: one step per triple a pattern matches, per node a
// property path reaches, per solution a group passes on. Every kCheckEvery
// steps the budget also looks at a steady clock. Whichever limit is reached
// first throws mospec::Error with code "sparql-limit" naming the limit, its
// value and how far evaluation got.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

namespace mospec::sparql {

struct Limits {
  // Wall-clock budget of one evaluation (a query for one set of pre-bound
  // values, or one path from one node); <= 0: none.
  double seconds = 10;
  // Steps of one evaluation; 0: none. About a minute of work on a current
  // machine, so the time budget normally ends runaway queries first.
  uint64_t steps = uint64_t{1} << 32;
  // Result rows one SELECT may collect (before OFFSET/LIMIT when it has
  // ORDER BY); 0: none.
  size_t rows = 10'000'000;
};

// The running count of one evaluation against its Limits. Cheap to construct
// (reads the clock once) and to tick (an increment and a compare).
class Budget {
 public:
  static constexpr uint64_t kCheckEvery = 4096;

  explicit Budget(const Limits& limits = {});

  void tick(uint64_t n = 1) {
    steps_ += n;
    if (steps_ >= next_check_) check();
  }
  // Called with the number of rows collected so far.
  void rows(size_t n) const {
    if (limits_.rows != 0 && n > limits_.rows) rows_exceeded(n);
  }
  uint64_t steps() const { return steps_; }
  const Limits& limits() const { return limits_; }

 private:
  void check();
  [[noreturn]] void rows_exceeded(size_t n) const;

  Limits limits_;
  std::chrono::steady_clock::time_point start_;
  uint64_t steps_ = 0;
  uint64_t next_check_ = kCheckEvery;
};

}  // namespace mospec::sparql
