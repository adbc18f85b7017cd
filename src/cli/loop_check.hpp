// The closed-loop check `mospec run` makes before it runs a controller: a
// gain whose sign drives its error away, or a loop with an unstable pole, is
// refused at the controller.
#pragma once

#include <vector>

#include "ir/ir.hpp"
#include "sim/config.hpp"
#include "sim/world.hpp"
#include "support/diagnostics.hpp"

namespace mospec::cli {

// How the loop check probes one controller: its output is held at +kProbe
// and at -kProbe (in the output's unit) for kProbeTicks control ticks from
// the world's start state, every other controller held at its first tick's
// output; the difference of the two errors, tick by tick, is the loop's plant
// linearised about the start (its response to a held unit step).
inline constexpr double kProbe = 1.0;
inline constexpr int kProbeTicks = 20;
// The sign is read from the first kSignTicks ticks of that response: the
// loop's direct effect, before what the held-open rest of the task (the other
// loops, a mount, a contact) adds over longer horizons.
inline constexpr int kSignTicks = 5;

// Linearises each PID and impedance controller's loop about the start state
// from the two probes, and refuses, each as an error at the controller naming
// the quantity:
//
//   loop-sign      a gain with the sign of d(error)/d(output): u = K e and
//                  de/du K > 0 drives the error away (the gain, its value and
//                  the sign it must have);
//   unstable-loop  signs right, but the loop closed around the identified
//                  plant (an integrator and a double integrator fitted to the
//                  response, runtime::held_step_plant) has a pole outside the
//                  unit circle that grows the error e-fold within the probe
//                  (the pole, and the factor by which scaling the gains down
//                  makes it stable).
//
// A loop whose error the probes do not move (a motion not running at the
// start, a band the quantity is inside, a force without contact), or move
// inconsistently, is not judged; nor is the pole of a loop whose response the
// fit does not explain (within 10 %), nor any loop of a probe in which a solve
// lost directions. Slower growth than e-fold over the probe is below what a
// linearisation over the probe can tell from the damping it does not see.
// `arms` are the world's chains (arm_chains()).
std::vector<Diagnostic> check_loops(const ir::Program& program, const sim::WorldConfig& world,
                                    const std::vector<runtime::Chain>& arms,
                                    const SourceFiles& files);

}  // namespace mospec::cli
