// IRIs of the modelling vocabularies: the published comp-rob2b metamodels
// (https://github.com/comp-rob2b/metamodels), mospec's own additions under the
// same base, the paper's group's published extensions (secorolab/metamodels),
// QUDT, and the IRIs of mospec's bundled robot descriptions. The one place they
// are spelled (the ctest `vocab_home` fails when either metamodel base appears
// elsewhere in src/).
//
// Each metamodel is a namespace whose `ns` is its namespace IRI ("...#"), named
// as the models' own JSON-LD contexts abbreviate it (geom-rel -> geom_rel).
// The MOSPEC_VOCAB_* macros are the same IRIs as string literals.
#pragma once

#include <string>
#include <string_view>

#define MOSPEC_VOCAB_MM "https://comp-rob2b.github.io/metamodels/"
#define MOSPEC_VOCAB_SECOROLAB "https://secorolab.github.io/metamodels/"
#define MOSPEC_VOCAB_QUDT "http://qudt.org/schema/qudt/"
#define MOSPEC_VOCAB_QUDT_UNIT "http://qudt.org/vocab/unit/"

namespace mospec::vocab {

// The base of every comp-rob2b metamodel IRI (and of their JSON-LD contexts,
// which mospec resolves to its own copy under metamodels/).
inline constexpr std::string_view kMetamodels = MOSPEC_VOCAB_MM;

// The base of the secorolab extension metamodels (IRIs and JSON-LD contexts):
// a context URL below it resolves to mospec's own context of the same path
// under metamodels/secorolab/ (only the extensions mospec reads have one).
inline constexpr std::string_view kSecorolab = MOSPEC_VOCAB_SECOROLAB;

// The term `local` of the metamodel at `domain` (a path below kMetamodels such
// as "geometry/spatial-relations"): kMetamodels + domain + "#" + local. For
// tables that name a term by (domain, local); prefer the named `ns` below.
inline std::string metamodel_term(std::string_view domain, std::string_view local) {
  std::string s(kMetamodels);
  s.append(domain).append("#").append(local);
  return s;
}

// ns + local, for the helpers that name terms of one namespace.
inline std::string term(std::string_view ns, std::string_view local) {
  std::string s(ns);
  s.append(local);
  return s;
}

#define MOSPEC_VOCAB_NS(name, path)                                \
  namespace name {                                                 \
  inline constexpr std::string_view ns = MOSPEC_VOCAB_MM path "#"; \
  }

MOSPEC_VOCAB_NS(geom_ent, "geometry/structural-entities")
MOSPEC_VOCAB_NS(geom_rel, "geometry/spatial-relations")
MOSPEC_VOCAB_NS(geom_coord, "geometry/coordinates")
MOSPEC_VOCAB_NS(geom_op, "geometry/spatial-operators")
MOSPEC_VOCAB_NS(kc_ent, "kinematic-chain/structural-entities")
MOSPEC_VOCAB_NS(kc_stat, "kinematic-chain/state")
MOSPEC_VOCAB_NS(dyn_ent, "newtonian-rigid-body-dynamics/structural-entities")
MOSPEC_VOCAB_NS(dyn_coord, "newtonian-rigid-body-dynamics/coordinates")
MOSPEC_VOCAB_NS(dyn_op, "newtonian-rigid-body-dynamics/operators")
MOSPEC_VOCAB_NS(cstr, "task/constraint")
MOSPEC_VOCAB_NS(cstr_hdl, "task/constraint-handler")
MOSPEC_VOCAB_NS(mot, "task/motion-specification")
MOSPEC_VOCAB_NS(slv, "task/solver-specification")
MOSPEC_VOCAB_NS(map, "task/map")
// mospec's own additions (metamodels/mospec/).
MOSPEC_VOCAB_NS(mospec_time, "mospec/time")
MOSPEC_VOCAB_NS(mospec_base, "mospec/mobile-base")
MOSPEC_VOCAB_NS(mospec_solver, "mospec/solver")
MOSPEC_VOCAB_NS(mospec_guards, "mospec/guards")
MOSPEC_VOCAB_NS(mospec_joints, "mospec/joints")
MOSPEC_VOCAB_NS(mospec_shapes, "mospec/shapes")
MOSPEC_VOCAB_NS(mospec_app, "mospec/app")

#undef MOSPEC_VOCAB_NS

// The secorolab extensions mospec reads (metamodels/secorolab/<path>.json is
// its context of https://secorolab.github.io/metamodels/<path>.json). The
// namespace is the published one, which is not always the context's path:
// task/constraint-extension.json defines cstr-ext as ".../task/constraint#".
#define MOSPEC_VOCAB_SECOROLAB_NS(name, path)                             \
  namespace name {                                                        \
  inline constexpr std::string_view ns = MOSPEC_VOCAB_SECOROLAB path "#"; \
  }
// kinematic-chain/structural-entities-extension.json: JointLimit.
MOSPEC_VOCAB_SECOROLAB_NS(kc_ext, "kinematic-chain/structural-entities-extension")
// task/constraint-extension.json: tolerance.
MOSPEC_VOCAB_SECOROLAB_NS(cstr_ext, "task/constraint")
#undef MOSPEC_VOCAB_SECOROLAB_NS

// The application model (app files): a "/"-namespace, unlike the others.
namespace app {
inline constexpr std::string_view ns = MOSPEC_VOCAB_MM "application/";
inline constexpr std::string_view constraints = MOSPEC_VOCAB_MM "application/constraints";
}  // namespace app

namespace qudt {
inline constexpr std::string_view ns = MOSPEC_VOCAB_QUDT;
inline constexpr std::string_view Quantity = MOSPEC_VOCAB_QUDT "Quantity";
inline constexpr std::string_view hasQuantityKind = MOSPEC_VOCAB_QUDT "hasQuantityKind";
inline constexpr std::string_view unit = MOSPEC_VOCAB_QUDT "unit";
inline constexpr std::string_view value = MOSPEC_VOCAB_QUDT "value";
}  // namespace qudt

namespace qudt_unit {
inline constexpr std::string_view ns = MOSPEC_VOCAB_QUDT_UNIT;
}  // namespace qudt_unit

// The kinematic chains of mospec's bundled robot descriptions (robots/*.jsonld).
namespace robots {
inline constexpr std::string_view kinova_gen3_chain =
    "https://mospec.example/robots/kinova-gen3/chain";
inline constexpr std::string_view kinova_gen3_left_chain =
    "https://mospec.example/robots/kinova-gen3-left/chain";
// The paper's mobile base (robots/kelo-base.jsonld): its CastorDriveBase.
inline constexpr std::string_view kelo_base = "https://mospec.example/robots/kelo-base/base";
// Where `mospec import-urdf` names a robot by default: this, the URDF's robot
// name and "/" (two robots imported side by side get two bases).
inline constexpr std::string_view imported_base = "https://mospec.example/robots/";
}  // namespace robots

}  // namespace mospec::vocab
