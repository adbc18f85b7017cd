// What a step kind's emit hook (kinds/*.cpp) asks the code generator while it
// builds the step's template section: how a datum, a step's member and an arm
// solver are named in the generated C++, and how a number or model text is
// spelled there. codegen implements it; the names are its decisions, the
// section's fields the kind's.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "ir/ir.hpp"
#include "support/mustache.hpp"

namespace mospec::ir {

// The identifiers of one arm solver's members and functions.
struct ArmNames {
  std::string arm;       // Model: its AchdModel (gravity); Data: its AchdData
  std::string task;      // Model: the AchdModel of the ACHD solve (no gravity)
  std::string X_BR;      // Model: the solver's root R in the chain's root B
  std::string model_fn;  // function: builds the AchdModel for a gravity
  std::string X_RB_fn;   // function: the mount pose
  std::string ws;        // Data: the steps' workspace
};

class EmitContext {
 public:
  virtual ~EmitContext() = default;
  virtual const Program& program() const = 0;
  // The expression naming a datum's slot, e.g. "d.scalar[slot::v_time]".
  virtual std::string ref(int data) const = 0;
  // The member a step owns (an evaluator, a controller's model, a monitor's
  // tolerance; StepKindInfo::member), empty for none.
  virtual const std::string& member(size_t step) const = 0;
  virtual const ArmNames& arm(int solver) const = 0;
  // A double that reads back exactly; model text safe in a // comment.
  virtual std::string number(double value) const = 0;
  virtual std::string comment(std::string_view text) const = 0;

  std::string in(const Step& st, size_t k) const { return ref(st.in[k]); }
  std::string out(const Step& st, size_t k) const { return ref(st.out[k]); }
  const Data& datum(int index) const { return program().data[static_cast<size_t>(index)]; }
};

// Template-data helpers for the emit hooks.
inline mustache::Data list() {
  return mustache::Data::list();
}
inline void put(mustache::Data& object, std::string_view key, mustache::Data value) {
  object.put(key, std::move(value));
}
inline void append(mustache::Data& list, mustache::Data value) {
  list.append(std::move(value));
}
// The expressions of a step's inputs [from, to) joined by `separator`: a gate
// ("a || b") or an argument list ("a, b").
std::string join_inputs(const EmitContext& ctx, const Step& st, size_t from, size_t to,
                        std::string_view separator);

}  // namespace mospec::ir
