// Executes an IR Program directly, without generating code: the reference
// semantics of every step kind. Generated controllers (src/codegen) make the
// same runtime calls in the same order and must log bit-identical values.
//
// Construction allocates everything (slots, solver workspaces, log columns);
// tick() allocates nothing and throws nothing.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "ir/controllers.hpp"
#include "ir/ir.hpp"
#include "ir/machine.hpp"
#include "ir/operators.hpp"
#include "robot/controller.hpp"
#include "runtime/monitors.hpp"
#include "runtime/steps.hpp"

namespace mospec::ir {

class Interpreter final : public robot::Controller {
 public:
  // Throws mospec::Error when the program does not verify or a constant is
  // invalid (e.g. a PID gain out of range), naming the step.
  explicit Interpreter(Program program);
  ~Interpreter() override;

  const char* app() const noexcept override { return program_.app.c_str(); }
  void tick(const robot::MeasuredState& state, robot::Command& command) noexcept override;
  std::span<const robot::LogColumnInfo> log_columns() const noexcept override { return columns_; }
  void log_values(std::span<double> out) const noexcept override;
  std::span<const int> arm_joints() const noexcept override { return arm_joints_; }

  const Program& program() const { return program_; }
  // The current value of a scalar, flag or event datum (flags as 0/1, events
  // as their code; NaN for other types).
  double value(int data) const noexcept;

 private:
  Program program_;
  Machine m_;  // after program_: it reads it
  std::vector<std::string> column_names_, column_units_;
  std::vector<int> arm_joints_;
  std::vector<InterpretHook> interpret_;  // each step's, looked up once
  std::vector<robot::LogColumnInfo> columns_;
};

}  // namespace mospec::ir
