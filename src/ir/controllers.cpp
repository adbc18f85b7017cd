#include "ir/controllers.hpp"

#include <concepts>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "runtime/steps.hpp"
#include "support/diagnostics.hpp"
#include "vocab/metamodels.hpp"

namespace mospec::ir {

namespace {

// A runtime type and its name as generated code spells it (mospec::runtime::).
template <class T>
struct Type {
  std::string_view name;
};
#define MOSPEC_TYPE(T) (Type<::mospec::runtime::T>{#T})
struct NoState {};
constexpr Type<NoState> kStateless{""};

// A field of a Spec (a double or an enum), by member pointer.
template <auto Member>
struct Field;
template <class Spec, class T, T Spec::*Member>
struct Field<Member> {
  using spec_type = Spec;
  static void set(void* spec, double v) {
    if constexpr (std::is_enum_v<T>) {
      static_cast<Spec*>(spec)->*Member = static_cast<T>(static_cast<int>(v));
    } else {
      static_cast<Spec*>(spec)->*Member = v;
    }
  }
  static double get(const Spec& spec) {
    if constexpr (std::is_enum_v<T>) {
      return static_cast<double>(static_cast<int>(spec.*Member));
    } else {
      return spec.*Member;
    }
  }
};

// What a parameter says besides its field.
struct ParameterDecl {
  std::string_view property;
  std::string_view json;
  ParameterSource source = ParameterSource::Fixed;
  bool required = false;
  std::string_view only_with;
  std::string_view enum_type;
  std::vector<std::string_view> enumerators;
  bool new_line = false;
  bool gain = false;
};

template <auto Member>
ControllerParameter parameter(std::string_view member, ParameterDecl d) {
  using F = Field<Member>;
  ControllerParameter p;
  p.member = member;
  p.property = d.property;
  p.json = d.json;
  p.source = d.source;
  p.required = d.required;
  p.only_with = d.only_with;
  p.enum_type = d.enum_type;
  p.enumerators = std::move(d.enumerators);
  p.new_line = d.new_line;
  p.gain = d.gain;
  p.set = &F::set;
  p.fallback = F::get(typename F::spec_type{});
  return p;
}
// A Spec's field, named once: MOSPEC_FIELD(PidSpec, kp, literal(...)).
#define MOSPEC_FIELD(Spec, member, decl) parameter<&::mospec::runtime::Spec::member>(#member, decl)

// An xsd:double literal of the controller, required (only with the class
// `only_with`, when given); written to the IR's JSON as `json`.
ParameterDecl literal(std::string_view property, std::string_view json,
                      std::string_view only_with = {}) {
  ParameterDecl d;
  d.property = property;
  d.json = json;
  d.source = ParameterSource::Literal;
  d.required = true;
  d.only_with = only_with;
  return d;
}
// A loop gain (the loop check wants its sign opposite to d(error)/d(output)).
ParameterDecl gain(ParameterDecl d) {
  d.gain = true;
  return d;
}
// A constant quantity the property names (its value, in its unit).
ParameterDecl quantity(std::string_view property, bool required) {
  ParameterDecl d;
  d.property = property;
  d.json = property;
  d.source = ParameterSource::Quantity;
  d.required = required;
  return d;
}
// Not in the model: the runtime's default.
ParameterDecl fixed(bool new_line = false) {
  ParameterDecl d;
  d.new_line = new_line;
  return d;
}
ParameterDecl fixed_enum(std::string_view type, std::vector<std::string_view> enumerators,
                         bool new_line) {
  ParameterDecl d = fixed(new_line);
  d.enum_type = type;
  d.enumerators = std::move(enumerators);
  return d;
}

struct Declaration {
  std::string_view name, vocabulary, type;
  std::vector<std::string_view> in;
  std::string_view out;
  std::vector<std::string_view> unit_ports;
  std::vector<std::vector<std::string_view>> units;
  std::vector<RefusedProperty> refused;
  std::string_view title, summary;
};

// The interpreter's controller: the runtime model, its state, and the kernel
// called as declared: (model, [state,] inputs..., [dt,] active).
template <class Model, class State, size_t N, class Kernel>
class Instance final : public ControllerInstance {
 public:
  static constexpr bool stateful = !std::is_same_v<State, NoState>;
  template <size_t... I>
  static constexpr bool invocable(bool with_dt, std::index_sequence<I...>) {
    if constexpr (stateful) {
      return with_dt ? std::is_invocable_r_v<double, Kernel, const Model&, State&,
                                             decltype(double(I))..., double, bool>
                     : std::is_invocable_r_v<double, Kernel, const Model&, State&,
                                             decltype(double(I))..., bool>;
    } else {
      return with_dt ? std::is_invocable_r_v<double, Kernel, const Model&, decltype(double(I))...,
                                             double, bool>
                     : std::is_invocable_r_v<double, Kernel, const Model&, decltype(double(I))...,
                                             bool>;
    }
  }
  static constexpr bool takes_dt = invocable(true, std::make_index_sequence<N>{});
  static_assert(takes_dt || invocable(false, std::make_index_sequence<N>{}),
                "the controller kernel must take (model, [state,] inputs..., [dt,] active) and "
                "return the control signal");

