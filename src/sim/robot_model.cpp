#include "sim/robot_model.hpp"

#include "app/app.hpp"
#include "runtime/chain_rdf.hpp"

namespace mospec::sim {

runtime::Chain load_arm_chain(const RobotModelSource& source) {
  app::LoadOptions options;
  options.maps = source.maps;
  const app::LoadedModel model = app::load({source.model}, options);
  return runtime::chain_from_rdf(model.flattened(), source.chain_iri);
}

}  // namespace mospec::sim
