// `mospec import-urdf`: a URDF serial chain as a kinematic-chain JSON-LD model in
// the published vocabulary, so robot descriptions compose with task models.
#include <iostream>

#include "cli/commands.hpp"
#include "description/chain_jsonld.hpp"
#include "description/urdf_import.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"

namespace mospec::cli {

namespace {

// The robot's name as one IRI path segment: characters an IRI path takes
// unescaped are kept, any other becomes '-'.
std::string iri_segment(const std::string& name) {
  std::string out;
  for (char c : name) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '-' || c == '.' || c == '_' || c == '~';
    out.push_back(plain ? c : '-');
  }
  return out.empty() || out == "." || out == ".." ? "robot" : out;
}

}  // namespace

Action add_import_urdf_command(CLI::App& app) {
  struct Flags {
    std::string input;
    std::string output = "-";
    std::string root, tip;
    description::ChainJsonldOptions jsonld;
  };
  auto flags = std::make_shared<Flags>();
  flags->jsonld.base.clear();  // default: after the robot's name
  CLI::App* cmd = app.add_subcommand("import-urdf", kImportUrdfSummary);
  cmd->add_option("urdf", flags->input, "URDF file")->required()->type_name("FILE.urdf");
  cmd->add_option("-o,--output", flags->output, "Output file ('-' = standard output)")
      ->type_name("OUT.jsonld");
  cmd->add_option("--root", flags->root, "Root link of the chain (default: the URDF's root)")
      ->type_name("LINK");
  cmd->add_option("--tip", flags->tip, "Tip link of the chain (default: the only leaf link)")
      ->type_name("LINK");
  cmd->add_option("--base", flags->jsonld.base,
                  "Base IRI of the entities in the model (default: " +
                      std::string(vocab::robots::imported_base) +
                      "NAME/, NAME the URDF's robot name)")
      ->type_name("IRI");
  cmd->add_flag_callback(
      "--no-limits", [flags] { flags->jsonld.limits = false; },
      "Leave the joints' <limit>s (kc-ext:JointLimit, the secorolab extension) out: the model "
      "then uses the comp-rob2b vocabulary alone (for models read with metamodels that lack "
      "the secorolab extension), and a world file states the arm's actuation");

  return [flags]() {
    const description::UrdfChain imported =
        description::import_urdf_file(flags->input, flags->root, flags->tip);
    description::ChainJsonldOptions options = flags->jsonld;
    if (options.base.empty()) {
      options.base = std::string(vocab::robots::imported_base) + iri_segment(imported.robot) + "/";
    }
    write_output(flags->output, description::chain_to_jsonld(imported.chain, options));
    const runtime::Chain& chain = imported.chain;
    if (!imported.tip_joints.empty() && chain.size() > 0) {
      // A tool link (tool0, a flange) fixed to the last moving link: say
      // which entities name it, so a task can make it the controlled frame.
      const std::string& last = chain.segment(chain.size() - 1).link;
      const std::string& tip = chain.tip();
      std::string joints;
      for (const std::string& j : imported.tip_joints) joints += (joints.empty() ? "" : ", ") + j;
      std::cerr << format(Diagnostic{
                       Severity::Note, "", 0, 0, "fixed-tip",
                       "the tip link '" + tip + "' is fixed to the last moving link '" + last +
                           "' (fixed joint " + joints + "): the model states it as the link <" +
                           options.base + "link-" + tip + "> with the frame <" + options.base +
                           "frame-" + tip + ">, posed by <" + options.base + "pose-" + tip +
                           "> in <" + options.base + "frame-" + last +
                           ">. It can be an arm solver's controlled frame: attach its motion "
                           "drivers to <" +
                           options.base + "link-" + tip + "> (they act at <" + options.base +
                           "point-" + tip +
                           "-origin>), and output its pose or twist "
                           "(docs/extending.md, \"A different arm\")"})
                << '\n';
    }
    return kExitOk;
  };
}

}  // namespace mospec::cli
