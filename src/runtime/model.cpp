#include "runtime/model.hpp"

#include "support/diagnostics.hpp"

namespace mospec::runtime {

std::string_view to_string(Status s) {
  switch (s) {
    case Status::Ok:
      return "ok";
    case Status::ConstraintsDegraded:
      return "constraint coupling matrix singular: lost constraint directions dropped";
    case Status::SizeMismatch:
      return "argument size does not match the model";
  }
  return "unknown status";
}

AchdModel::AchdModel(const Chain& chain, const Vec3& g_B_in) : nq(chain.size()), g_B(g_B_in) {
  if (nq == 0) {
    throw Error("invalid-chain", "chain rooted at '" + chain.root() + "' has no moving joints");
  }
  if (!g_B.allFinite()) throw Error("invalid-chain", "gravity must be finite");
  for (int i = 0; i < nq; ++i) {
    const Segment& s = chain.segment(i);
    SegmentModel& m = segments[static_cast<std::size_t>(i)];
    m.type = s.type;
    m.X_PJ = s.X_PJ;
    m.axis = s.axis_J;
    m.I_So_S = s.inertia.spatial();
    m.armature = s.armature;
    for (int k = 0; k < 3; ++k) {
      if (m.axis == Vec3::Unit(k)) m.unit_axis = k;
    }
  }
  X_NT = chain.X_NT();
}

AchdData::AchdData(const AchdModel& model) : nq(model.nq) {
  // Size everything once; later resizes stay within the fixed capacity and so
  // never allocate.
  J_To_B.setZero(6, nq);
  for (auto& e : E) e.setZero(6, 0);
  for (auto& e : EZ) e.setZero(0);
  E_base.setZero(6, 0);
  alpha_No_N.setZero(6, 0);
  M.setZero(0, 0);
  G.setZero(0);
  rhs.setZero(0);
  qdd.setZero(nq);
  tau.setZero(nq);
  nu.setZero(0);
  H.setZero(nq, nq);
  bias.setZero(nq);
}

}  // namespace mospec::runtime
