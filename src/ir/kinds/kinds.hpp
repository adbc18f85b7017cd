// The behaviour of every step kind, one file per family: how the interpreter
// prepares and executes it (over a Machine) and which template section codegen
// emits for it (through an EmitContext). The registry (kStepKinds, ir.cpp)
// points each kind at its functions here; nothing else dispatches on a kind.
#pragma once

#include <cstddef>

#include "ir/emit.hpp"
#include "ir/ir.hpp"
#include "ir/machine.hpp"

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

// What the interpreter allocates for a step before the first tick.
void prepare_operator(Machine& m, const Step& st, size_t index);
void prepare_evaluate(Machine& m, const Step& st, size_t index);
void prepare_controller(Machine& m, const Step& st, size_t index);

}  // namespace mospec::ir::kinds
