// Runtime solver timings: mospec's ACHD against KDL's ChainHdSolver_Vereshchagin
// on the same problem (Kinova Gen3, 5 end-effector constraints, random state
// with external wrenches and feed-forward torques), plus the other algorithms.
// Each benchmark repeats 10 times and reports mean/median/stddev; compare medians.
#include <benchmark/benchmark.h>

#include <kdl/chainhdsolver_vereshchagin.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <random>

#include "description/urdf_import.hpp"
#include "kdl_reference.hpp"
#include "runtime/achd.hpp"
#include "runtime/crba.hpp"
#include "runtime/kinematics.hpp"
#include "runtime/rne.hpp"
#include "test_robots.hpp"

namespace {

using namespace mospec::runtime;
using mospec::description::chain_from_urdf_file;
namespace tst = mospec::runtime::testing;

struct Problem {
  Chain chain;
  KDL::Chain kdl;
  tst::RandomState s;
  Eigen::Matrix<double, 6, Eigen::Dynamic> alpha;
  Eigen::VectorXd beta;
};

const Problem* problem() {
  static const Problem* p = []() -> const Problem* {
    const std::string path = tst::gen3_urdf_path();
    if (path.empty()) return nullptr;
    std::mt19937 rng(2024);
    auto* out = new Problem{chain_from_urdf_file(path, tst::kGen3Root, tst::kGen3Tip),
                            tst::fold_fixed_segments(tst::kdl_chain(
                                tst::kdl_tree_from_urdf_file(path), tst::kGen3Root, tst::kGen3Tip)),
                            {},
                            {},
                            {}};
    out->s = tst::random_state(rng, out->chain.size());
    out->alpha = tst::random_alpha(rng, 5, false);
    out->beta = Eigen::VectorXd::LinSpaced(5, -1.0, 1.0);
    return out;
  }();
  return p;
}

#define NEED_PROBLEM(state)                                                                \
  const Problem* p = problem();                                                            \
  if (p == nullptr) {                                                                      \
    state.SkipWithError("needs " MOSPEC_SHARED_DIR "/upstream/kinova/GEN3_URDF_V12.urdf"); \
    return;                                                                                \
  }

void achd_mospec(benchmark::State& state) {
  NEED_PROBLEM(state);
  const AchdModel model(p->chain);
  AchdData data(model);
  JointVector q = p->s.q;
  for (auto _ : state) {
    q[0] += 1e-9;  // keep the compiler from hoisting anything
    benchmark::DoNotOptimize(
        achd(model, data, q, p->s.qd, p->s.tau, p->s.F_ext, p->alpha, p->beta));
    benchmark::DoNotOptimize(data.qdd.data());
  }
}

void achd_kdl(benchmark::State& state) {
  NEED_PROBLEM(state);
  const unsigned n = p->kdl.getNrOfJoints(), nc = 5;
  KDL::ChainHdSolver_Vereshchagin solver(
      p->kdl, KDL::Twist(KDL::Vector(0, 0, 9.81), KDL::Vector::Zero()), nc);
  KDL::JntArray q = tst::to_kdl(p->s.q), qd = tst::to_kdl(p->s.qd), ff = tst::to_kdl(p->s.tau),
                qdd(n), tc(n), beta(nc);
  KDL::Jacobian alpha(nc);
  alpha.data.topRows(3) = p->alpha.bottomRows(3);
  alpha.data.bottomRows(3) = p->alpha.topRows(3);
  beta.data = p->beta;
  // Same wrenches; the reference-point shift on the last segment does not
  // change the cost.
  KDL::Wrenches f_ext;
  for (const Vec6& F : p->s.F_ext) f_ext.push_back(tst::to_kdl_wrench(F));
  for (auto _ : state) {
    q(0) += 1e-9;
    benchmark::DoNotOptimize(solver.CartToJnt(q, qd, qdd, alpha, beta, f_ext, ff, tc));
    benchmark::DoNotOptimize(qdd.data.data());
  }
}

void rne_mospec(benchmark::State& state) {
  NEED_PROBLEM(state);
  const AchdModel model(p->chain);
  AchdData data(model);
  JointVector q = p->s.q;
  for (auto _ : state) {
    q[0] += 1e-9;
    benchmark::DoNotOptimize(rne(model, data, q, p->s.qd, p->s.qdd, p->s.F_ext));
    benchmark::DoNotOptimize(data.tau.data());
  }
}

void rne_kdl(benchmark::State& state) {
  NEED_PROBLEM(state);
  const unsigned n = p->kdl.getNrOfJoints();
  KDL::ChainIdSolver_RNE solver(p->kdl, KDL::Vector(0, 0, -9.81));
  KDL::JntArray q = tst::to_kdl(p->s.q), qd = tst::to_kdl(p->s.qd), qdd = tst::to_kdl(p->s.qdd),
                tau(n);
  KDL::Wrenches f_ext;
  for (const Vec6& F : p->s.F_ext) f_ext.push_back(tst::to_kdl_wrench(F));
  for (auto _ : state) {
    q(0) += 1e-9;
    benchmark::DoNotOptimize(solver.CartToJnt(q, qd, qdd, f_ext, tau));
    benchmark::DoNotOptimize(tau.data.data());
  }
}

void fd_mospec(benchmark::State& state) {
  NEED_PROBLEM(state);
  const AchdModel model(p->chain);
  AchdData data(model);
  JointVector q = p->s.q;
  for (auto _ : state) {
    q[0] += 1e-9;
    benchmark::DoNotOptimize(forward_dynamics(model, data, q, p->s.qd, p->s.tau, p->s.F_ext));
    benchmark::DoNotOptimize(data.qdd.data());
  }
}

void register_all() {
  for (auto [name, fn] :
       {std::pair{"BM_Achd/mospec", &achd_mospec}, std::pair{"BM_Achd/kdl", &achd_kdl},
        std::pair{"BM_Rne/mospec", &rne_mospec}, std::pair{"BM_Rne/kdl", &rne_kdl},
        std::pair{"BM_ForwardDynamicsCrba/mospec", &fd_mospec}}) {
    benchmark::RegisterBenchmark(name, fn)->Repetitions(10)->ReportAggregatesOnly(true)->Unit(
        benchmark::kNanosecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
