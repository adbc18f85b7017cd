// The registry of controller kinds: every law that maps a signal (a
// constraint's error, a measured velocity) to a control signal and may keep
// state across ticks (paper Sec. II-E), each declared once, in controllers.cpp,
// as one table entry:
//
//   name        the IR's name of the kind ("pid"): its steps' `kind` in the
//               IR's JSON, its members' prefix in generated code;
//   vocabulary  the model class it lowers from, the properties naming its
//               signals (scalar inputs, one scalar output) and its
//               parameters, each parameter with where its value comes from
//               (a literal, a constant quantity, or the runtime's default);
//   units       the combinations of units its signals and quantity
//               parameters may have (lowering refuses any other);
//   refused     properties of its class that mospec cannot honour, each with
//               its diagnostic code and the reason;
//   runtime     the mospec::runtime types of its description (Model), its
//               parameters (Spec) and its per-controller state (State, or
//               none), and the step kernel. The interpreter's call, the
//               generated code's members, state arrays and call all derive
//               from them; the compiler checks that the kernel takes
//               (model, [state,] inputs..., [dt,] active).
//
// Lowering, the verifier, the IR's JSON, the interpreter and codegen read this
// table; none of them lists controllers. docs/extending.md walks through
// adding one ("Adding a controller").
#pragma once

#include <complex>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/transfer.hpp"

namespace mospec::ir {

// Where a controller parameter's value comes from.
enum class ParameterSource : uint8_t {
  Literal,   // an xsd:double literal of the controller ("proportional-gain": "200.0")
  Quantity,  // a constant quantity the property names: its qudt:value, in its qudt:unit
  Fixed,     // not in the model: the runtime's default (the PID's output limits)
};

// One field of the kind's runtime Spec, in the Spec's order.
struct ControllerParameter {
  std::string_view member;    // the Spec's field, as generated code spells it ("kp")
  std::string_view property;  // vocabulary property (local name); empty when Fixed
  std::string_view json;      // key in the IR's JSON; empty: not written there
  ParameterSource source = ParameterSource::Fixed;
  bool required = false;
  // Read only when the controller also has this class of the kind's
  // vocabulary (the PID's decay-rate: DecayingIntegralTerm).
  std::string_view only_with;
  // An enum field: its type and its enumerators' names (the value is the index).
  std::string_view enum_type;
  std::vector<std::string_view> enumerators;
  bool new_line = false;  // generated code breaks the line before it (layout only)
  // A loop gain: the output grows with it times the error, its integral or
  // its derivative, so the loop check before a run wants its sign opposite to
  // that of d(error)/d(output), and scales these to find a stable loop.
  bool gain = false;
  double fallback = 0.0;  // the Spec's default, for a parameter the model leaves out
  // (internal) writes / reads the field of a Spec.
  void (*set)(void* spec, double value) = nullptr;
};

// A property of the kind's class that mospec cannot honour.
struct RefusedProperty {
  std::string_view property;
  std::string_view code;  // the diagnostic's code
  std::string_view why;   // said after "mospec cannot honour it: "
};

// Most signals a controller kind may take.
inline constexpr int kMaxControllerSignals = 4;

// A controller as the interpreter runs it: its model and state.
class ControllerInstance {
 public:
  virtual ~ControllerInstance() = default;
  // One step: `in` holds the signals in declaration order.
  virtual double step(const double* in, double dt, bool active) noexcept = 0;
};

struct ControllerKind {
  std::string_view name;             // "pid"
  std::string_view vocabulary;       // namespace IRI of the class and its properties
  std::string_view type;             // the class's local name
  std::vector<std::string_view> in;  // signal properties (scalar inputs), kernel order
  std::string_view out;              // the control signal's property (a scalar)
  std::vector<ControllerParameter> parameters;
  // Units: `unit_ports` names signals and Quantity parameters; each row of
  // `units` is one accepted assignment (a QUDT local name per port). Empty:
  // no unit is checked.
  std::vector<std::string_view> unit_ports;
  std::vector<std::vector<std::string_view>> units;
  std::vector<RefusedProperty> refused;
  // Runtime (mospec::runtime): the generated code's spelling.
  std::string_view model_type, spec_type, state_type;  // state_type empty: stateless
  std::string_view kernel;                             // "steps::pid"
  bool kernel_takes_dt = true;
  std::string_view title;    // generated code's comment over the members: "PID controllers"
  std::string_view summary;  // one line: what it computes

  // (internal) builds the runtime model from a spec's values.
  std::unique_ptr<ControllerInstance> (*make)(const ControllerKind&, const std::vector<double>&,
                                              const char* name) = nullptr;
  // (internal) the poles of the loop the kind closes around a plant (see
  // closed_loop_poles below); null when the runtime model declares no linear
  // law (`Transfer transfer(double period) const`): such loops are not judged.
  std::vector<std::complex<double>> (*loop_poles)(const ControllerKind&,
                                                  const std::vector<double>& values, double period,
                                                  const runtime::Transfer& plant) = nullptr;

  bool has_state() const { return !state_type.empty(); }
  std::string class_iri() const { return std::string(vocabulary).append(type); }
  std::string property_iri(std::string_view property) const {
    return std::string(vocabulary).append(property);
  }
  // The parameter whose Spec field is `member`, or -1.
  int parameter(std::string_view member) const;
  // Every parameter's fallback (the runtime Spec's defaults).
  std::vector<double> defaults() const;
  // The runtime model of a spec (values: one per parameter); throws
  // mospec::Error("invalid-controller") naming `name` when the runtime refuses
  // the values (lowering reports it at the controller).
  std::unique_ptr<ControllerInstance> instantiate(const std::vector<double>& values,
                                                  const char* name) const;
  // Whether the loop check can judge the kind's loops (its law is linear).
  bool linear() const { return loop_poles != nullptr; }
  // The closed-loop poles (in z, one sample per `period` [s]) of a controller
  // of this kind with `values`, driving `plant` from its output to its first
  // signal (runtime::closed_loop_poles). Empty when the kind is not linear().
  std::vector<std::complex<double>> closed_loop_poles(const std::vector<double>& values,
                                                      double period,
                                                      const runtime::Transfer& plant) const {
    return loop_poles ? loop_poles(*this, values, period, plant)
                      : std::vector<std::complex<double>>{};
  }
};

// The plant a loop drives, identified from the response of its error to a
// held unit step of its output (runtime::identify_second_order).
inline runtime::IdentifiedPlant identify_loop_plant(const std::vector<double>& step) {
  return runtime::identify_second_order(step);
}

// Every controller kind, in a fixed order (Step::controller indexes it).
std::span<const ControllerKind> controller_kinds();
// The kind named `name` ("pid"), or -1.
int controller_index(std::string_view name);

}  // namespace mospec::ir
