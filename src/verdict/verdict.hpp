// What a run did, in a few lines: `mospec run` ends every simulated run with
// a verdict on the console and in the summary ("verdict", docs/simulation.md):
// the motion timeline (when each motion started and ended, and which of its
// guards ended it), the events, each constraint's final error and whether it
// holds, the peak torque ratio per arm, limit breaches, non-finite commands,
// degraded solves, and contact lost while a force was commanded.
//
// The plan is read from the IR before the run (which log columns the verdict
// needs, which it watches tick by tick: sim::RunOptions::watch and ::pushing);
// the verdict reads only the log's columns and sim::RunResult, so an
// interpreted and a generated run of one program get the same verdict.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "ir/ir.hpp"
#include "robot/interface.hpp"
#include "sim/run.hpp"

namespace mospec::verdict {

// A number as the console shows it: 4 significant digits.
std::string console_number(double x);

// What the verdict reads, by controller log column (an index into
// ir::Program::log, i.e. Controller::log_columns(); RunResult::columns is
// shifted by one for "t").
struct VerdictPlan {
  struct Guard {
    std::string constraint;  // the constraint's IRI
    std::string name;        // its log name ("cstr-time-sc0a-timeout")
    std::size_t satisfied = 0;
    bool timeout = false;  // a greater-than on the clock's time
  };
  // A constraint the motion enforces (ir::Step::goals): judged when the
  // motion ends (its `.ended` event; at the run's end while it runs),
  // against its tolerance, and watched every tick it runs.
  struct Goal {
    std::string constraint, name, relation;
    std::string unit;  // the quantity's (QUDT local name)
    runtime::ConstraintSpec spec;
    std::string tolerance_source;  // "stated", "default" or "none"
    bool is_while = false;         // listed in the motion's `while`
    bool acted_on = false;         // a controller whose output reaches a solver reads its error
    std::size_t satisfied = 0;
    std::ptrdiff_t value = -1, error = -1;
  };
  struct Motion {
    std::string iri, name;
    std::size_t running = 0, ended = 0;
    bool has_when = false;
    std::vector<Guard> whiles, untils;  // the checked per-conditions, the post-conditions
    std::vector<Goal> goals;
  };
  struct Constraint {
    std::string iri, name, relation;
    std::ptrdiff_t value = -1, error = -1;  // -1: not logged (an assignment has no error)
    std::size_t satisfied = 0;
    bool guard = false;  // a motion's `when` or `until`
    bool goal = false;   // a goal of some motion (Motion::goals), judged there
    std::string tolerance_source;
    // An equality without a tolerance (none stated, and no motion enforces
    // it, so none by default) holds only at an error of exactly 0: its final
    // error is reported, not judged.
    bool judged = true;
    double tolerance = 0.0;
  };
  struct Solver {
    std::string name;  // as its `.degraded` column names it
    std::size_t degraded = 0;
  };
  struct Arm {
    // The Cartesian forces on the end effector (the chain's last segment) and
    // the logged values they are made of; a force none of whose values is
    // logged cannot be observed.
    std::vector<std::string> forces;
    std::vector<std::size_t> columns;
    std::vector<std::string> unobserved;
  };
  std::vector<Motion> motions;
  std::vector<Constraint> constraints;
  std::vector<Solver> solvers;
  std::vector<Arm> arms;  // by the robot's arm index (ir::ArmSolver::port)
};

VerdictPlan plan_verdict(const ir::Program& program);

// Adds the columns the verdict watches to `options`, and the snapshots (a
// motion's goals when it ends) and held records (its goals while it runs) it
// reads, in plan order: per motion with goals, one snapshot; per goal, one
// held record.
void watch_for_verdict(const VerdictPlan& plan, sim::RunOptions& options);

struct Verdict {
  bool failed = false;           // exit status 1
  std::vector<std::string> why;  // one reason per failure ("a joint position left its limits")
  nlohmann::ordered_json json;   // the summary's "verdict"
  std::string text;              // the console's lines
};

Verdict judge(const VerdictPlan& plan, const sim::RunResult& run);

// Per arm solve of the run's controller: in how many ticks it lost constraint
// directions (its `.degraded` log column).
std::vector<std::pair<std::string, std::uint64_t>> degraded_solves(const sim::RunResult& r);

}  // namespace mospec::verdict
