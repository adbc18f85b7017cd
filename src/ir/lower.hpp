// Lowering: a loaded, validated task model -> the IR Program (ir.hpp).
//
// Every decision the back-ends need is made here: the data type, frames and
// unit of each quantity; which runtime operator computes it; whether a view
// reads a component of a 3D quantity or writes one into it (by what produces
// the superobject or the subobject); how each arm's motion drivers map onto
// ACHD's inputs (acceleration constraints on the tip, wrenches on segments,
// joint forces) and which priority level each belongs to; which motion gates
// which controller; and the schedule, a topological order from sensor reads
// to actuator writes.
//
// Errors are collected, not thrown one by one: every quantity that nothing
// produces, every datum produced twice, every cycle, every frame or unit the
// runtime cannot honour, each located at the entity's file:line.
#pragma once

#include <functional>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "app/app.hpp"
#include "ir/ir.hpp"
#include "support/diagnostics.hpp"

namespace mospec::ir {

struct LowerOptions {
  // Which arm of the robot (its index in the robot interface's arms) each
  // kinematic chain drives. Lowering knows no robot of its own: the CLI takes
  // them from the scenario's world file (sim::WorldConfig::arms, the default
  // world's when there is none); an arm solver of a chain not listed here is
  // refused ("unbound-chain").
  std::map<std::string, int> ports;
  // Called after each pass (lowering_passes()) with the program so far: its
  // steps in declaration order until the "schedule" pass orders them.
  std::function<void(std::string_view pass, const Program&)> after_pass;
  // Where lowering reports what a model says that has no effect in the
  // program it lowers to ("controller-reaches-no-solver": a controller whose
  // output no solver depends on). The CLI prints them; --strict refuses them.
  // nullptr: not collected.
  DiagnosticSink* warnings = nullptr;
};

// The names of lowering's passes, in the order they run. Each reads the model
// graph and adds data and steps to the program; ir::check(Stage::Unscheduled)
// runs after each one, and the full ir::verify after the last.
std::span<const std::string_view> lowering_passes();

// Thrown by lower(): all the problems found, each a located Diagnostic;
// what() is them formatted one per line.
class LowerError : public Error {
 public:
  explicit LowerError(std::vector<Diagnostic> diagnostics);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

// Lowers the flattened graph of `model`. The caller validates first (the CLI
// refuses models with violations before lowering). Throws LowerError.
Program lower(const app::LoadedModel& model, const LowerOptions& options = {});

// The content hash of a program's JSON (hex FNV-1a 64): the cache key for
// generated and built controllers.
std::string content_hash(const std::string& text);

}  // namespace mospec::ir
