// The interpreter's state for one Program: every slot, every stateful step's
// state and every solver's workspace, allocated once when the interpreter is
// built (prepare hooks), then read and written by the step kinds' interpret
// hooks (kinds/*.cpp), which allocate nothing and throw nothing.
#pragma once

#include <memory>
#include <vector>

#include "ir/controllers.hpp"
#include "ir/ir.hpp"
#include "ir/operators.hpp"
#include "runtime/achd.hpp"
#include "runtime/kelo.hpp"
#include "runtime/monitors.hpp"
#include "runtime/steps.hpp"

namespace mospec::ir {

struct Machine {
  // One arm solver's models (physical, with gravity; and the ACHD solve's,
  // without it when compensated), its data and the steps' workspace.
  struct Arm {
    explicit Arm(const ArmSolver& s);
    runtime::AchdModel model;
    runtime::AchdModel task_model;
    runtime::AchdData data;
    runtime::Pose X_BR;  // the chain's root in the solver's root (mount inverse)
    runtime::steps::ArmWorkspace ws;
  };
  struct Base {
    explicit Base(const BaseSolver& s);
    runtime::KeloModel model;
    runtime::KeloData data;
  };

  explicit Machine(const Program& program) : program(program) {}
  size_t slot(int data) const {
    return static_cast<size_t>(program.data[static_cast<size_t>(data)].slot);
  }

  const Program& program;
  Slots s;
  // Operator steps' input slots, flattened; a step's start by step index.
  std::vector<int> operator_slots;
  std::vector<size_t> operator_slot_offset;
  // By step index (null for steps of other kinds).
  std::vector<std::unique_ptr<ControllerInstance>> controllers;
  std::vector<std::unique_ptr<runtime::ConstraintEvaluator>> evaluators;
  std::vector<runtime::MonitorState> monitor_states;
  std::vector<runtime::steps::MotionState> motion_states;
  std::vector<std::unique_ptr<Arm>> arms;
  std::unique_ptr<Base> base;
};

}  // namespace mospec::ir
