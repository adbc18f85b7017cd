// The registry of operator kinds: every pure computation a step can make from
// its inputs (the paper's 3D->1D maps, the pose/twist/wrench algebra), each
// declared once, in operators.cpp, as one table entry:
//
//   name        the IR's name of the kind ("rotate-wrench-to-proximal");
//   vocabulary  the model class it lowers from and the properties that name
//               its inputs and its output, each with its data type;
//   frames      the frame relations between those quantities that the
//               kernel's arithmetic assumes ("to.as-seen-by = pose.of");
//               lowering refuses a model that states other frames;
//   kernel      the mospec::runtime function computing it; the interpreter's
//               call and the generated code's call both derive from it, and the
//               compiler checks the kernel's C++ signature against the
//               declared data types.
//
// Lowering, the verifier, the IR's JSON, the interpreter and codegen read this
// table; none of them lists operators. docs/extending.md walks through adding
// one.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ir/ir.hpp"
#include "runtime/spatial.hpp"

namespace mospec::ir {

// The storage an interpreter keeps: one array per data type, indexed by slot.
struct Slots {
  std::vector<double> scalars;
  std::vector<runtime::Vec3> vec3s;
  std::vector<runtime::Pose> poses;
  std::vector<runtime::Vec6> twists, wrenches;
  std::vector<char> flags, events;
  std::vector<runtime::RigidBodyInertia> inertias;
};

// The frame attributes of a quantity an operator relates (ir::Data's fields).
enum class FrameField : uint8_t { Of, WithRespectTo, ReferencePoint, AsSeenBy };

// "a.field = b.field" or "a.field = origin(b.field)": ports are named by their
// vocabulary property.
struct FrameRule {
  std::string text;  // as declared, for messages
  int lhs_port = 0;  // index: inputs first, then the output
  FrameField lhs_field = FrameField::Of;
  int rhs_port = 0;
  FrameField rhs_field = FrameField::Of;
  bool rhs_origin = false;  // the rhs names a frame; compare with its origin point
};

// Where a port's value comes from.
enum class PortSource : uint8_t {
  Datum,  // the property names a quantity of the model
  Axis,   // the property names an axis (x, y, z of the vocabulary): a unit-vector constant
};

struct OperatorPort {
  std::string_view property;  // local name in the operator's vocabulary namespace
  DataType type = DataType::Scalar;
  PortSource source = PortSource::Datum;
};

struct OperatorKind {
  using Interpret = void (*)(Slots&, const int* in_slots, int out_slot) noexcept;

  std::string_view name;
  std::string_view vocabulary;  // namespace IRI of the class and its properties
  std::string_view type;        // the class's local name
  std::vector<OperatorPort> in;
  OperatorPort out;
  std::vector<FrameRule> frames;
  std::string_view kernel;     // function in mospec::runtime
  bool kernel_returns = true;  // out = kernel(in...) (else kernel(in..., out))
  Interpret interpret = nullptr;
  std::string_view summary;  // one line: what it computes, in which frames
  // Whether lowering maps the class's properties onto the ports one-to-one;
  // false for a kind lowering lowers by hand (an ordered list of inputs).
  bool generic_lowering = true;

  std::string class_iri() const { return std::string(vocabulary).append(type); }
  std::string property_iri(std::string_view property) const {
    return std::string(vocabulary).append(property);
  }
  // The port called `property` (inputs 0..n-1, the output n), or -1.
  int port(std::string_view property) const;
  const OperatorPort& port_at(int index) const {
    return index < static_cast<int>(in.size()) ? in[static_cast<size_t>(index)] : out;
  }
};

// Every operator kind, in a fixed order (Step::op indexes it).
std::span<const OperatorKind> operator_kinds();
// The kind named `name` ("compose-pose"), or -1.
int operator_index(std::string_view name);

std::string_view to_string(FrameField);
// The frame attribute `field` of a quantity (lowering's and the verifier's
// frame rules read it).
const std::string& frame_field(const Data& d, FrameField field);

}  // namespace mospec::ir
