// `mospec rdf`: load and compose models, print the RDF they mean.
#include <iostream>

#include "cli/commands.hpp"
#include "rdf/nquads.hpp"
#include "support/io.hpp"

namespace mospec::cli {

Action add_rdf_command(CLI::App& app) {
  struct Flags {
    std::vector<std::string> inputs;
    std::string format = "nquads";
    std::string output = "-";
    LoadFlags load;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "rdf",
      "Load app models or JSON-LD files (offline) and write their RDF. 'nquads' keeps each "
      "file's graph; 'ntriples' writes the flattened union that later stages read.");
  cmd->add_option("inputs", flags->inputs, "App model or JSON-LD model files")
      ->required()
      ->type_name("APP_OR_FILE");
  cmd->add_option("--format", flags->format, "Output syntax")
      ->check(CLI::IsMember({"nquads", "ntriples"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", flags->output, "Output file ('-' = standard output)")
      ->type_name("FILE");
  flags->load.add_to(*cmd, /*strict=*/true, /*validates=*/false);

  return [flags]() {
    for (const std::string& input : flags->inputs) refuse_world_file_as_model(input);
    app::LoadedModel model = app::load(flags->inputs, flags->load.to_options());
    size_t warnings = print_diagnostics(model.diagnostics());
    if (flags->load.strict && warnings > 0) {
      std::cerr << "mospec: " << warnings << " finding(s) under --strict; no output written\n";
      return kExitFindings;
    }
    std::string text = flags->format == "ntriples"
                           ? rdf::to_nquads(model.flattened(), rdf::Format::NTriples)
                           : rdf::to_nquads(model.dataset(), rdf::Format::NQuads);
    write_output(flags->output, text);
    return kExitOk;
  };
}

}  // namespace mospec::cli
