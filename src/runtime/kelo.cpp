#include "runtime/kelo.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>

#include "runtime/operators.hpp"
#include "support/diagnostics.hpp"

namespace mospec::runtime {
namespace {

[[noreturn]] void reject(const std::string& what) {
  throw Error("invalid-kelo", "KELO base: " + what);
}

void require_positive(const char* field, double v) {
  if (!(v > 0.0) || !std::isfinite(v)) {
    reject(std::string(field) + " must be finite and > 0, got " + exact_number(v));
  }
}

void require_weight(const char* field, int i, double v) {
  if (!(v >= 0.0) || !std::isfinite(v)) {
    reject(std::string(field) + " of drive " + std::to_string(i) +
           " must be finite and >= 0, got " + exact_number(v));
  }
}

// The tick's products over the drive count: compiled with fixed sizes for the
// paper's four-drive base (unrolled, as fast as when four was the only count)
// and with runtime sizes for every other count. Both views read and write
// KeloData's own storage, whose column-major layout for a runtime size of n
// drives is exactly that of the fixed-size matrices.
template <int N>
struct Sized {
  static constexpr int M = N == Eigen::Dynamic ? Eigen::Dynamic : 2 * N;
  using Drive = Eigen::Map<Eigen::Matrix<double, M, 1>>;
  using ConstDrive = Eigen::Map<const Eigen::Matrix<double, M, 1>>;
  using Composition = Eigen::Map<Eigen::Matrix<double, 3, M>>;
  using ConstComposition = Eigen::Map<const Eigen::Matrix<double, 3, M>>;
  using Distribution = Eigen::Map<Eigen::Matrix<double, M, 3>>;
  using ConstDistribution = Eigen::Map<const Eigen::Matrix<double, M, 3>>;
  // A 2n x 3 value (no allocation either way): the right-hand side of the
  // solve below is faster as a plain matrix than as a view.
  using DistributionValue =
      std::conditional_t<N == Eigen::Dynamic, KeloDistribution, Eigen::Matrix<double, M, 3>>;
};

// Runs `kernel.template operator()<N>()` with N = 4 for a four-drive base, else
// Eigen::Dynamic.
template <class Kernel>
decltype(auto) for_drive_count(int drives, Kernel&& kernel) {
  if (drives == 4) return kernel.template operator()<4>();
  return kernel.template operator()<Eigen::Dynamic>();
}

template <int N>
void set_pivots_sized(const KeloModel& model, KeloData& data) noexcept {
  using S = Sized<N>;
  const int m = 2 * model.drives;
  typename S::Composition G(data.G.data(), 3, m);
  for (int i = 0; i < model.drives; ++i) {
    const double c = std::cos(data.q_pivot[i]), s = std::sin(data.q_pivot[i]);
    const double x = model.config.geometry.p_PoAi_P[static_cast<size_t>(i)].x();
    const double y = model.config.geometry.p_PoAi_P[static_cast<size_t>(i)].y();
    G.col(2 * i) << c, s, x * s - y * c;
    G.col(2 * i + 1) << -s, c, x * c + y * s;
  }
  // W^{-1} G^T (2n x 3), then (G W^{-1} G^T) and G⁺ = W^{-1} G^T (G W^{-1} G^T)^{-1}.
  const typename S::DistributionValue WinvGt =
      typename S::ConstDrive(model.w_inv.data(), m).asDiagonal() * G.transpose();
  const Mat3 GWGt = G * WinvGt;
  data.llt_GWGt.compute(GWGt);
  const typename S::DistributionValue G_pinv = data.llt_GWGt.solve(WinvGt.transpose()).transpose();
  typename S::Distribution(data.G_pinv.data(), m, 3) = G_pinv;
}

template <int N>
void distribute_sized(const KeloModel& model, KeloData& data, const Vec3& F_p) noexcept {
  using S = Sized<N>;
  const int m = 2 * model.drives;
  const typename S::ConstComposition G(data.G.data(), 3, m);
  const typename S::ConstDistribution G_pinv(data.G_pinv.data(), m, 3);
  const typename S::ConstDrive ref(data.ref.data(), m);
  typename S::Drive F_d_null(data.F_d_null.data(), m);
  typename S::Drive F_d(data.F_d.data(), m);
  // N F̄ = F̄ - G⁺ (G F̄), without forming the 2n x 2n N.
  const Vec3 G_ref = G * ref;
  F_d_null.noalias() = ref - G_pinv * G_ref;

  if (model.config.rescale_reference) {
    double max_ref = 0.0, max_null = 0.0;
    for (int i = 0; i < model.drives; ++i) {
      max_ref = std::max(max_ref, ref.template segment<2>(2 * i).norm());
      max_null = std::max(max_null, F_d_null.template segment<2>(2 * i).norm());
    }
    data.alpha = max_null > 1e-9 * max_ref ? max_ref / max_null : 0.0;
  } else {
    data.alpha = 1.0;
  }
  F_d.noalias() = G_pinv * F_p;
  F_d += data.alpha * F_d_null;
}

}  // namespace

KeloModel::KeloModel(const KeloConfig& c) : config(c) {
  const KeloGeometry& g = c.geometry;
  require_positive("wheel radius", g.wheel_radius);
  require_positive("wheel distance", g.wheel_distance);
  require_positive("castor offset", g.castor_offset);
  wheel_radius = g.wheel_radius;
  lateral_ratio = g.wheel_distance / (2.0 * g.castor_offset);
  const size_t n = g.p_PoAi_P.size();
  if (n < 2 || n > static_cast<size_t>(kMaxKeloDrives)) {
    reject("it has " + std::to_string(n) + " drives; mospec's base has 2 to " +
           std::to_string(kMaxKeloDrives));
  }
  if (c.drive_weight.size() != n || c.align_force_weight.size() != n ||
      c.align_moment_weight.size() != n) {
    reject("the drive, force-alignment and moment-alignment weights need one entry per drive (" +
           std::to_string(n) + ")");
  }
  drives = static_cast<int>(n);
  w_inv = KeloDriveVector::Zero(2 * drives);
  int first = -1;
  bool two_distinct = false;
  for (size_t i = 0; i < n; ++i) {
    if (!g.p_PoAi_P[i].allFinite()) {
      reject("pivot position of drive " + std::to_string(i) + " must be finite");
    }
    const int d = static_cast<int>(i);
    require_weight("drive weight", d, c.drive_weight[i]);
    require_weight("force-alignment weight", d, c.align_force_weight[i]);
    require_weight("moment-alignment weight", d, c.align_moment_weight[i]);
    if (c.align_moment_weight[i] > 0.0 && !(g.p_PoAi_P[i].norm() > 0.0)) {
      reject("drive " + std::to_string(i) +
             " is at the platform centre, so it cannot align with the moment; set its "
             "moment-alignment weight to 0");
    }
    enabled[i] = c.drive_weight[i] > 0.0;
    w_inv[2 * d] = w_inv[2 * d + 1] = c.drive_weight[i];
    if (!enabled[i]) continue;
    if (first < 0) {
      first = d;
    } else if ((g.p_PoAi_P[i] - g.p_PoAi_P[static_cast<size_t>(first)]).norm() > 1e-6) {
      two_distinct = true;
    }
  }
  if (!two_distinct) {
    reject(
        "at least two enabled drives (drive weight > 0) at distinct pivot positions are "
        "needed to produce every platform wrench");
  }
}

KeloData::KeloData(const KeloModel& model) {
  const int n = model.drives, m = 2 * model.drives;
  q_pivot = KeloPivotVector::Zero(n);
  qd_pivot = KeloPivotVector::Zero(n);
  G = KeloComposition::Zero(3, m);
  G_pinv = KeloDistribution::Zero(m, 3);
  for (KeloDriveVector* v :
       {&F_d_ref, &ref, &F_d_null, &F_d, &f_wheel, &tau_wheel, &u_pivot, &wheel_rates}) {
    *v = KeloDriveVector::Zero(m);
  }
  // A valid G W^{-1} G^T to start from: the one at zero pivot angles.
  kelo_set_pivots(model, *this, KeloPivotVector::Zero(n));
}

const KeloComposition& kelo_set_pivots(const KeloModel& model, KeloData& data,
                                       const KeloPivotVector& q_pivot) noexcept {
  data.q_pivot = q_pivot;
  for_drive_count(model.drives, [&]<int N>() { set_pivots_sized<N>(model, data); });
  return data.G;
}

const KeloDriveVector& kelo_alignment_reference(const KeloModel& model, KeloData& data,
                                                const Vec3& F_p) noexcept {
  const double f = std::hypot(F_p[0], F_p[1]);
  const double m = F_p[2];
  const double force_heading = std::atan2(F_p[1], F_p[0]);
  for (int i = 0; i < model.drives; ++i) {
    data.F_d_ref[2 * i] = 0.0;
    data.F_d_ref[2 * i + 1] = 0.0;
    if (!model.enabled[i]) continue;
    const double q = data.q_pivot[i];
    double lateral = 0.0;
    if (f > 0.0) {
      lateral += model.config.align_force_weight[i] * f * wrap_angle(force_heading - q);
    }
    const Vec2& p = model.config.geometry.p_PoAi_P[i];
    if (m != 0.0 && model.config.align_moment_weight[i] > 0.0) {
      const double sign = m > 0.0 ? 1.0 : -1.0;
      const double rho = p.norm();
      const double tangent_heading = std::atan2(sign * p.x(), -sign * p.y());
      lateral += model.config.align_moment_weight[i] * (std::abs(m) / rho) *
                 wrap_angle(tangent_heading - q);
    }
    data.F_d_ref[2 * i + 1] = lateral;
  }
  return data.F_d_ref;
}

const KeloDriveVector& kelo_distribute(const KeloModel& model, KeloData& data, const Vec3& F_p,
                                       const KeloDriveVector& F_d_ref) noexcept {
  // Disabled drives' references are ignored: N keeps a reference on a drive
  // that G⁺ never loads, so it must not enter at all.
  for (int k = 0; k < 2 * model.drives; ++k) {
    data.ref[k] = model.w_inv[k] > 0.0 ? F_d_ref[k] : 0.0;
  }
  for_drive_count(model.drives, [&]<int N>() { distribute_sized<N>(model, data, F_p); });
  return data.F_d;
}

const KeloDriveVector& kelo_hub_torques(const KeloModel& model, KeloData& data) noexcept {
  const double r = model.wheel_radius;
  const double k = 0.5 / model.lateral_ratio;  // (f_r - f_l) / 2 = s f_y / d
  for (int i = 0; i < model.drives; ++i) {
    const double fx = data.F_d[2 * i], fy = data.F_d[2 * i + 1];
    data.f_wheel[2 * i] = 0.5 * fx - k * fy;      // left
    data.f_wheel[2 * i + 1] = 0.5 * fx + k * fy;  // right
  }
  data.tau_wheel = r * data.f_wheel;
  return data.tau_wheel;
}

const KeloDriveVector& kelo_force_step(const KeloModel& model, KeloData& data,
                                       const KeloPivotVector& q_pivot, const Vec3& F_p) noexcept {
  data.input_fault = !q_pivot.allFinite() || !F_p.allFinite();
  if (data.input_fault) {
    data.F_d.setZero();
    data.f_wheel.setZero();
    data.tau_wheel.setZero();
    return data.tau_wheel;
  }
  kelo_set_pivots(model, data, q_pivot);
  kelo_alignment_reference(model, data, F_p);
  kelo_distribute(model, data, F_p, data.F_d_ref);
  return kelo_hub_torques(model, data);
}

const Vec3& kelo_platform_twist(const KeloModel& model, KeloData& data,
                                const KeloDriveVector& wheel_rates) noexcept {
  const double r = model.wheel_radius;
  const double s_over_d = 0.5 / model.lateral_ratio;  // s / d
  for (int i = 0; i < model.drives; ++i) {
    const double vl = r * wheel_rates[2 * i], vr = r * wheel_rates[2 * i + 1];
    data.u_pivot[2 * i] = 0.5 * (vl + vr);
    data.u_pivot[2 * i + 1] = s_over_d * (vr - vl);
  }
  const int m = 2 * model.drives;
  for_drive_count(model.drives, [&]<int N>() {
    data.xd_platform.noalias() =
        typename Sized<N>::ConstDistribution(data.G_pinv.data(), m, 3).transpose() *
        typename Sized<N>::ConstDrive(data.u_pivot.data(), m);
  });
  return data.xd_platform;
}

const KeloDriveVector& kelo_wheel_rates(const KeloModel& model, KeloData& data,
                                        const Vec3& xd_p) noexcept {
  const double r = model.wheel_radius;
  const double s = model.config.geometry.castor_offset;
  const int m = 2 * model.drives;
  for_drive_count(model.drives, [&]<int N>() {
    typename Sized<N>::Drive(data.u_pivot.data(), m).noalias() =
        typename Sized<N>::ConstComposition(data.G.data(), 3, m).transpose() * xd_p;
  });
  for (int i = 0; i < model.drives; ++i) {
    const double ux = data.u_pivot[2 * i], uy = data.u_pivot[2 * i + 1];
    // v_r - v_l = d u_y / s; the drive turns at (v_r - v_l)/d = u_y / s.
    const double half_diff = model.lateral_ratio * uy;
    data.wheel_rates[2 * i] = (ux - half_diff) / r;
    data.wheel_rates[2 * i + 1] = (ux + half_diff) / r;
    data.qd_pivot[i] = uy / s - xd_p[2];
  }
  return data.wheel_rates;
}

KeloProjector kelo_nullspace_projector(const KeloData& data) noexcept {
  KeloProjector N = -data.G_pinv * data.G;
  N.diagonal().array() += 1.0;
  return N;
}

}  // namespace mospec::runtime
