// Controllers (paper Sec. II-E): 1D laws that map a signal (a constraint's
// error, a measured velocity) to a control signal (a force, an acceleration
// setpoint). The IR declares each kind once (src/ir/controllers.cpp); this file
// holds their arithmetic. Three kinds:
//
//   Pid        Eq. (4), below;
//   Damping    the published DampingController: a saturated linear damper;
//   Impedance  the published ImpedanceController: a spring and a damper on
//              the error.
//
// Each is Model/Data shaped: a constant description checked at construction
// (throwing mospec::Error "invalid-controller" that names the controller and
// the offending values) and, where it needs one, a per-controller state; the
// step functions are noexcept and allocation-free.
//
// PID: 1D PID controllers with the paper's decaying integral term
//
//   f(t) = Kp ε(t) + Ki ∫_0^t e^{λ(τ - t)} ε(τ) dτ + Kd dε(t)/dt      (4)
//
// plus a feed-forward term, output saturation and anti-windup.
//
// Time. Every step gets the MEASURED time since the previous step, dt [s]; the
// integral is a true time integral and the derivative a difference quotient
// over dt. A step with dt <= 0, NaN or inf changes nothing (the state and the
// held output stay as they were) and reports HeldInvalidDt.
//
// λ is a rate per SECOND, as in Eq. (4): an error sample's weight in the
// integral decays as e^{-λ (t - τ)}, so the integral forgets with time constant
// 1/λ whatever the tick rate. The paper allows 0 <= λ <= 1 [1/s] (λ = 0 is the
// ordinary integral); the authors' models use 0.99. A gain tuned as a per-TICK
// factor β (I <- β I + ...) at period T corresponds to λ = -ln(β) / T:
// decay_rate_from_factor_per_tick() converts.
//
// Discretisation (exact for an error that is linear between samples — a
// first-order hold): with h = dt, a = λh, ε0 the previous and ε1 the new error,
//   I1 = e^{-a} I0 + h [ φ2(a) ε0 + (φ1(a) - φ2(a)) ε1 ],
//   φ1(a) = (1 - e^{-a}) / a,   φ2(a) = (1 - (1 + a) e^{-a}) / a²,
// which for λ = 0 is the trapezoidal rule (φ1 = 1, φ2 = 1/2). So a constant
// error gives I(t) = ε (1 - e^{-λt}) / λ (ε t for λ = 0) exactly, for any
// sequence of dt. The first step after a reset has no previous error; it holds
// the new error over its dt (ε0 = ε1) and its derivative term is zero — prime
// the previous error with reset(state, ε0) to avoid both.
//
// Output and anti-windup. u = ff + Kp ε + Ki I + Kd ε̇, clamped to
// [output_min, output_max]; state.saturated reports the clamp.
//   ConditionalIntegration (default): while the output is clamped and this
//     step's integration increment (Ki times it) would push further past the
//     clamped limit, the increment is dropped (the decay e^{-a} still applies,
//     which only shrinks |I|).
//   BackCalculation: the integral is pulled towards the value that makes the
//     unclamped output equal the clamped one, at rate tracking_rate k_b [1/s]:
//     Ki I += (1 - e^{-k_b h}) (u_clamped - u_unclamped), the exact solution of
//     d(Ki I)/dt = k_b (u_clamped - u) over the step with the other terms held.
//   None: the integral integrates regardless.
//
// Faults. A non-finite error or feed-forward leaves the state untouched, holds
// the previous output, latches state.fault (cleared only by reset) and reports
// HeldInvalidInput: no NaN ever reaches the integral or the output.
//
// Model/Data: Pid is the constant description (gains, limits), checked at
// setup; PidState is the per-controller data. step() is noexcept and
// allocation-free.
#pragma once

#include <cstdint>
#include <limits>

#include "runtime/transfer.hpp"

namespace mospec::runtime {

enum class AntiWindup : uint8_t { None, ConditionalIntegration, BackCalculation };

struct PidSpec {
  double kp = 0.0;          // [output unit / error unit]
  double ki = 0.0;          // [output unit / (error unit · s)]
  double kd = 0.0;          // [output unit · s / error unit]
  double decay_rate = 0.0;  // λ [1/s], 0 <= λ <= 1 (paper, Eq. 4); 0: plain integral
  double output_min = -std::numeric_limits<double>::infinity();
  double output_max = std::numeric_limits<double>::infinity();
  AntiWindup anti_windup = AntiWindup::ConditionalIntegration;
  double tracking_rate = 0.0;  // k_b [1/s] for BackCalculation (> 0 there)
};

struct PidState {
  double integral = 0.0;        // I = ∫ e^{-λ(t-τ)} ε(τ) dτ [error unit · s]
  double previous_error = 0.0;  // ε at the previous valid step
  bool has_previous = false;
  double derivative = 0.0;  // the last dε/dt [error unit / s]
  double output = 0.0;      // the last output (held while inputs are invalid)
  bool saturated = false;   // the last output was clamped
  bool fault = false;       // latched: a non-finite input was seen since reset
};

enum class PidStatus : int8_t {
  Ok = 0,
  HeldInvalidDt = 1,     // dt <= 0, NaN or inf: nothing changed
  HeldInvalidInput = -1  // error or feed-forward not finite: output held, fault latched
};

// λ [1/s] equivalent to multiplying the integral by `factor` (0 < factor <= 1)
// every tick of `period` seconds.
double decay_rate_from_factor_per_tick(double factor, double period) noexcept;

// φ1(a) = (1 - e^{-a})/a and φ2(a) = (1 - (1 + a) e^{-a})/a², a >= 0, with their
// limits 1 and 1/2 at a = 0; accurate to a few ulp for every a (φ2 by its
// Taylor series below a = 1, where the closed form cancels).
double decay_phi1(double a) noexcept;
double decay_phi2(double a) noexcept;

class Pid {
 public:
  // Throws mospec::Error("invalid-controller") naming `name` and the offending
  // values: non-finite gains, λ outside [0, 1], output_min >= output_max or NaN
  // limits, a negative or non-finite tracking rate, or BackCalculation with
  // Ki != 0 and no positive tracking rate.
  explicit Pid(const PidSpec& spec, const char* name = "controller");

