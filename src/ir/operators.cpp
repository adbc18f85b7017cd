#include "ir/operators.hpp"

#include <stdexcept>
#include <type_traits>
#include <utility>

#include "runtime/operators.hpp"
#include "vocab/metamodels.hpp"

namespace mospec::ir {

namespace {

// The C++ type and storage of each data type an operator can take or give.
template <class Cpp, DataType D, std::vector<Cpp> Slots::*member, PortSource S = PortSource::Datum>
struct SlotType {
  using cpp = Cpp;
  static constexpr DataType type = D;
  static constexpr PortSource source = S;
  static Cpp& at(Slots& s, int i) { return (s.*member)[static_cast<size_t>(i)]; }
};
namespace t {
using Scalar = SlotType<double, DataType::Scalar, &Slots::scalars>;
using Vector3 = SlotType<runtime::Vec3, DataType::Vector3, &Slots::vec3s>;
// An axis the model names (x, y or z): a unit-vector constant.
using Axis = SlotType<runtime::Vec3, DataType::Vector3, &Slots::vec3s, PortSource::Axis>;
using Pose = SlotType<runtime::Pose, DataType::Pose, &Slots::poses>;
using Twist = SlotType<runtime::Vec6, DataType::Twist, &Slots::twists>;
using Wrench = SlotType<runtime::Vec6, DataType::Wrench, &Slots::wrenches>;
using Inertia = SlotType<runtime::RigidBodyInertia, DataType::Inertia, &Slots::inertias>;
}  // namespace t

// The interpreter's call of a kernel, derived from the declared signature
// Out(In...): the kernel either returns the output or writes it through a
// last reference parameter; anything else does not compile.
template <class Sig, class Kernel>
struct Call;
template <class Out, class... In, class Kernel>
struct Call<Out(In...), Kernel> {
  static constexpr bool returns =
      std::is_invocable_r_v<typename Out::cpp, Kernel, const typename In::cpp&...>;
  static_assert(returns ||
                    std::is_invocable_v<Kernel, const typename In::cpp&..., typename Out::cpp&>,
                "the kernel's parameters do not match the operator's declared data types");

