// --fault KIND[:SENSOR]@TICK[+TICKS], shared by `mospec sim` and `mospec run`.
#pragma once

#include <string>

#include "robot/faults.hpp"

namespace mospec::cli {

// nan:right_arm.q[1]@500+100, stale:pivot_q[0]@100, drop@200+5 (TICKS
// omitted: until the end for sensors, one command for drop). Throws
// mospec::Error("usage") naming the spec and what is wrong.
void add_fault(robot::FaultInjector& faults, const std::string& spec);

inline constexpr const char* kFaultHelp =
    "Inject a fault, by control tick; repeatable: nan:SENSOR@TICK[+TICKS], "
    "stale:SENSOR@TICK[+TICKS] (sensors: right_arm.q[0], left_arm.tau[6], pivot_q[2], "
    "wheel_qd[7], ...), drop@TICK[+COUNT]";

}  // namespace mospec::cli
