#include "description/robot_model.hpp"

#include "app/app.hpp"
#include "description/chain_rdf.hpp"

namespace mospec::description {

runtime::Chain load_chain(const std::string& model_file, const std::string& chain_iri,
                          const std::vector<std::pair<std::string, std::string>>& maps) {
  app::LoadOptions options;
  options.maps = maps;
  const app::LoadedModel model = app::load({model_file}, options);
  return chain_from_rdf(model.flattened(), chain_iri);
}

}  // namespace mospec::description
