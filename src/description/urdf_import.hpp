// URDF -> Chain, on urdfdom. Lives in the mospec_description library (setup time
// only) so the real-time mospec_runtime library does not link an XML parser.
#pragma once

#include <string>
#include <vector>

#include "runtime/chain.hpp"

namespace mospec::description {

using runtime::Chain;

// Extracts the serial chain from link `root` to link `tip`: one Segment per
// moving joint on the path (URDF revolute and continuous -> Revolute,
// prismatic -> Prismatic), fixed joints folded (see chain.hpp). Each link's
// <inertial> is re-expressed in its own link frame; links without one are
// massless. An empty `root` means the URDF's root link; an empty `tip` means
// its only leaf link.
//
// The text is untrusted. Before urdfdom sees it, scan_xml (xml_outline.hpp)
// bounds its depth, element and attribute counts and refuses malformed XML;
// the document must be one <robot> element whose links form a tree (no link
// with two parent joints, no cycle). Every number the chain is built from is
// checked where it is stated and again after each computation (rpy to a
// rotation, an inertia rotated into its link frame, origins composed and
// inertias merged when fixed joints are folded): finite positions, rotations,
// masses and inertias, a stated <mass> > 0, an inertia positive semi-definite
// whose principal moments satisfy the triangle inequality, a non-zero axis,
// <limit> lower <= upper and velocity, effort >= 0.
//
// Throws mospec::Error (code "invalid-urdf") at `source`:LINE:COL of the
// element concerned — the <link>, <joint>, <inertial>, <mass>, <inertia>,
// <origin>, <axis> or <limit>; the <robot> element for a root or tip link that
// does not exist (listing the links) or for several leaves when `tip` is empty;
// urdfdom's own refusals at the element its message names, or at the file
// alone when it names none. Also refused: `root` not an ancestor of `tip`, a
// floating or planar joint on the path, more than kMaxSegments moving joints.
Chain chain_from_urdf(const std::string& urdf_xml, const std::string& root, const std::string& tip,
                      const std::string& source = "<urdf>");

// The same, reading the file at `path`.
Chain chain_from_urdf_file(const std::string& path, const std::string& root,
                           const std::string& tip);

// The chain with what `mospec import-urdf` tells about it: the robot's name
// (<robot name>) and the fixed joints that attach the tip link to the last
// moving link (a tool0/flange link), in path order from that link.
struct UrdfChain {
  Chain chain;
  std::string robot;
  std::vector<std::string> tip_joints;
};
UrdfChain import_urdf(const std::string& urdf_xml, const std::string& root, const std::string& tip,
                      const std::string& source = "<urdf>");
UrdfChain import_urdf_file(const std::string& path, const std::string& root,
                           const std::string& tip);

}  // namespace mospec::description
