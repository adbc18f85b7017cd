// Chain -> JSON-LD text in the published comp-rob2b vocabulary (kinematic
// chain, geometry, rigid-body dynamics, QUDT units), so a robot description can
// be composed with task models like any other model file.
#pragma once

#include <string>

#include "runtime/chain.hpp"
#include "vocab/metamodels.hpp"

namespace mospec::description {

using runtime::Chain;

struct ChainJsonldOptions {
  // Base IRI of the document; every entity id is relative to it.
  std::string base = std::string(vocab::robots::imported_base) + "robot/";
  // Where the published metamodel contexts live (IRI prefix).
  std::string metamodels = std::string(vocab::kMetamodels);
  // Where the published secorolab extension contexts live (IRI prefix).
  std::string secorolab = std::string(vocab::kSecorolab);
  // Whether to state the joints' limits (kc-ext:JointLimit). Off for a
  // description that must load against the published metamodels alone (the
  // Gen3's, read with the authors' metamodels; its limits are the world's
  // default actuation).
  bool limits = true;
};

// The document, deterministic to the byte (numbers in shortest round-trip
// form), so generated files can be committed and compared.
//
// What it states (ids relative to the base):
//   link-L, frame-L (origin point-L-origin)   every link on the chain, the
//                                             root and the tip (a tool fixed to
//                                             the last link: its mass is folded
//                                             into that link); frame-L is the
//                                             URDF link frame
//   joint-J: RevoluteJoint, or PrismaticJoint between-attachments
//                                             {frame-J-attachment, frame-C}
//                                             (C the child link), common-axis axis-J
//   pose-J: Pose of frame-J-attachment w.r.t. and as seen by the parent link
//           frame (DirectionCosineXYZ: the attachment's x, y, z axes in parent
//           coordinates; VectorXYZ: its origin), units [UNITLESS, M]; at q = 0
//           the child frame coincides with the attachment
//   axis-J: UnitVector as seen by frame-J-attachment (and frame-C)
//   mass-L, position-L-com, inertia-L: mass [KiloGM], centre of mass
//           point-L-com in frame-L [M], rotational inertia about point-L-com
//           as seen by frame-L [KiloGM-M2] (folded links already merged)
//   pose-T: the tip frame w.r.t. the last link frame, when they differ
//   position-limit-J, velocity-limit-J, effort-limit-J: kc-ext:JointLimit
//           (the secorolab kinematic-chain extension) and kc-stat:JointPosition,
//           JointVelocity or JointForce, of-joint joint-J, `lower` and `upper`
//           qudt:Quantity nodes (kind and unit: Angle RAD, AngularVelocity
//           RAD-PER-SEC, Torque N-M; Length M, LinearVelocity M-PER-SEC, Force N
//           on a prismatic joint), when finite (a URDF's <limit>; velocity and
//           effort as -limit..limit)
//   chain: KinematicChain with its joints.
// A prismatic joint is a mos-jnt:PrismaticJoint (mospec's joint extension,
// metamodels/mospec/joints.json: the published vocabulary has no term for
// one), translating along its common-axis. The document lists the
// extension's context only when the chain has one, and the secorolab and
// kc-stat contexts only when it states limits, so an all-revolute chain
// without limits uses the comp-rob2b vocabulary alone.
std::string chain_to_jsonld(const Chain& chain, const ChainJsonldOptions& options = {});

}  // namespace mospec::description
