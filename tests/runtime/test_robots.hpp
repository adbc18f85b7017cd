// Small robots and random states shared by the runtime tests.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "runtime/model.hpp"

namespace mospec::runtime::testing {

// A 5-joint toy arm exercising what Gen3 does not: fixed joints at the root, in
// the middle and at the tip (each with mass, each with rotated offsets), a
// prismatic joint, a non-axis-aligned joint axis and rotated <inertial> frames.
inline const std::string kToyUrdf = R"(<robot name="toy">
  <link name="world"/>
  <link name="base"><inertial><origin xyz="0 0 0.05"/><mass value="3"/>
    <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.01"/></inertial></link>
  <joint name="mount" type="fixed"><parent link="world"/><child link="base"/>
    <origin xyz="0.1 -0.2 0.3" rpy="0.1 0.2 0.3"/></joint>
  <link name="l1"><inertial><origin xyz="0.01 0.02 0.1" rpy="0.3 -0.2 0.1"/><mass value="2"/>
    <inertia ixx="0.03" ixy="0.001" ixz="-0.002" iyy="0.025" iyz="0.003" izz="0.01"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.1" rpy="0 0 0.5"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="50" velocity="2"/></joint>
  <link name="l2"><inertial><origin xyz="0 0 0.2"/><mass value="1.5"/>
    <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.004"/></inertial></link>
  <joint name="j2" type="prismatic"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.05 0 0.2" rpy="1.2 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-0.2" upper="0.3" effort="200" velocity="0.5"/></joint>
  <link name="l2b"><inertial><origin xyz="0.03 0 0.01" rpy="0 0.4 0"/><mass value="0.7"/>
    <inertia ixx="0.002" ixy="0" ixz="0" iyy="0.003" iyz="0" izz="0.001"/></inertial></link>
  <joint name="f_mid" type="fixed"><parent link="l2"/><child link="l2b"/>
    <origin xyz="0 0.02 0.3" rpy="-0.4 0.1 0.7"/></joint>
  <link name="l3"><inertial><origin xyz="0.1 0 0" rpy="0 0 0.2"/><mass value="1.1"/>
    <inertia ixx="0.002" ixy="0.0001" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="j3" type="revolute"><parent link="l2b"/><child link="l3"/>
    <origin xyz="0 0 0.05" rpy="0 0 0"/><axis xyz="0 0.6 0.8"/>
    <limit lower="-2" upper="2" effort="30" velocity="2"/></joint>
  <link name="l4"><inertial><origin xyz="0 0 0.05"/><mass value="0.6"/>
    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.0005"/></inertial></link>
  <joint name="j4" type="continuous"><parent link="l3"/><child link="l4"/>
    <origin xyz="0.2 0 0" rpy="0 1.5707963267948966 0"/><axis xyz="1 0 0"/></joint>
  <link name="l5"><inertial><origin xyz="0 0.01 0.03"/><mass value="0.4"/>
    <inertia ixx="0.0005" ixy="0" ixz="0" iyy="0.0005" iyz="0" izz="0.0003"/></inertial></link>
  <joint name="j5" type="revolute"><parent link="l4"/><child link="l5"/>
    <origin xyz="0 0 0.08" rpy="0.3 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="10" velocity="3"/></joint>
  <link name="tool"><inertial><origin xyz="0 0 0.04" rpy="0.5 0.5 0"/><mass value="0.3"/>
    <inertia ixx="0.0002" ixy="0" ixz="0" iyy="0.0003" iyz="0" izz="0.0001"/></inertial></link>
  <joint name="f_tool" type="fixed"><parent link="l5"/><child link="tool"/>
    <origin xyz="0.01 0 0.1" rpy="0 0 1"/></joint>
</robot>
)";

struct RandomState {
  Eigen::VectorXd q, qd, qdd, tau;
  std::vector<Vec6> F_ext;  // per segment, at So_i, in B (mospec's convention)
};

inline RandomState random_state(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> angle(-3.1, 3.1), unit(-1.0, 1.0);
  RandomState s;
  s.q.resize(n);
  s.qd.resize(n);
  s.qdd.resize(n);
  s.tau.resize(n);
  for (int i = 0; i < n; ++i) {
    s.q[i] = angle(rng);
    s.qd[i] = 2.0 * unit(rng);
    s.qdd[i] = 5.0 * unit(rng);
    s.tau[i] = 10.0 * unit(rng);
  }
  s.F_ext.resize(static_cast<std::size_t>(n));
  for (auto& F : s.F_ext) {
    for (int k = 0; k < 3; ++k) F[k] = 2.0 * unit(rng);   // N m
    for (int k = 3; k < 6; ++k) F[k] = 10.0 * unit(rng);  // N
  }
  return s;
}

// nc constraint columns: either nc of the six unit wrenches, or nc orthonormal
// random directions (both are "unit constraint forces").
inline Eigen::Matrix<double, 6, Eigen::Dynamic> random_alpha(std::mt19937& rng, int nc,
                                                             bool axis_aligned) {
  Eigen::Matrix<double, 6, Eigen::Dynamic> alpha(6, nc);
  if (axis_aligned) {
    std::vector<int> idx{0, 1, 2, 3, 4, 5};
    std::shuffle(idx.begin(), idx.end(), rng);
    alpha.setZero();
    for (int c = 0; c < nc; ++c) alpha(idx[static_cast<std::size_t>(c)], c) = 1.0;
  } else {
    std::normal_distribution<double> g;
    Mat6 A;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) A(r, c) = g(rng);
    const Mat6 Q = Eigen::HouseholderQR<Mat6>(A).householderQ();
    alpha = Q.leftCols(nc);
  }
  return alpha;
}

// |a - b| <= tol * max(1, |b|) entrywise, with a readable failure.
template <typename A, typename B>
::testing::AssertionResult near(const A& a, const B& b, double tol) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return ::testing::AssertionFailure()
           << "size " << a.rows() << "x" << a.cols() << " vs " << b.rows() << "x" << b.cols();
  }
  const double scale = std::max(1.0, b.cwiseAbs().maxCoeff());
  const double err = (a - b).cwiseAbs().maxCoeff();
  if (err <= tol * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "max error " << err << " > " << tol << " * " << scale << "\n got:\n"
         << a << "\n want:\n"
         << b;
}

}  // namespace mospec::runtime::testing
