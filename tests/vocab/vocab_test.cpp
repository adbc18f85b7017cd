// The vocabulary IRIs (src/vocab): the helpers that build term IRIs, and the
// namespaces against what the project ships: each metamodel namespace is the
// one its JSON-LD context under metamodels/ defines, so models written with
// the contexts and code naming terms through vocab:: agree on every IRI.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "json/json.hpp"
#include "support/io.hpp"
#include "vocab/metamodels.hpp"
#include "vocab/w3c.hpp"

namespace mospec::vocab {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = MOSPEC_SOURCE_DIR;

TEST(Vocab, MetamodelTermIsTheNamespaceAndTheLocalName) {
  EXPECT_EQ(metamodel_term("geometry/spatial-relations", "Pose"),
            "https://comp-rob2b.github.io/metamodels/geometry/spatial-relations#Pose");
  EXPECT_EQ(metamodel_term("geometry/spatial-relations", "Pose"), term(geom_rel::ns, "Pose"));
  EXPECT_EQ(term(qudt::ns, "unit"), qudt::unit);
  EXPECT_EQ(term(app::ns, "constraints"), app::constraints);
  EXPECT_EQ(term("", ""), "");
}

TEST(Vocab, W3cTermsAreTheirNamespaceAndLocalName) {
  EXPECT_EQ(rdf::type, "http://www.w3.org/1999/02/22-rdf-syntax-ns#type");
  EXPECT_EQ(term(rdf::ns, "nil"), rdf::nil);
  EXPECT_EQ(term(rdfs::ns, "Class"), rdfs::Class);
  EXPECT_EQ(term(sh::ns, "NodeShape"), sh::NodeShape);
  // C++ keywords get a trailing underscore; the IRI keeps the local name.
  EXPECT_EQ(sh::class_, "http://www.w3.org/ns/shacl#class");
  EXPECT_EQ(sh::and_, "http://www.w3.org/ns/shacl#and");
  EXPECT_EQ(xsd::ns, "http://www.w3.org/2001/XMLSchema#");
}

// The prefix a context file maps to `ns` (empty when none does), read from its
// top-level "@context" object.
std::string prefix_for(const fs::path& context_file, std::string_view ns) {
  const json::Value doc = json::parse(read_file(context_file.string()), 0, context_file.string());
  const json::Value* context = doc.get("@context");
  if (context == nullptr || !context->is_object()) return "";
  const json::Object& members = context->as_object();
  for (size_t i = 0; i < members.size(); ++i) {
    if (members.value(i).is_string() && members.value(i).as_string() == ns)
      return std::string(members.key(i));
  }
  return "";
}

struct Namespace {
  std::string_view ns;
  const char* context;  // below the source tree
};

TEST(Vocab, EveryMetamodelNamespaceIsTheOneItsContextDefines) {
  const std::vector<Namespace> namespaces = {
      {geom_ent::ns, "metamodels/geometry/structural-entities.json"},
      {geom_rel::ns, "metamodels/geometry/spatial-relations.json"},
      {geom_coord::ns, "metamodels/geometry/coordinates.json"},
      {geom_op::ns, "metamodels/geometry/spatial-operators.json"},
      {kc_ent::ns, "metamodels/kinematic-chain/structural-entities.json"},
      {kc_stat::ns, "metamodels/kinematic-chain/state.json"},
      {dyn_ent::ns, "metamodels/newtonian-rigid-body-dynamics/structural-entities.json"},
      {dyn_coord::ns, "metamodels/newtonian-rigid-body-dynamics/coordinates.json"},
      {dyn_op::ns, "metamodels/newtonian-rigid-body-dynamics/operators.json"},
      {cstr::ns, "metamodels/task/constraint.json"},
      {cstr_hdl::ns, "metamodels/task/constraint-handler.json"},
      {mot::ns, "metamodels/task/motion-specification.json"},
      {slv::ns, "metamodels/task/solver-specification.json"},
      {map::ns, "metamodels/task/map.json"},
      {mospec_time::ns, "metamodels/mospec/time.json"},
      {mospec_base::ns, "metamodels/mospec/mobile-base.json"},
      {mospec_solver::ns, "metamodels/mospec/solver.json"},
      {mospec_guards::ns, "metamodels/mospec/guards.json"},
      {mospec_joints::ns, "metamodels/mospec/joints.json"},
      {mospec_app::ns, "metamodels/mospec/app.json"},
      // The secorolab extensions: their published namespace, not always the
      // context's path (constraint-extension.json extends task/constraint#).
      {kc_ext::ns, "metamodels/secorolab/kinematic-chain/structural-entities-extension.json"},
      {cstr_ext::ns, "metamodels/secorolab/task/constraint-extension.json"},
  };
  for (const Namespace& n : namespaces) {
    SCOPED_TRACE(n.context);
    EXPECT_TRUE(n.ns.ends_with('#')) << n.ns;
    EXPECT_TRUE(n.ns.starts_with(kMetamodels) || n.ns.starts_with(kSecorolab)) << n.ns;
    const fs::path file = kSource / n.context;
    ASSERT_TRUE(fs::exists(file));
    EXPECT_NE(prefix_for(file, n.ns), "") << "no prefix of " << n.context << " maps to " << n.ns;
  }
  // A namespace that differs from its context by one character is caught.
  EXPECT_EQ(prefix_for(kSource / "metamodels/geometry/spatial-relations.json",
                       "https://comp-rob2b.github.io/metamodels/geometry/spatial-relation#"),
            "");
  // mospec_shapes has no JSON-LD context: its terms (mos:DefinedReferences)
  // appear only in the Turtle shape files.
  EXPECT_TRUE(mospec_shapes::ns.starts_with(kMetamodels));
}

}  // namespace
}  // namespace mospec::vocab
