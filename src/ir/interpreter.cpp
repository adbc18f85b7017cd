#include "ir/interpreter.hpp"

#include <array>
#include <cmath>

#include "ir/machine.hpp"
#include "ir/operators.hpp"
#include "runtime/model.hpp"

namespace mospec::ir {

using runtime::Pose;
using runtime::Vec3;
using runtime::Vec6;

Interpreter::Interpreter(Program program) : program_(std::move(program)), m_(program_) {
  verify(program_);
  m_.s.scalars.assign(static_cast<size_t>(program_.count(DataType::Scalar)), 0.0);
  m_.s.vec3s.assign(static_cast<size_t>(program_.count(DataType::Vector3)), Vec3::Zero());
  m_.s.poses.assign(static_cast<size_t>(program_.count(DataType::Pose)), Pose{});
  m_.s.twists.assign(static_cast<size_t>(program_.count(DataType::Twist)), Vec6::Zero());
  m_.s.wrenches.assign(static_cast<size_t>(program_.count(DataType::Wrench)), Vec6::Zero());
  m_.s.flags.assign(static_cast<size_t>(program_.count(DataType::Flag)), 0);
  m_.s.events.assign(static_cast<size_t>(program_.count(DataType::Event)), 0);
  m_.s.inertias.assign(static_cast<size_t>(program_.count(DataType::Inertia)), {});
  for (const Data& d : program_.data) {
    if (d.value.empty()) continue;
    const auto s = static_cast<size_t>(d.slot);
    switch (d.type) {
      case DataType::Scalar:
        m_.s.scalars[s] = d.value[0];
        break;
      case DataType::Vector3:
        m_.s.vec3s[s] = Vec3(d.value[0], d.value[1], d.value[2]);
        break;
      case DataType::Pose:
        m_.s.poses[s] = constant_pose(d.value);
        break;
      case DataType::Twist:
      case DataType::Wrench: {
        Vec6 v;
        for (int i = 0; i < 6; ++i) v[i] = d.value[static_cast<size_t>(i)];
        (d.type == DataType::Twist ? m_.s.twists : m_.s.wrenches)[s] = v;
        break;
      }
      case DataType::Flag:
        m_.s.flags[s] = d.value[0] != 0.0;
        break;
      case DataType::Event:
        break;
      case DataType::Inertia:
        m_.s.inertias[s] =
            runtime::rigid_body_inertia(std::span<const double, 10>(d.value.data(), 10));
        break;
    }
  }
  m_.monitor_states.resize(
      static_cast<size_t>(program_.states[static_cast<int>(StateKind::Monitor)]));
  m_.motion_states.assign(static_cast<size_t>(program_.states[static_cast<int>(StateKind::Motion)]),
                          runtime::steps::MotionState::Idle);
  m_.operator_slot_offset.assign(program_.steps.size(), 0);
  m_.evaluators.resize(program_.steps.size());
  m_.controllers.resize(program_.steps.size());
  for (size_t i = 0; i < program_.steps.size(); ++i) {
    const Step& st = program_.steps[i];
    if (const PrepareHook prepare = info(st.kind).prepare) prepare(m_, st, i);
  }
  for (const ArmSolver& a : program_.arms) m_.arms.push_back(std::make_unique<Machine::Arm>(a));
  if (program_.base) m_.base = std::make_unique<Machine::Base>(*program_.base);
  for (const LogColumn& c : program_.log) {
    column_names_.push_back(c.name);
    column_units_.push_back(c.unit);
  }
  for (size_t i = 0; i < column_names_.size(); ++i) {
    columns_.push_back({column_names_[i].c_str(), column_units_[i].c_str(), program_.log[i].kind});
  }
  arm_joints_ = ir::arm_joints(program_);
  for (const Step& st : program_.steps) interpret_.push_back(info(st.kind).interpret);
}

Interpreter::~Interpreter() = default;

void Interpreter::tick(const robot::MeasuredState& state, robot::Command& command) noexcept {
  robot::zero(command);
  command.tick = state.clock.tick;
  std::fill(m_.s.events.begin(), m_.s.events.end(), 0);
  for (size_t i = 0; i < program_.steps.size(); ++i) {
    const Step& st = program_.steps[i];
    interpret_[i](m_, st, i, state, command);
  }
}

double Interpreter::value(int data) const noexcept {
  const Data& d = program_.data[static_cast<size_t>(data)];
  const auto s = static_cast<size_t>(d.slot);
  switch (d.type) {
    case DataType::Scalar:
      return m_.s.scalars[s];
    case DataType::Flag:
      return m_.s.flags[s] ? 1.0 : 0.0;
    case DataType::Event:
      return static_cast<double>(static_cast<unsigned char>(m_.s.events[s]));
    default:
      return std::nan("");
  }
}

void Interpreter::log_values(std::span<double> out) const noexcept {
  for (size_t i = 0; i < out.size() && i < program_.log.size(); ++i) {
    const LogColumn& c = program_.log[i];
    const Data& d = program_.data[static_cast<size_t>(c.data)];
    if (c.component >= 0 && (d.type == DataType::Twist || d.type == DataType::Wrench)) {
      out[i] =
          (d.type == DataType::Twist ? m_.s.twists
                                     : m_.s.wrenches)[static_cast<size_t>(d.slot)][c.component];
    } else {
      out[i] = value(c.data);
    }
  }
}

}  // namespace mospec::ir