  const PidSpec& spec() const { return spec_; }

  // One control step; the output is also in state.output.
  PidStatus step(PidState& state, double error, double dt,
                 double feed_forward = 0.0) const noexcept;

  // The law from the error to the output at a fixed tick `period` [s], as
  // step() computes it when nothing clamps (for the closed-loop check):
  //   C(z) = Kp + Ki h ((φ1 - φ2) z + φ2) / (z - e^{-λh}) + Kd (z - 1) / (h z).
  // Setup-time: allocates.
  Transfer transfer(double period) const;

  // Back to the initial state (zero integral, no previous error, no fault).
  static void reset(PidState& state) noexcept { state = PidState{}; }
  // ... with a known error at the start, so the first step's integral uses a
  // first-order hold and its derivative is finite.
  static void reset(PidState& state, double initial_error) noexcept {
    state = PidState{};
    state.previous_error = initial_error;
    state.has_previous = true;
  }

 private:
  PidSpec spec_;
};

// ---------------------------------------------------------------------------
// Damping (the published cstr-hdl:DampingController): the force that opposes a
// measured velocity v, proportional to it, such that the maximum velocity
// v_max calls for the maximum force F_max, and never more than F_max:
//
//   f = clamp(-(F_max / v_max) v, -F_max, F_max)
//
// that is, a linear damper with coefficient b = F_max / v_max [N s/m or
// N m s/rad] saturated at F_max. Units pair up: a linear velocity [m/s] with a
// force [N], an angular velocity [rad/s] with a torque [N m]. It has no state.
// A non-finite velocity (a sensor that fails) commands no force.
struct DampingSpec {
  double maximum_velocity = 1.0;  // v_max > 0 [m/s or rad/s]
  double maximum_force = 0.0;     // F_max > 0 [N or N m]
};

class Damping {
 public:
  // Throws mospec::Error("invalid-controller") naming `name` unless v_max and
  // F_max are finite and > 0.
  explicit Damping(const DampingSpec& spec, const char* name = "controller");

  const DampingSpec& spec() const { return spec_; }
  // b = F_max / v_max.
  double coefficient() const { return coefficient_; }
  double force(double velocity) const noexcept;

 private:
  DampingSpec spec_;
  double coefficient_ = 0.0;
};

// ---------------------------------------------------------------------------
// Impedance (the published cstr-hdl:ImpedanceController): a spring of
// stiffness K and a damper of damping D acting on the error signal ε,
//
//   f = K ε + D dε/dt,
//
// with dε/dt the difference quotient over the MEASURED dt, as the PID's
// derivative (zero on the first step after a reset). With a constant
// reference, dε/dt is minus the measured rate, so this is the spring-damper
// the controlled coordinate feels; its sign convention is the PID's (K = Kp,
// D = Kd give the same output as a PD controller). K, D >= 0 (a negative
// spring or damper is not passive) and not both 0. Units: an error in m gives
// a force in N (K in N/m, D in N s/m); in rad a torque in N m (K in N m/rad,
// D in N m s/rad).
//
// Apparent inertia (the vocabulary's `inertia`) needs the measured contact
// force (admittance control), which this controller's signals do not carry:
// lowering refuses a model that states it.
//
// dt <= 0, NaN or inf changes nothing; a non-finite error holds the previous
// output and latches state.fault (cleared by a reset), as the PID does.
struct ImpedanceSpec {
  double stiffness = 0.0;  // K >= 0 [N/m or N m/rad]
  double damping = 0.0;    // D >= 0 [N s/m or N m s/rad]
};

struct ImpedanceState {
  double previous_error = 0.0;
  bool has_previous = false;
  double rate = 0.0;    // the last dε/dt
  double output = 0.0;  // the last output (held while inputs are invalid)
  bool fault = false;   // latched: a non-finite error was seen since reset
};

class Impedance {
 public:
  // Throws mospec::Error("invalid-controller") naming `name` unless K and D
  // are finite, >= 0 and not both 0.
  explicit Impedance(const ImpedanceSpec& spec, const char* name = "controller");

  const ImpedanceSpec& spec() const { return spec_; }
  // One control step; the output is also in state.output.
  void step(ImpedanceState& state, double error, double dt) const noexcept;
  // The law at a fixed tick `period` [s]: C(z) = K + D (z - 1) / (h z).
  // Setup-time: allocates.
  Transfer transfer(double period) const;
  static void reset(ImpedanceState& state) noexcept { state = ImpedanceState{}; }

 private:
  ImpedanceSpec spec_;
};

}  // namespace mospec::runtime
