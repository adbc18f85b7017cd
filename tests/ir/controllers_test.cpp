// The controller registry (src/ir/controllers.*): every kind is complete — a
// name generated code can use, a vocabulary class with signals and parameters,
// units that name its ports, a runtime model the interpreter builds and codegen
// names — and comes with what a user of its class needs: a JSON-LD context
// term for the class and each property, a SHACL shape, and a conforming and a
// violating shape test case. A kind that lacks any of them fails here.
#include "ir/controllers.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "runtime/controllers.hpp"
#include "source_tree.hpp"
#include "support/diagnostics.hpp"

namespace mospec::ir {
namespace {

namespace fs = std::filesystem;

TEST(ControllerRegistry, EveryKindIsComplete) {
  // Generated code's Data names each stateful kind's state array by the kind's
  // name: it must be an identifier and not one of Data's other members.
  const std::set<std::string> taken{"scalar", "vec3",  "pose",    "twist",  "wrench",
                                    "flag",   "event", "monitor", "motion", "base"};
  std::set<std::string> names, classes;
  for (const ControllerKind& k : controller_kinds()) {
    SCOPED_TRACE(std::string(k.name));
    EXPECT_TRUE(std::regex_match(std::string(k.name), std::regex("[a-z]+")));
    EXPECT_FALSE(taken.count(std::string(k.name)));
    EXPECT_TRUE(names.insert(std::string(k.name)).second) << "two kinds named " << k.name;
    EXPECT_TRUE(classes.insert(k.class_iri()).second) << "two kinds lower " << k.class_iri();
    EXPECT_TRUE(k.vocabulary.starts_with("https://") && k.vocabulary.ends_with("#"));
    EXPECT_FALSE(k.type.empty());
    EXPECT_FALSE(k.in.empty());
    EXPECT_LE(k.in.size(), static_cast<size_t>(kMaxControllerSignals));
    EXPECT_FALSE(k.out.empty());
    EXPECT_FALSE(k.model_type.empty());
    EXPECT_FALSE(k.spec_type.empty());
    EXPECT_FALSE(k.kernel.empty());
    EXPECT_NE(k.make, nullptr);
    EXPECT_FALSE(k.title.empty());
    EXPECT_FALSE(k.summary.empty());
    EXPECT_EQ(controller_index(k.name), &k - controller_kinds().data());
    std::set<std::string> ports(k.in.begin(), k.in.end());
    ports.insert(std::string(k.out));
    for (const ControllerParameter& p : k.parameters) {
      SCOPED_TRACE(std::string(p.member));
      EXPECT_NE(p.set, nullptr);
      EXPECT_EQ(p.property.empty(), p.source == ParameterSource::Fixed);
      EXPECT_EQ(p.json.empty(), p.source == ParameterSource::Fixed);
      EXPECT_EQ(k.parameter(p.member), &p - k.parameters.data());
      if (p.source == ParameterSource::Quantity) ports.insert(std::string(p.property));
      EXPECT_EQ(p.enumerators.empty(), p.enum_type.empty());
    }
    for (const auto& row : k.units) EXPECT_EQ(row.size(), k.unit_ports.size());
    for (std::string_view port : k.unit_ports)
      EXPECT_TRUE(ports.count(std::string(port)))
          << "unit port " << port << " is no signal or quantity parameter";
    for (const RefusedProperty& r : k.refused) {
      EXPECT_FALSE(r.property.empty());
      EXPECT_FALSE(r.code.empty());
      EXPECT_FALSE(r.why.empty());
    }
    // The runtime's defaults build (the fixed parameters are valid as they are)
    // once the model's parameters are given valid values.
    std::vector<double> values = k.defaults();
    for (size_t i = 0; i < values.size(); ++i) {
      if (k.parameters[i].source != ParameterSource::Fixed) values[i] = 0.5;
    }
    EXPECT_NE(k.instantiate(values, "ctrl"), nullptr);
  }
}

TEST(ControllerRegistry, EveryClassHasContextTermsAShapeAndShapeTests) {
  const fs::path src = MOSPEC_SOURCE_DIR;
  const auto contexts = mospec::test::texts_of_files(src / "metamodels", ".json");
  const auto shapes = mospec::test::texts_of_files(src / "metamodels", ".ttl");
  const auto good = mospec::test::texts_of_files(src / "tests/models/data", "-good.json");
  const auto bad = mospec::test::texts_of_files(src / "tests/models/data", "-bad.json");
  for (const ControllerKind& k : controller_kinds()) {
    SCOPED_TRACE(k.class_iri());
    std::vector<std::string> terms{std::string(k.type), std::string(k.out)};
    terms.insert(terms.end(), k.in.begin(), k.in.end());
    for (const ControllerParameter& p : k.parameters) {
      if (!p.property.empty()) terms.emplace_back(p.property);
    }
    for (const RefusedProperty& r : k.refused) terms.emplace_back(r.property);
    for (const std::string& term : terms) {
      bool context = false;
      for (const std::string& text : contexts) {
        context = context || (text.find(std::string(k.vocabulary)) != std::string::npos &&
                              text.find('"' + term + "\": {") != std::string::npos);
      }
      EXPECT_TRUE(context) << "no JSON-LD context in metamodels/ defines the term " << term;
    }
    const std::regex shape_of("sh:targetClass [A-Za-z_-]+:" + std::string(k.type) + "\\b");
    bool shape = false, conforming = false, violating = false;
    for (const std::string& text : shapes) shape = shape || std::regex_search(text, shape_of);
    const std::regex typed("\"([A-Za-z_-]+:|[^\"]*#)" + std::string(k.type) + "\"");
    for (const std::string& text : good) conforming = conforming || std::regex_search(text, typed);
    for (const std::string& text : bad) violating = violating || std::regex_search(text, typed);
    EXPECT_TRUE(shape) << "no shape in metamodels/ targets " << k.type;
    EXPECT_TRUE(conforming) << "no tests/models/data/*-good.json has an instance of " << k.type;
    EXPECT_TRUE(violating) << "no tests/models/data/*-bad.json has an instance of " << k.type;
  }
}

TEST(ControllerRegistry, ThePidsDefaultsAreTheRuntimes) {
  const ControllerKind& pid = controller_kinds()[static_cast<size_t>(controller_index("pid"))];
  const runtime::PidSpec spec;
  const std::vector<double> d = pid.defaults();
  EXPECT_EQ(d[static_cast<size_t>(pid.parameter("output_min"))], spec.output_min);
  EXPECT_EQ(d[static_cast<size_t>(pid.parameter("output_max"))], spec.output_max);
  EXPECT_EQ(d[static_cast<size_t>(pid.parameter("anti_windup"))],
            static_cast<int>(spec.anti_windup));
  EXPECT_EQ(pid.parameters[static_cast<size_t>(pid.parameter("anti_windup"))]
                .enumerators[static_cast<size_t>(spec.anti_windup)],
            "ConditionalIntegration");
}

TEST(ControllerRegistry, TheInterpretersInstanceRunsTheKernel) {
  // A damper (v_max 0.5 m/s, F_max 2 N): -4 N s/m, gated.
  const ControllerKind& k = controller_kinds()[static_cast<size_t>(controller_index("damping"))];
  std::vector<double> values = k.defaults();
  values[static_cast<size_t>(k.parameter("maximum_velocity"))] = 0.5;
  values[static_cast<size_t>(k.parameter("maximum_force"))] = 2.0;
  const auto damper = k.instantiate(values, "damper");
  const double v = 0.25;
  EXPECT_DOUBLE_EQ(damper->step(&v, 1e-3, true), -1.0);
  EXPECT_DOUBLE_EQ(damper->step(&v, 1e-3, false), 0.0);
}

TEST(ControllerRegistry, TheRuntimeRefusalNamesTheController) {
  const ControllerKind& k = controller_kinds()[static_cast<size_t>(controller_index("damping"))];
  try {
    k.instantiate(k.defaults(), "https://ex.org/damper");  // F_max 0
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid-controller");
    EXPECT_EQ(e.diagnostic().message.rfind("https://ex.org/damper: a damping controller needs", 0),
              0u)
        << e.diagnostic().message;
  }
}

// The loop check judges a kind whose runtime model declares its linear law:
// the PID and the impedance do, the saturated damper does not. A kind's poles
// are its runtime transfer's, closed around the plant.
TEST(ControllerRegistry, LinearKindsGiveTheirClosedLoopPoles) {
  const auto kind = [](std::string_view name) -> const ControllerKind& {
    return controller_kinds()[static_cast<size_t>(controller_index(name))];
  };
  EXPECT_TRUE(kind("pid").linear());
  EXPECT_TRUE(kind("impedance").linear());
  EXPECT_FALSE(kind("damping").linear());
  EXPECT_TRUE(kind("damping").closed_loop_poles(kind("damping").defaults(), 1e-3, {}).empty());
  // Their loop gains, whose signs the check judges and which it scales.
  const auto gains = [](const ControllerKind& k) {
    std::vector<std::string_view> g;
    for (const ControllerParameter& p : k.parameters)
      if (p.gain) g.push_back(p.member);
    return g;
  };
  EXPECT_EQ(gains(kind("pid")), (std::vector<std::string_view>{"kp", "ki", "kd"}));
  EXPECT_EQ(gains(kind("impedance")), (std::vector<std::string_view>{"stiffness", "damping"}));
  EXPECT_TRUE(gains(kind("damping")).empty());
  // u = kp e around e_{k+1} = e_k - 0.001 u_k: one pole at 1 - 0.001 kp.
  const ControllerKind& pid = kind("pid");
  std::vector<double> values = pid.defaults();
  values[static_cast<size_t>(pid.parameter("kp"))] = 300.0;
  const runtime::Transfer plant{.num = {-0.001}, .den = {-1.0, 1.0}};
  const auto poles = pid.closed_loop_poles(values, 1e-3, plant);
  EXPECT_NEAR(runtime::spectral_radius(poles), 0.7, 1e-12);
}

}  // namespace
}  // namespace mospec::ir
