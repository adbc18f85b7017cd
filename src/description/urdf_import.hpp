// URDF -> Chain, on urdfdom. Lives in the mospec_description library (setup time
// only) so the real-time mospec_runtime library does not link an XML parser.
#pragma once

#include <string>

#include "runtime/chain.hpp"

namespace mospec::description {

using runtime::Chain;

// Extracts the serial chain from link `root` to link `tip`: one Segment per
// moving joint on the path (URDF revolute and continuous -> Revolute,
// prismatic -> Prismatic), fixed joints folded (see chain.hpp). Each link's
// <inertial> is re-expressed in its own link frame; links without one are
// massless. Throws mospec::Error, naming `source` (a file name for messages),
// when the XML does not parse (with urdfdom's own message), when `root` or `tip`
// is not a link (listing the links), when `root` is not an ancestor of `tip`,
// on a floating or planar joint on the path, or when the chain exceeds
// kMaxSegments moving joints. An empty `root` means the URDF's root link; an
// empty `tip` means its only leaf link (an error listing the leaves when there
// are several).
Chain chain_from_urdf(const std::string& urdf_xml, const std::string& root, const std::string& tip,
                      const std::string& source = "<urdf>");

// The same, reading the file at `path`.
Chain chain_from_urdf_file(const std::string& path, const std::string& root,
                           const std::string& tip);

}  // namespace mospec::description
