// Lowering finds a chain's frames, links and origins through the model's
// relations, never by how their IRIs are spelled: sc1 with its robot and model
// IRIs renamed consistently (frame-X -> fr_X, link-X -> body_X, point-X ->
// pt_X, joint-X -> jt_X, the chain node "chain" -> "kinematic-chain-1", across
// the robot descriptions and every model file) lowers to the same program up
// to names and ticks to the same log, bit for bit.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <regex>

#include "app/app.hpp"
#include "default_robot_ports.hpp"
#include "ir/interpreter.hpp"
#include "ir/lower.hpp"
#include "sim/config.hpp"
#include "support/io.hpp"

namespace mospec::ir {
namespace {

namespace fs = std::filesystem;

// Renames inside every JSON string value (not keys: vocabulary terms such as
// "joint-force" stay as they are).
std::string rename_iris(const std::string& text) {
  static const std::regex value(R"re("([^"\\]*)"(\s*)(:?))re");
  static const std::pair<std::regex, const char*> renames[] = {
      {std::regex(R"((^|[/#])frame-)"), "$1fr_"},
      {std::regex(R"((^|[/#])link-)"), "$1body_"},
      {std::regex(R"((^|[/#])point-)"), "$1pt_"},
      {std::regex(R"((^|[/#])joint-)"), "$1jt_"},
      {std::regex(R"((^|/)chain$)"), "$1kinematic-chain-1"},
  };
  std::string out;
  auto begin = std::sregex_iterator(text.begin(), text.end(), value);
  size_t at = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    out.append(text, at, static_cast<size_t>(m.position(0)) - at);
    std::string s = m[1].str();
    if (m[3].str().empty()) {  // a value, not a key
      for (const auto& [from, to] : renames) s = std::regex_replace(s, from, to);
    }
    out.append("\"").append(s).append("\"").append(m[2].str()).append(m[3].str());
    at = static_cast<size_t>(m.position(0) + m.length(0));
  }
  out.append(text, at, std::string::npos);
  return out;
}

void copy_renamed(const fs::path& from, const fs::path& to) {
  for (const auto& e : fs::recursive_directory_iterator(from)) {
    const fs::path target = to / fs::relative(e.path(), from);
    if (e.is_directory()) {
      fs::create_directories(target);
    } else if (e.is_regular_file()) {
      fs::create_directories(target.parent_path());
      const std::string text = read_file(e.path().string());
      const std::string ext = e.path().extension().string();
      write_output(target.string(), ext == ".json" || ext == ".jsonld" ? rename_iris(text) : text);
    }
  }
}

Program lower_sc1(const fs::path& root, const std::map<std::string, int>& ports) {
  app::LoadOptions options;
  options.root = root.string();
  app::LoadedModel model = app::load({(root / "models/sc1.json").string()}, options);
  LowerOptions lower_options;
  lower_options.ports = ports;
  return lower(model, lower_options);
}

robot::MeasuredState measurement(int k) {
  const sim::WorldConfig world = sim::default_world();
  robot::MeasuredState state = robot::make_state(robot::gen3_pair_shape());
  for (size_t arm = 0; arm < state.arm.size(); ++arm) {
    state.arm[arm].q = world.arms[arm].q0;
    state.arm[arm].qd[1] =
        0.02 * std::sin(0.01 * static_cast<double>(k) + static_cast<double>(arm));
  }
  state.clock.tick = static_cast<std::uint64_t>(k);
  state.clock.t = 0.001 * k;
  state.clock.dt = k == 0 ? 0.0 : 0.001;
  for (size_t i = 0; i < state.pivot_q.size(); ++i) state.pivot_q[i] = 0.1 * static_cast<double>(i);
  return state;
}

TEST(RenamedModel, RenamingHelperRenamesValuesNotKeys) {
  EXPECT_EQ(
      rename_iris(R"({"joint-force": ["frame-a", "https://x/kinova/link-b"], "@id": "chain"})"),
      R"({"joint-force": ["fr_a", "https://x/kinova/body_b"], "@id": "kinematic-chain-1"})");
  EXPECT_EQ(rename_iris(R"({"of": "point-c-origin", "x": "cstr-dist-frame-z"})"),
            R"({"of": "pt_c-origin", "x": "cstr-dist-frame-z"})");
}

TEST(RenamedModel, Sc1LowersToTheSameProgramUpToNamesAndTicksToTheSameLog) {
  const fs::path src = MOSPEC_SOURCE_DIR;
  const fs::path root = fs::temp_directory_path() / ("mospec-rename-" + std::to_string(getpid()));
  fs::remove_all(root);
  copy_renamed(src / "models", root / "models");
  copy_renamed(src / "robots", root / "robots");
  fs::copy(src / "metamodels", root / "metamodels", fs::copy_options::recursive);
  // The renamed robot file really is renamed (the test would prove nothing otherwise).
  const std::string robot = read_file((root / "robots/kinova-gen3.jsonld").string());
  ASSERT_EQ(robot.find("\"frame-"), std::string::npos);
  ASSERT_NE(robot.find("\"kinematic-chain-1\""), std::string::npos);

  const Program a = lower_sc1(src, testing::default_robot_ports());
  const Program b =
      lower_sc1(root, {{"https://mospec.example/robots/kinova-gen3/kinematic-chain-1", 0},
                       {"https://mospec.example/robots/kinova-gen3-left/kinematic-chain-1", 1}});
  fs::remove_all(root);

  // The same program up to names: data, steps, solvers, log.
  ASSERT_EQ(a.data.size(), b.data.size());
  EXPECT_EQ(a.slots, b.slots);
  for (size_t i = 0; i < a.data.size(); ++i) {
    EXPECT_EQ(a.data[i].type, b.data[i].type) << a.data[i].iri;
    EXPECT_EQ(a.data[i].slot, b.data[i].slot) << a.data[i].iri;
    EXPECT_EQ(a.data[i].value, b.data[i].value) << a.data[i].iri;
    EXPECT_EQ(a.data[i].unit, b.data[i].unit) << a.data[i].iri;
  }
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (size_t i = 0; i < a.steps.size(); ++i) {
    EXPECT_EQ(kind_name(a.steps[i]), kind_name(b.steps[i])) << i;
    EXPECT_EQ(a.steps[i].in, b.steps[i].in) << a.steps[i].name;
    EXPECT_EQ(a.steps[i].out, b.steps[i].out) << a.steps[i].name;
    EXPECT_EQ(a.steps[i].views, b.steps[i].views) << a.steps[i].name;
  }
  // ... and the names did change (the chain, its frames and points).
  EXPECT_EQ(b.arms.at(0).chain_iri.find("/kinematic-chain-1"), b.arms.at(0).chain_iri.size() - 18);
  EXPECT_NE(b.arms.at(0).root_frame.find("fr_"), std::string::npos) << b.arms.at(0).root_frame;
  ASSERT_EQ(a.arms.size(), b.arms.size());
  for (size_t k = 0; k < a.arms.size(); ++k) {
    const ArmSolver &x = a.arms[k], &y = b.arms[k];
    EXPECT_EQ(x.port, y.port);
    ASSERT_EQ(x.chain.size(), y.chain.size());
    for (int s = 0; s < x.chain.size(); ++s) {
      EXPECT_EQ(x.chain.segment(s).X_PJ.R, y.chain.segment(s).X_PJ.R);
      EXPECT_EQ(x.chain.segment(s).X_PJ.p, y.chain.segment(s).X_PJ.p);
      EXPECT_EQ(x.chain.segment(s).inertia.mass, y.chain.segment(s).inertia.mass);
    }
    ASSERT_EQ(x.outputs.size(), y.outputs.size());
    for (size_t o = 0; o < x.outputs.size(); ++o) {
      EXPECT_EQ(x.outputs[o].segment, y.outputs[o].segment);
      EXPECT_EQ(x.outputs[o].what, y.outputs[o].what);
    }
    ASSERT_EQ(x.cartesian_forces.size(), y.cartesian_forces.size());
    for (size_t f = 0; f < x.cartesian_forces.size(); ++f)
      EXPECT_EQ(x.cartesian_forces[f].segment, y.cartesian_forces[f].segment);
    ASSERT_EQ(x.acceleration_constraints.size(), y.acceleration_constraints.size());
  }
  ASSERT_EQ(a.log.size(), b.log.size());

  // The same log, tick for tick, bit for bit.
  Interpreter ia(a), ib(b);
  std::vector<double> va(ia.log_columns().size()), vb(va.size());
  for (int k = 0; k < 1000; ++k) {
    const robot::MeasuredState state = measurement(k);
    robot::Command ca = robot::make_command(robot::gen3_pair_shape()), cb = ca;
    ia.tick(state, ca);
    ib.tick(state, cb);
    ia.log_values(va);
    ib.log_values(vb);
    ASSERT_EQ(std::memcmp(va.data(), vb.data(), va.size() * sizeof(double)), 0) << "tick " << k;
    ASSERT_EQ(ca.arm_tau.size(), cb.arm_tau.size());
    for (size_t a = 0; a < ca.arm_tau.size(); ++a) {
      ASSERT_EQ(std::memcmp(ca.arm_tau[a].data(), cb.arm_tau[a].data(),
                            ca.arm_tau[a].size() * sizeof(double)),
                0)
          << "tick " << k;
    }
    ASSERT_EQ(ca.wheel_tau.size(), cb.wheel_tau.size());
    ASSERT_EQ(
        std::memcmp(ca.wheel_tau.data(), cb.wheel_tau.data(), ca.wheel_tau.size() * sizeof(double)),
        0)
        << "tick " << k;
  }
}

}  // namespace
}  // namespace mospec::ir
