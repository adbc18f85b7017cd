// `mospec import-urdf`: a URDF serial chain as a kinematic-chain JSON-LD model in
// the published vocabulary, so robot descriptions compose with task models.
#include "cli/commands.hpp"
#include "description/chain_jsonld.hpp"
#include "description/urdf_import.hpp"
#include "support/io.hpp"

namespace mospec::cli {

Action add_import_urdf_command(CLI::App& app) {
  struct Flags {
    std::string input;
    std::string output = "-";
    std::string root, tip;
    description::ChainJsonldOptions jsonld;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand("import-urdf", kImportUrdfSummary);
  cmd->add_option("urdf", flags->input, "URDF file")->required()->type_name("FILE.urdf");
  cmd->add_option("-o,--output", flags->output, "Output file ('-' = standard output)")
      ->type_name("OUT.jsonld");
  cmd->add_option("--root", flags->root, "Root link of the chain (default: the URDF's root)")
      ->type_name("LINK");
  cmd->add_option("--tip", flags->tip, "Tip link of the chain (default: the only leaf link)")
      ->type_name("LINK");
  cmd->add_option("--base", flags->jsonld.base, "Base IRI of the entities in the model")
      ->type_name("IRI")
      ->capture_default_str();

  return [flags]() {
    const runtime::Chain chain =
        description::chain_from_urdf_file(flags->input, flags->root, flags->tip);
    write_output(flags->output, description::chain_to_jsonld(chain, flags->jsonld));
    return kExitOk;
  };
}

}  // namespace mospec::cli