  explicit Instance(Model model) : model_(std::move(model)) {}

  double step(const double* in, double dt, bool active) noexcept override {
    return call(in, dt, active, std::make_index_sequence<N>{});
  }

 private:
  template <size_t... I>
  double call(const double* in, [[maybe_unused]] double dt, bool active,
              std::index_sequence<I...>) noexcept {
    if constexpr (stateful && takes_dt) {
      return Kernel{}(model_, state_, in[I]..., dt, active);
    } else if constexpr (stateful) {
      return Kernel{}(model_, state_, in[I]..., active);
    } else if constexpr (takes_dt) {
      return Kernel{}(model_, in[I]..., dt, active);
    } else {
      return Kernel{}(model_, in[I]..., active);
    }
  }

  Model model_;
  [[no_unique_address]] State state_{};
};

template <size_t N, class Model, class Spec, class State, class Kernel>
ControllerKind declare(const Declaration& d, Type<Model> model, Type<Spec> spec, Type<State> state,
                       std::vector<ControllerParameter> parameters, std::string_view kernel,
                       Kernel) {
  using I = Instance<Model, State, N, Kernel>;
  static_assert(N <= kMaxControllerSignals, "raise kMaxControllerSignals");
  if (d.in.size() != N)
    throw std::logic_error("controller '" + std::string(d.name) +
                           "': its signals do not match the declared number of inputs");
  ControllerKind k;
  k.name = d.name;
  k.vocabulary = d.vocabulary;
  k.type = d.type;
  k.in = d.in;
  k.out = d.out;
  k.unit_ports = d.unit_ports;
  k.units = d.units;
  k.refused = d.refused;
  k.title = d.title;
  k.summary = d.summary;
  k.model_type = model.name;
  k.spec_type = spec.name;
  k.state_type = state.name;
  k.kernel = kernel;
  k.kernel_takes_dt = I::takes_dt;
  k.parameters = std::move(parameters);
  k.make = [](const ControllerKind& kind, const std::vector<double>& values,
              const char* name) -> std::unique_ptr<ControllerInstance> {
    if (values.size() != kind.parameters.size())
      throw Error("invalid-controller", std::string(name) + ": " + std::to_string(values.size()) +
                                            " parameters for " + std::string(kind.name) +
                                            ", which has " +
                                            std::to_string(kind.parameters.size()));
    Spec s{};
    for (size_t i = 0; i < values.size(); ++i) kind.parameters[i].set(&s, values[i]);
    return std::make_unique<I>(Model(s, name));
  };
  if constexpr (requires(const Model& m) {
                  { m.transfer(1.0) } -> std::same_as<runtime::Transfer>;
                }) {
    k.loop_poles = [](const ControllerKind& kind, const std::vector<double>& values, double period,
                      const runtime::Transfer& plant) {
      Spec s{};
      for (size_t i = 0; i < values.size() && i < kind.parameters.size(); ++i)
        kind.parameters[i].set(&s, values[i]);
      return runtime::closed_loop_poles(plant,
                                        Model(s, std::string(kind.name).c_str()).transfer(period));
    };
  }
  return k;
}

// A kernel: its name (for generated code) and a call of it (for the
// interpreter), spelled once.
#define MOSPEC_KERNEL(fn)                                             \
#fn, [](auto&&... a) noexcept                                       \
        -> decltype(::mospec::runtime::fn(std::forward <decltype(a)>( \
            a)...)) { return ::mospec::runtime::fn(std::forward<decltype(a)>(a)...); }

constexpr std::string_view kCstrHdl = vocab::cstr_hdl::ns;

std::vector<ControllerKind> declare_all() {
  std::vector<ControllerKind> k;
  // Eq. (4): the paper's PID with a decaying integral term (runtime/controllers.hpp).
  k.push_back(declare<1>(
      {.name = "pid",
       .vocabulary = kCstrHdl,
       .type = "ProportionalIntegralDerivative",
       .in = {"error-signal"},
       .out = "control-signal",
       .unit_ports = {},
       .units = {},
       .refused = {},
       .title = "PID controllers",
       .summary = "Eq. (4): f = Kp e + Ki (the integral of e, decaying at rate lambda) + Kd de/dt"},
      MOSPEC_TYPE(Pid), MOSPEC_TYPE(PidSpec), MOSPEC_TYPE(PidState),
      {
          MOSPEC_FIELD(PidSpec, kp, gain(literal("proportional-gain", "kp"))),
          MOSPEC_FIELD(PidSpec, ki, gain(literal("integral-gain", "ki"))),
          MOSPEC_FIELD(PidSpec, kd, gain(literal("derivative-gain", "kd"))),
          MOSPEC_FIELD(PidSpec, decay_rate,
                       literal("decay-rate", "decay-rate", "DecayingIntegralTerm")),
          MOSPEC_FIELD(PidSpec, output_min, fixed(true)),
          MOSPEC_FIELD(PidSpec, output_max, fixed(true)),
          MOSPEC_FIELD(PidSpec, anti_windup,
                       fixed_enum("AntiWindup",
                                  {"None", "ConditionalIntegration", "BackCalculation"}, true)),
          MOSPEC_FIELD(PidSpec, tracking_rate, fixed()),
      },
      MOSPEC_KERNEL(steps::pid)));
  // The published DampingController: f = clamp(-(F_max / v_max) v, -F_max, F_max).
  k.push_back(declare<1>(
      {.name = "damping",
       .vocabulary = kCstrHdl,
       .type = "DampingController",
       .in = {"measured-velocity"},
       .out = "commanded-force",
       .unit_ports = {"measured-velocity", "maximum-velocity", "maximum-force", "commanded-force"},
       .units = {{"M-PER-SEC", "M-PER-SEC", "N", "N"},
                 {"RAD-PER-SEC", "RAD-PER-SEC", "N-M", "N-M"}},
       .refused = {},
       .title = "Damping controllers",
       .summary = "f = clamp(-(F_max / v_max) v, -F_max, F_max): a saturated linear damper"},
      MOSPEC_TYPE(Damping), MOSPEC_TYPE(DampingSpec), kStateless,
      {
          MOSPEC_FIELD(DampingSpec, maximum_velocity, quantity("maximum-velocity", true)),
          MOSPEC_FIELD(DampingSpec, maximum_force, quantity("maximum-force", true)),
      },
      MOSPEC_KERNEL(steps::damping)));
  // The published ImpedanceController: f = K e + D de/dt.
  k.push_back(declare<1>(
      {.name = "impedance",
       .vocabulary = kCstrHdl,
       .type = "ImpedanceController",
       .in = {"error-signal"},
       .out = "control-signal",
       .unit_ports = {"error-signal", "control-signal", "stiffness", "damping"},
       .units = {{"M", "N", "N-PER-M", "N-SEC-PER-M"},
                 {"RAD", "N-M", "N-M-PER-RAD", "N-M-SEC-PER-RAD"}},
       .refused = {{"inertia", "unsupported-inertia",
                    "an apparent inertia needs the measured contact force (admittance control), "
                    "which an impedance controller's signals (error-signal, control-signal) do "
                    "not carry; remove it, or leave the inertia the robot has"}},
       .title = "Impedance controllers",
       .summary = "f = K e + D de/dt: a spring and a damper on the error"},
      MOSPEC_TYPE(Impedance), MOSPEC_TYPE(ImpedanceSpec), MOSPEC_TYPE(ImpedanceState),
      {
          MOSPEC_FIELD(ImpedanceSpec, stiffness, gain(quantity("stiffness", false))),
          MOSPEC_FIELD(ImpedanceSpec, damping, gain(quantity("damping", false))),
      },
      MOSPEC_KERNEL(steps::impedance)));
  return k;
}

#undef MOSPEC_KERNEL
#undef MOSPEC_FIELD
#undef MOSPEC_TYPE

}  // namespace

int ControllerKind::parameter(std::string_view member) const {
  for (size_t i = 0; i < parameters.size(); ++i) {
    if (parameters[i].member == member) return static_cast<int>(i);
  }
  return -1;
}

std::vector<double> ControllerKind::defaults() const {
  std::vector<double> out;
  for (const ControllerParameter& p : parameters) out.push_back(p.fallback);
  return out;
}

std::unique_ptr<ControllerInstance> ControllerKind::instantiate(const std::vector<double>& values,
                                                                const char* name) const {
  return make(*this, values, name);
}

std::span<const ControllerKind> controller_kinds() {
  static const std::vector<ControllerKind> kinds = declare_all();
  return kinds;
}

int controller_index(std::string_view name) {
  const auto kinds = controller_kinds();
  for (size_t i = 0; i < kinds.size(); ++i) {
    if (kinds[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace mospec::ir
