// Bounds on the SPARQL work of one command, so that a hostile or careless
// query (a join of every triple with every other, `rdf:rest*/rdf:rest*` over a
// long list, nested `*` paths, REGEX over megabytes for every focus node) ends
// with an error instead of running for hours.
//
// One Budget is shared by every evaluation of a command (`mospec validate`:
// every SPARQL constraint and every sh:path, for every shape and focus node),
// because a per-evaluation budget multiplied by thousands of focus nodes bounds
// nothing.
//
// Work is counted in steps: one step per triple a pattern matches, per node a
// property path reaches, per solution a group passes on, per comparison a sort
// makes, and one per kBytesPerStep bytes a string function or REGEX reads. The
// budget looks at its clock whenever kCheckEvery steps have been charged since
// the last look, and before a bulk operation (a REGEX, a sort) charged
// kCheckEvery steps or more, whose duration it estimates from the slowest rate
// seen so far, refusing to start one that would end past the time budget: no
// single operation can overrun the budget by more than its estimate is off.
// Whichever limit is reached first throws mospec::Error with code
// "sparql-limit" naming the limit, its value and how far evaluation got.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace mospec::sparql {

struct Limits {
  // Wall-clock budget of one command (every evaluation sharing its Budget);
  // <= 0: none.
  double seconds = 60;
  // Steps of one command; 0: none. About a minute of work on a current
  // machine, so the time budget normally ends runaway queries first.
  uint64_t steps = uint64_t{1} << 32;
  // Result rows one SELECT may collect (before OFFSET/LIMIT when it has
  // ORDER BY), per evaluation; 0: none.
  size_t rows = 10'000'000;
};

// The running count of one command's SPARQL work against its Limits. Cheap to
// tick (an increment and a compare). Not thread-safe: one per thread.
class Budget {
 public:
  static constexpr uint64_t kCheckEvery = 4096;
  // Bytes a string function or REGEX reads per step. A step is about the cost
  // of matching one triple (~50-100 ns); RE2 scans 64 bytes in about that.
  static constexpr uint64_t kBytesPerStep = 64;

  // Bulk operations whose duration is estimated before they start.
  enum class Bulk : uint8_t { Regex, Sort, String };

  // Seconds since an arbitrary origin; a test seam (the default reads
  // std::chrono::steady_clock).
  using Clock = std::function<double()>;

  explicit Budget(const Limits& limits = {}, Clock clock = {});

  void tick(uint64_t n = 1) {
    steps_ += n;
    if (steps_ >= next_check_) check();
  }
  // Charges `n` bytes a string function is about to read. Past kCheckEvery
  // steps, like bulk(): refused when its estimate would end past the time
  // budget (and the next tick reads the clock again, right after it).
  void bytes(size_t n) {
    const uint64_t steps = 1 + n / kBytesPerStep;
    if (steps < kCheckEvery || limits_.seconds <= 0) {
      tick(steps);
      return;
    }
    before_bulk(Bulk::String, steps);
  }

  // Runs `op`, charged `steps` steps of kind `kind`. An operation of
  // kCheckEvery steps or more reads the clock first and throws "sparql-limit"
  // when its estimated duration would end past the time budget; afterwards its
  // measured duration updates the estimate.
  template <class F>
  auto bulk(Bulk kind, uint64_t steps, F&& op) {
    if (steps < kCheckEvery || limits_.seconds <= 0) {
      tick(steps);
      return op();
    }
    const double started = before_bulk(kind, steps);
    auto result = op();
    after_bulk(kind, steps, started);
    return result;
  }

  // Runs `search`, a REGEX over `bytes` bytes of text, as bulk(Bulk::Regex)
  // charged by those bytes; counts them in regex_bytes() once it starts.
  template <class F>
  bool regex(size_t bytes, F&& search) {
    return bulk(Bulk::Regex, 1 + bytes / kBytesPerStep, [&] {
      regex_bytes_ += bytes;
      return search();
    });
  }
  // Bytes of text the REGEXes charged to this budget were given: the work
  // done, whatever the steps charged for it estimate (tests model a clock on it).
  uint64_t regex_bytes() const { return regex_bytes_; }

  // Called with the number of rows collected so far by one evaluation.
  void rows(size_t n) const {
    if (limits_.rows != 0 && n > limits_.rows) rows_exceeded(n);
  }
  uint64_t steps() const { return steps_; }
  const Limits& limits() const { return limits_; }
  // Seconds since the budget was made (reads the clock).
  double elapsed() const;
  // Clock reads so far (for tests).
  uint64_t clock_reads() const { return clock_reads_; }
  // The estimated seconds per step of a bulk operation of that kind: the
  // slowest rate measured so far, at least the default (kRegexSecondsPerStep,
  // kSortSecondsPerStep; string functions keep kStringSecondsPerStep).
  double seconds_per_step(Bulk kind) const { return rate_[static_cast<size_t>(kind)]; }

  // Conservative defaults: RE2's DFA scans about 1 ns per byte, its NFA
  // fallback several times that; a sort comparison of decoded values ~100 ns.
  static constexpr double kRegexSecondsPerStep = 4e-9 * kBytesPerStep;
  static constexpr double kSortSecondsPerStep = 2e-7;
  // Copying, case mapping, comparing and searching run at a GB/s or more.
  static constexpr double kStringSecondsPerStep = 2e-9 * kBytesPerStep;

 private:
  void check();
  double now() const;
  double before_bulk(Bulk kind, uint64_t steps);
  void after_bulk(Bulk kind, uint64_t steps, double started);
  [[noreturn]] void time_exceeded() const;
  [[noreturn]] void rows_exceeded(size_t n) const;

  Limits limits_;
  Clock clock_;
  double start_ = 0;
  mutable uint64_t clock_reads_ = 0;
  uint64_t steps_ = 0;
  uint64_t regex_bytes_ = 0;
  uint64_t next_check_ = kCheckEvery;
  double rate_[3] = {kRegexSecondsPerStep, kSortSecondsPerStep, kStringSecondsPerStep};
};

}  // namespace mospec::sparql
