// RDF graph -> Chain: reads back a kinematic chain written in the vocabulary
// that chain_to_jsonld() emits (after JSON-LD loading, e.g. by app::load).
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rdf/dataset.hpp"
#include "runtime/chain.hpp"

namespace mospec::description {

using runtime::Chain;

// Builds the Chain whose KinematicChain node is `chain_iri` in `graph` (one
// flattened graph: every quad is read regardless of its graph name).
//
// The joints are a set in RDF; their order comes from the topology: each joint's
// parent-side attachment frame has a Pose with respect to the parent link's
// frame, its other attachment is the child link's frame, and the root is the
// one parent frame that no joint moves. A Pose of a further frame relative to
// the last link's frame is the tip. Link and joint names are the ids' last path
// segment without the "frame-" / "joint-" prefix. Lengths must be in M,
// masses in KiloGM, inertias in KiloGM-M2 (QUDT). Joint limits are the
// published secorolab kc-ext:JointLimit of a joint, typed also
// kc-stat:JointPosition, JointVelocity or JointForce (chain_to_jsonld writes
// them; velocity and force limits symmetric); without, they stay unbounded.
// mospec/joints' retired limit classes are refused, naming kc-ext:JointLimit.
// Throws mospec::Error naming the entity and what is missing or wrong.
Chain chain_from_rdf(const rdf::Dataset& graph, std::string_view chain_iri);

// The model entities of one frame of a chain, found through the graph's
// relations (never by how their IRIs are spelled): the frame, its `origin`
// point, and the body (link) it is attached to — the simplicial complex whose
// `simplices` hold the frame, else the body whose rotational inertia the frame
// sees. An entity the model does not relate is "".
struct FrameEntities {
  std::string frame, origin, body;
  std::string joint;  // a segment's: the joint that moves its frame (empty for the root)
};
struct ChainFrames {
  FrameEntities root;                   // the chain's root frame (the base link's)
  std::vector<FrameEntities> segments;  // segment i's frame S_i (the moving link's)
  // The tip frame fixed to the last segment's frame (a tool0, a flange), and
  // the Pose that places it there; empty when the chain names none.
  FrameEntities tip;
  std::string tip_pose;
};
struct ChainDescription {
  Chain chain;
  ChainFrames frames;
};
// chain_from_rdf() and the entities of the chain's frames.
ChainDescription describe_chain(const rdf::Dataset& graph, std::string_view chain_iri);
// The same read from the union of some graphs of `dataset` (as a set of
// triples) in place, without copying them into a dataset of their own.
ChainDescription describe_chain(const rdf::Dataset& dataset, std::span<const rdf::TermId> graphs,
                                std::string_view chain_iri);

}  // namespace mospec::description
