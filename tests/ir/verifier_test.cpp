// The verifier checks meaning, not only shapes: each invariant lowering
// establishes (units, frames, what ACHD needs of its drivers) is broken in a
// lowered program, and ir::check must report it, located at the model entity
// involved, with what it expected and what it got. It runs after every pass,
// so a pass that breaks one is caught where it does.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "app/app.hpp"
#include "default_robot_ports.hpp"
#include "ir/ir.hpp"
#include "ir/lower.hpp"
#include "ir/operators.hpp"

namespace mospec::ir {
namespace {

struct Lowered {
  app::LoadedModel model;
  Program program;
};

// sc1: both arms with Cartesian forces and acceleration constraints, and
// bilateral constraints with bound data.
const Lowered& sc1() {
  static const Lowered lowered = [] {
    app::LoadOptions options;
    options.root = MOSPEC_SOURCE_DIR;
    Lowered l{app::load({std::string(MOSPEC_SOURCE_DIR) + "/models/sc1.json"}, options), {}};
    LowerOptions lower_options;
    lower_options.ports = testing::default_robot_ports();
    l.program = lower(l.model, lower_options);
    return l;
  }();
  return lowered;
}

// The findings after `edit`, one per line as the CLI prints them.
std::string findings_after(const std::function<void(Program&)>& edit) {
  Program p = sc1().program;
  edit(p);
  std::string all;
  for (const Diagnostic& d : check(p, &sc1().model.files())) all.append(format(d)).append("\n");
  return all;
}

Step& first(Program& p, const std::function<bool(const Step&)>& which) {
  for (Step& st : p.steps)
    if (which(st)) return st;
  throw std::runtime_error("sc1 has no such step");
}

Data& datum(Program& p, int d) {
  return p.data[static_cast<size_t>(d)];
}

TEST(VerifierMeaning, TheLoweredProgramHasNoFindings) {
  EXPECT_EQ(findings_after([](Program&) {}), "");
}

TEST(VerifierMeaning, AnErrorInAnotherUnitThanItsQuantity) {
  const std::string all = findings_after([](Program& p) {
    Step& e = first(p, [](const Step& s) {
      return s.kind == StepKind::Evaluate &&
             s.constraint.kind != runtime::ConstraintKind::Assignment;
    });
    datum(p, e.out[1]).unit = "KiloGM";
  });
  EXPECT_NE(all.find("error '"), std::string::npos) << all;
  EXPECT_NE(all.find("is in 'KiloGM'; expected its quantity's unit"), std::string::npos) << all;
  EXPECT_NE(all.find("models/sc1/"), std::string::npos) << "not located in the model:\n" << all;
}

TEST(VerifierMeaning, ABoundInAnotherUnitOrOnAConstraintWithoutBounds) {
  std::string all = findings_after([](Program& p) {
    Step& e = first(p, [](const Step& s) { return s.lower_bound >= 0; });
    datum(p, e.upper_bound).unit = "RAD";
  });
  EXPECT_NE(all.find("upper bound '"), std::string::npos) << all;
  EXPECT_NE(all.find("is in 'RAD'; expected its quantity's unit"), std::string::npos) << all;
  all = findings_after([](Program& p) {
    Step& bilateral = first(p, [](const Step& s) { return s.lower_bound >= 0; });
    const int bound = bilateral.lower_bound;
    Step& other = first(p, [](const Step& s) {
      return s.kind == StepKind::Evaluate && s.constraint.kind == runtime::ConstraintKind::LessThan;
    });
    other.lower_bound = bound;
  });
  EXPECT_NE(all.find("has bound data, but its constraint is not bilateral"), std::string::npos)
      << all;
}

TEST(VerifierMeaning, AnOperatorThatBreaksItsFrameRule) {
  std::string rule;
  const std::string all = findings_after([&](Program& p) {
    for (Step& st : p.steps) {
      if (st.kind != StepKind::Operator) continue;
      const OperatorKind& k = operator_kinds()[static_cast<size_t>(st.op)];
      for (const FrameRule& r : k.frames) {
        if (r.rhs_origin || r.lhs_field != FrameField::AsSeenBy) continue;
        const int port = r.lhs_port;
        const int d =
            port < static_cast<int>(st.in.size()) ? st.in[static_cast<size_t>(port)] : st.out[0];
        if (datum(p, d).as_seen_by.empty()) continue;
        datum(p, d).as_seen_by = "http://example.org/elsewhere";
        rule = r.text;
        return;
      }
    }
  });
  ASSERT_FALSE(rule.empty()) << "sc1 has no operator with an as-seen-by frame rule";
  EXPECT_NE(all.find("breaks its frame rule '" + rule + "': as-seen-by of '"), std::string::npos)
      << all;
  EXPECT_NE(all.find("is 'http://example.org/elsewhere'; expected '"), std::string::npos) << all;
}

TEST(VerifierMeaning, AnAccelerationEnergyInAnotherUnit) {
  const std::string all = findings_after(
      [](Program& p) { datum(p, p.arms[0].acceleration_constraints[0].energy).unit = "KiloGM"; });
  EXPECT_NE(all.find("takes its energy from '"), std::string::npos) << all;
  EXPECT_NE(all.find("in 'KiloGM'; expected N-M2-PER-SEC2"), std::string::npos) << all;
}

TEST(VerifierMeaning, ACartesianForceNotSeenByTheRoot) {
  std::string root;
  const std::string all = findings_after([&](Program& p) {
    root = p.arms[0].root_frame;
    datum(p, p.arms[0].cartesian_forces[0].wrench).as_seen_by = "http://example.org/tool";
  });
  EXPECT_NE(
      all.find("seen by 'http://example.org/tool'; ACHD needs it seen by the root '" + root + "'"),
      std::string::npos)
      << all;
}

TEST(VerifierMeaning, AJointForceInTheWrongUnitForItsJoint) {
  const std::string all = findings_after([](Program& p) {
    // A revolute joint driven by a datum in metres.
    int length = -1;
    for (size_t d = 0; d < p.data.size() && length < 0; ++d)
      if (p.data[d].unit == "M" && p.data[d].type == DataType::Scalar) length = static_cast<int>(d);
    ASSERT_GE(length, 0);
    p.arms[0].joint_forces.push_back({"http://example.org/jf", 1, length, 0});
  });
  EXPECT_NE(all.find("joint force 'http://example.org/jf' applies '"), std::string::npos) << all;
  EXPECT_NE(all.find("in 'M' to revolute joint 1; expected N-M"), std::string::npos) << all;
}

}  // namespace
}  // namespace mospec::ir
