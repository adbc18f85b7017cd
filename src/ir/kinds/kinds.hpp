// The behaviour of every step kind, one file per family: how the interpreter
// prepares and executes it (over a Machine) and which template section codegen
// emits for it (through an EmitContext). The registry (kStepKinds, ir.cpp)
// points each kind at its functions here; nothing else dispatches on a kind.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>

#include "ir/emit.hpp"
#include "ir/ir.hpp"
#include "ir/lowering.hpp"
#include "ir/machine.hpp"
#include "ir/verify.hpp"

namespace mospec::ir {

// The JSON object of one step that a kind's print hook adds to.
struct StepJson {
  nlohmann::ordered_json& e;
};

}  // namespace mospec::ir

namespace mospec::ir::kinds {

#define MOSPEC_STEP_KIND_HOOKS(kind)                                                          \
  void interpret_##kind(Machine& m, const Step& st, size_t index,                             \
                        const robot::MeasuredState& state, robot::Command& command) noexcept; \
  void emit_##kind(const EmitContext& ctx, const Step& st, size_t index, mustache::Data& s);

MOSPEC_STEP_KIND_HOOKS(read_clock)
MOSPEC_STEP_KIND_HOOKS(arm_kinematics)
MOSPEC_STEP_KIND_HOOKS(view_read)
MOSPEC_STEP_KIND_HOOKS(view_write)
MOSPEC_STEP_KIND_HOOKS(operator)
MOSPEC_STEP_KIND_HOOKS(evaluate)
MOSPEC_STEP_KIND_HOOKS(monitor)
MOSPEC_STEP_KIND_HOOKS(guarded_motion)
MOSPEC_STEP_KIND_HOOKS(any_of)
MOSPEC_STEP_KIND_HOOKS(controller)
MOSPEC_STEP_KIND_HOOKS(arm_solve)
MOSPEC_STEP_KIND_HOOKS(base_force_distribution)
MOSPEC_STEP_KIND_HOOKS(base_velocity_composition)

#undef MOSPEC_STEP_KIND_HOOKS

// The data types each kind takes and gives (the verifier's signature).
Signature signature_read_clock(const Step&, const Program&);
Signature signature_arm_kinematics(const Step&, const Program&);
Signature signature_view_read(const Step&, const Program&);
Signature signature_view_write(const Step&, const Program&);
Signature signature_operator(const Step&, const Program&);
Signature signature_evaluate(const Step&, const Program&);
Signature signature_monitor(const Step&, const Program&);
Signature signature_guarded_motion(const Step&, const Program&);
Signature signature_any_of(const Step&, const Program&);
Signature signature_controller(const Step&, const Program&);
Signature signature_arm_solve(const Step&, const Program&);
Signature signature_base_force_distribution(const Step&, const Program&);
Signature signature_base_velocity_composition(const Step&, const Program&);

// The rules of a kind's own fields, beyond its signature.
void verify_view_read(const Step&, const Program&, Findings&);
void verify_view_write(const Step&, const Program&, Findings&);
void verify_monitor(const Step&, const Program&, Findings&);
void verify_guarded_motion(const Step&, const Program&, Findings&);
void verify_controller(const Step&, const Program&, Findings&);
void verify_arm_solver(const Step&, const Program&, Findings&);  // arm-kinematics
void verify_arm_solve(const Step&, const Program&, Findings&);
void verify_base(const Step&, const Program&, Findings&);  // base-velocity-composition
void verify_base_force_distribution(const Step&, const Program&, Findings&);
// A solve's drivers and the motion gates after them (arm-solve,
// base-force-distribution).
void verify_gates(const Step&, const Program&, Findings&);

// A kind's own fields in the IR's JSON (to_json), after the common ones.
using Json = nlohmann::ordered_json;
void print_view(const Step&, StepJson&);
void print_evaluate(const Step&, StepJson&);
void print_monitor(const Step&, StepJson&);
void print_guarded_motion(const Step&, StepJson&);
void print_controller(const Step&, StepJson&);
void print_drivers(const Step&, StepJson&);  // arm-solve, base-force-distribution
// A constraint's relation, bounds and tolerance (evaluate, the monitors).
Json constraint_json(const runtime::ConstraintSpec& c);

void verify_evaluate(const Step&, const Program&, Findings&);
void verify_operator(const Step&, const Program&, Findings&);

// The log columns of a kind's outputs (lowering's log pass; the verdict reads
// them by name).
void log_evaluate(const Program&, const Step&, std::vector<LogColumn>&);
void log_monitor(const Program&, const Step&, std::vector<LogColumn>&);
void log_guarded_motion(const Program&, const Step&, std::vector<LogColumn>&);
void log_controller(const Program&, const Step&, std::vector<LogColumn>&);
void log_arm_solve(const Program&, const Step&, std::vector<LogColumn>&);
void log_base_force_distribution(const Program&, const Step&, std::vector<LogColumn>&);
void log_base_velocity_composition(const Program&, const Step&, std::vector<LogColumn>&);
// The column "<step's local name><suffix>" of one of its outputs.
LogColumn step_column(const Program& p, const Step& st, std::string_view suffix, int data,
                      robot::LogColumnKind kind);

// Which input gates a step's output (StepKindInfo::gate).
int gate_controller(const Step&);
int gate_evaluate(const Step&);

// What the interpreter allocates for a step before the first tick.
void prepare_operator(Machine& m, const Step& st, size_t index);
void prepare_evaluate(Machine& m, const Step& st, size_t index);
void prepare_controller(Machine& m, const Step& st, size_t index);

}  // namespace mospec::ir::kinds
