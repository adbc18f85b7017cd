// The closed-loop sign check `mospec run` makes before it runs a controller:
// a gain whose sign drives its error away is refused at the controller.
#pragma once

#include <vector>

#include "ir/ir.hpp"
#include "sim/config.hpp"
#include "sim/world.hpp"
#include "support/diagnostics.hpp"

namespace mospec::cli {

// How the loop check probes one controller: its output is held at +kProbe
// and at -kProbe (in the output's unit) for kProbeTicks control ticks from
// the world's start state, every other step running as the program says.
inline constexpr double kProbe = 1.0;
inline constexpr int kProbeTicks = 20;

// Linearises each PID and impedance controller's loop about the start state:
// from the two probes, the sign of d(error)/d(output) through the solve, the
// robot and the world. A loop is stable only if each gain has the opposite
// sign (u = K e, de/du K < 0); a gain with the same sign drives the error
// away, and is an error at the controller naming the quantity, the gain and
// the sign it must have. A loop whose error the probes do not move (a motion
// not running at the start, a band the quantity is inside, a force without
// contact) is not judged. `arms` are the world's chains (arm_chains()).
std::vector<Diagnostic> check_loop_signs(const ir::Program& program, const sim::WorldConfig& world,
                                         const std::vector<runtime::Chain>& arms,
                                         const SourceFiles& files);

}  // namespace mospec::cli