  static void run(Slots& s, const int* in, int out) noexcept {
    run(s, in, out, std::index_sequence_for<In...>{});
  }
  template <size_t... I>
  static void run(Slots& s, const int* in, int out, std::index_sequence<I...>) noexcept {
    if constexpr (returns) {
      Out::at(s, out) = Kernel{}(std::as_const(In::at(s, in[I]))...);
    } else {
      Kernel{}(std::as_const(In::at(s, in[I]))..., Out::at(s, out));
    }
  }
};

FrameField field(std::string_view name, const std::string& rule) {
  if (name == "of") return FrameField::Of;
  if (name == "with-respect-to") return FrameField::WithRespectTo;
  if (name == "reference-point") return FrameField::ReferencePoint;
  if (name == "as-seen-by") return FrameField::AsSeenBy;
  throw std::logic_error("operator frame rule '" + rule + "': no frame field '" +
                         std::string(name) + "'");
}

// "port.field" -> (port index, field).
std::pair<int, FrameField> operand(const OperatorKind& k, std::string_view text,
                                   const std::string& rule) {
  const size_t dot = text.find('.');
  const int port = dot == std::string_view::npos ? -1 : k.port(text.substr(0, dot));
  if (port < 0)
    throw std::logic_error("operator frame rule '" + rule + "' of '" + std::string(k.name) +
                           "': no port '" + std::string(text.substr(0, dot)) + "'");
  return {port, field(text.substr(dot + 1), rule)};
}

FrameRule parse_rule(const OperatorKind& k, std::string_view text) {
  FrameRule r;
  r.text = text;
  const size_t eq = text.find(" = ");
  if (eq == std::string_view::npos)
    throw std::logic_error("operator frame rule '" + r.text + "': expected 'a.f = b.f'");
  std::string_view rhs = text.substr(eq + 3);
  if (rhs.starts_with("origin(") && rhs.ends_with(")")) {
    r.rhs_origin = true;
    rhs = rhs.substr(7, rhs.size() - 8);
  }
  std::tie(r.lhs_port, r.lhs_field) = operand(k, text.substr(0, eq), r.text);
  std::tie(r.rhs_port, r.rhs_field) = operand(k, rhs, r.text);
  return r;
}

struct Declaration {
  std::string_view name, vocabulary, type;
  std::vector<std::string_view> in;
  std::string_view out;
  std::vector<std::string_view> frames;
  std::string_view summary;
  // false: the class's properties do not map one-to-one onto the ports
  // (PlanarAngleFromDirections' ordered list); lower_operators.cpp lowers it by hand.
  bool generic_lowering = true;
};

template <class Sig, class Kernel>
struct Ports;
template <class Out, class... In, class Kernel>
struct Ports<Out(In...), Kernel> {
  static OperatorKind make(const Declaration& d, std::string_view kernel) {
    if (d.in.size() != sizeof...(In))
      throw std::logic_error("operator '" + std::string(d.name) +
                             "': properties do not match the signature");
    OperatorKind k;
    k.name = d.name;
    k.vocabulary = d.vocabulary;
    k.type = d.type;
    const DataType types[] = {In::type..., DataType::Scalar};
    const PortSource sources[] = {In::source..., PortSource::Datum};
    for (size_t i = 0; i < d.in.size(); ++i) k.in.push_back({d.in[i], types[i], sources[i]});
    k.out = {d.out, Out::type, Out::source};
    k.kernel = kernel;
    k.kernel_returns = Call<Out(In...), Kernel>::returns;
    k.interpret = &Call<Out(In...), Kernel>::run;
    k.summary = d.summary;
    k.generic_lowering = d.generic_lowering;
    for (std::string_view f : d.frames) k.frames.push_back(parse_rule(k, f));
    return k;
  }
};

template <class Sig, class Kernel>
OperatorKind declare(const Declaration& d, std::string_view kernel, Kernel) {
  return Ports<Sig, Kernel>::make(d, kernel);
}

// A kernel: its name (for generated code) and a call of it (for the
// interpreter), spelled once.
#define MOSPEC_KERNEL(fn)                                             \
#fn, [](auto&&... a) noexcept                                       \
        -> decltype(::mospec::runtime::fn(std::forward <decltype(a)>( \
            a)...)) { return ::mospec::runtime::fn(std::forward<decltype(a)>(a)...); }

constexpr std::string_view kGeomOp = vocab::geom_op::ns;
constexpr std::string_view kDynOp = vocab::dyn_op::ns;

// The pose operators, and those of directions and angles.
void declare_poses(std::vector<OperatorKind>& k) {
  // --- poses ----------------------------------------------------------------
  k.push_back(
      declare<t::Pose(t::Pose, t::Pose)>({"compose-pose",
                                          kGeomOp,
                                          "ComposePose",
                                          {"in1", "in2"},
                                          "composite",
                                          {"in1.of = in2.with-respect-to", "composite.of = in2.of",
                                           "composite.with-respect-to = in1.with-respect-to"},
                                          "X_AC = X_AB X_BC"},
                                         MOSPEC_KERNEL(compose_pose)));
  k.push_back(declare<t::Scalar(t::Pose)>(
      {"pose-to-linear-distance",
       kGeomOp,
       "PoseToLinearDistance",
       {"pose"},
       "distance",
       {},
       "|p_AoBo|, the distance between the origins of the pose's frames"},
      MOSPEC_KERNEL(pose_to_linear_distance)));
  k.push_back(declare<t::Vector3(t::Pose)>(
      {"pose-to-direction",
       kGeomOp,
       "PoseToDirection",
       {"pose"},
       "direction",
       {"direction.as-seen-by = pose.as-seen-by"},
       "the unit vector from Ao towards Bo, seen by A (0 when they coincide)"},
      MOSPEC_KERNEL(pose_to_direction)));
  k.push_back(declare<t::Scalar(t::Pose, t::Axis)>(
      {"pose-to-angle-around-axis",
       kGeomOp,
       "PoseToAngleAroundAxis",
       {"pose", "axis"},
       "angle",
       {},
       "the angle (-pi, pi] by which X_AB turns about the axis x, y or z (the twist part)"},
      MOSPEC_KERNEL(pose_to_angle_around_axis)));
  // --- directions and angles --------------------------------------------------
  k.push_back(declare<t::Vector3(t::Pose, t::Vector3)>(
      {"rotate-direction-to-proximal",
       kGeomOp,
       "RotateDirectionDistalToProximalWithPose",
       {"pose", "from"},
       "to",
       {"from.as-seen-by = pose.of", "to.as-seen-by = pose.with-respect-to"},
       "d_A = R_AB d_B"},
      MOSPEC_KERNEL(rotate_direction_to_proximal)));
  k.push_back(declare<t::Scalar(t::Vector3, t::Vector3, t::Vector3)>(
      {"planar-angle-from-directions",
       kGeomOp,
       "PlanarAngleFromDirections",
       {"first-direction", "second-direction", "normal"},
       "angle",
       {},
       "the signed angle from d1 to d2 about the z axis of the frame both are seen by",
       /*generic_lowering=*/false},
      MOSPEC_KERNEL(planar_angle_from_directions)));
  k.push_back(declare<t::Scalar(t::Scalar)>(
      {"invert-angle", kGeomOp, "InvertAngle", {"in"}, "out", {}, "-angle"},
      MOSPEC_KERNEL(invert_angle)));
}

// The twist operators.
void declare_twists(std::vector<OperatorKind>& k) {
  // --- twists -----------------------------------------------------------------
  k.push_back(declare<t::Twist(t::Pose, t::Twist)>(
      {"rotate-twist-to-proximal",
       kGeomOp,
       "RotateVelocityTwistToProximalWithPose",
       {"pose", "from"},
       "to",
       {"from.as-seen-by = pose.of", "to.as-seen-by = pose.with-respect-to", "to.of = from.of",
        "to.with-respect-to = from.with-respect-to", "to.reference-point = from.reference-point"},
       "the same twist at the same point, seen by A instead of B"},
      MOSPEC_KERNEL(rotate_twist_to_proximal)));
  k.push_back(declare<t::Twist(t::Pose, t::Twist)>(
      {"transform-twist-to-distal",
       kGeomOp,
       "TransformVelocityTwistToDistal",
       {"pose", "from"},
       "to",
       {"from.as-seen-by = pose.with-respect-to",
        "from.reference-point = origin(pose.with-respect-to)", "to.as-seen-by = pose.of",
        "to.reference-point = origin(pose.of)", "to.of = from.of",
        "to.with-respect-to = from.with-respect-to"},
       "the same twist, moved from Ao seen by A to Bo seen by B"},
      MOSPEC_KERNEL(transform_twist_to_distal)));
  k.push_back(declare<t::Twist(t::Twist, t::Twist)>(
      {"add-velocity-twist",
       kGeomOp,
       "AddVelocityTwist",
       {"in1", "in2"},
       "composite",
       {"in1.of = in2.with-respect-to", "composite.of = in2.of",
        "composite.with-respect-to = in1.with-respect-to",
        "in2.reference-point = in1.reference-point",
        "composite.reference-point = in1.reference-point", "in2.as-seen-by = in1.as-seen-by",
        "composite.as-seen-by = in1.as-seen-by"},
       "V_CA = V_BA + V_CB, at one point, seen by one frame"},
      MOSPEC_KERNEL(add_velocity_twist)));
}

// The wrench operators moving a wrench between frames.
void declare_wrench_transforms(std::vector<OperatorKind>& k) {
  // --- wrenches ---------------------------------------------------------------
  k.push_back(declare<t::Wrench(t::Pose, t::Wrench)>(
      {"rotate-wrench-to-proximal",
       kDynOp,
       "RotateWrenchToProximalWithPose",
       {"pose", "from"},
       "to",
       {"from.as-seen-by = pose.of", "to.as-seen-by = pose.with-respect-to",
        "to.reference-point = from.reference-point"},
       "the same wrench about the same point, seen by A instead of B"},
      MOSPEC_KERNEL(rotate_wrench_to_proximal)));
  k.push_back(declare<t::Wrench(t::Pose, t::Wrench)>(
      {"rotate-wrench-to-distal",
       kDynOp,
       "RotateWrenchToDistalWithPose",
       {"pose", "from"},
       "to",
       {"from.as-seen-by = pose.with-respect-to", "to.as-seen-by = pose.of",
        "to.reference-point = from.reference-point"},
       "the same wrench about the same point, seen by B instead of A"},
      MOSPEC_KERNEL(rotate_wrench_to_distal)));
  k.push_back(declare<t::Wrench(t::Pose, t::Wrench)>(
      {"transform-wrench-to-proximal",
       kDynOp,
       "TransformWrenchToProximal",
       {"pose", "from"},
       "to",
       {"from.as-seen-by = pose.of", "from.reference-point = origin(pose.of)",
        "to.as-seen-by = pose.with-respect-to",
        "to.reference-point = origin(pose.with-respect-to)"},
       "the same wrench, moved from about Bo seen by B to about Ao seen by A"},
      MOSPEC_KERNEL(transform_wrench_to_proximal)));
}

// The wrench operators building, adding, inverting and copying wrenches.
void declare_wrench_arithmetic(std::vector<OperatorKind>& k) {
  k.push_back(declare<t::Wrench(t::Vector3, t::Vector3, t::Scalar)>(
      {"wrench-from-position-direction-and-magnitude",
       kDynOp,
       "WrenchFromPositionDirectionAndMagnitude",
       {"position", "direction", "magnitude"},
       "wrench",
       {"direction.as-seen-by = position.as-seen-by", "wrench.as-seen-by = position.as-seen-by"},
       "Eq. (1): F = [p x (f d); f d]"},
      MOSPEC_KERNEL(wrench_from_position_direction_and_magnitude)));
  k.push_back(declare<t::Wrench(t::Wrench, t::Wrench)>(
      {"add-wrench",
       kDynOp,
       "AddWrench",
       {"in1", "in2"},
       "out",
       {"in2.reference-point = in1.reference-point", "in2.as-seen-by = in1.as-seen-by",
        "out.reference-point = in1.reference-point", "out.as-seen-by = in1.as-seen-by"},
       "F1 + F2, about one point, seen by one frame"},
      MOSPEC_KERNEL(add_wrench)));
  k.push_back(declare<t::Wrench(t::Wrench)>(
      {"invert-wrench",
       kDynOp,
       "InvertWrench",
       {"from"},
       "to",
       {"to.reference-point = from.reference-point", "to.as-seen-by = from.as-seen-by"},
       "-F"},
      MOSPEC_KERNEL(invert_wrench)));
  k.push_back(declare<t::Wrench(t::Wrench)>(
      {"assign-wrench",
       kDynOp,
       "AssignWrench",
       {"from"},
       "to",
       {"to.reference-point = from.reference-point", "to.as-seen-by = from.as-seen-by"},
       "a copy of F"},
      MOSPEC_KERNEL(assign_wrench)));
  k.push_back(declare<t::Wrench(t::Inertia, t::Twist)>(
      {"inertial-wrench",
       kDynOp,
       "InertialWrench",
       {"rigid-body-inertia", "velocity-twist"},
       "wrench",
       {"velocity-twist.reference-point = rigid-body-inertia.reference-point",
        "velocity-twist.as-seen-by = rigid-body-inertia.as-seen-by",
        "wrench.reference-point = rigid-body-inertia.reference-point",
        "wrench.as-seen-by = rigid-body-inertia.as-seen-by"},
       "V x* (M V): the velocity-product (Coriolis, centripetal) wrench of a body of inertia M "
       "moving with twist V, about M's point, seen by M's frame"},
      MOSPEC_KERNEL(inertial_wrench)));
}

// The registry, in the order operator indices follow.
std::vector<OperatorKind> declare_all() {
  std::vector<OperatorKind> k;
  declare_poses(k);
  declare_twists(k);
  declare_wrench_transforms(k);
  declare_wrench_arithmetic(k);
  return k;
}

#undef MOSPEC_KERNEL

}  // namespace

int OperatorKind::port(std::string_view property) const {
  for (size_t i = 0; i < in.size(); ++i) {
    if (in[i].property == property) return static_cast<int>(i);
  }
  return out.property == property ? static_cast<int>(in.size()) : -1;
}

std::span<const OperatorKind> operator_kinds() {
  static const std::vector<OperatorKind> kinds = declare_all();
  return kinds;
}

int operator_index(std::string_view name) {
  const auto kinds = operator_kinds();
  for (size_t i = 0; i < kinds.size(); ++i) {
    if (kinds[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

std::string_view to_string(FrameField f) {
  switch (f) {
    case FrameField::Of:
      return "of";
    case FrameField::WithRespectTo:
      return "with-respect-to";
    case FrameField::ReferencePoint:
      return "reference-point";
    case FrameField::AsSeenBy:
      return "as-seen-by";
  }
  return "?";
}

const std::string& frame_field(const Data& d, FrameField field) {
  switch (field) {
    case FrameField::Of:
      return d.of;
    case FrameField::WithRespectTo:
      return d.with_respect_to;
    case FrameField::ReferencePoint:
      return d.reference_point;
    case FrameField::AsSeenBy:
      break;
  }
  return d.as_seen_by;
}

}  // namespace mospec::ir
