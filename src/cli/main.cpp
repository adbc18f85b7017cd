// mospec: composable JSON-LD task models -> verified controllers.
#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "support/diagnostics.hpp"

namespace mospec::cli {

void LoadFlags::add_to(CLI::App& cmd) {
  cmd.add_option("--map", maps,
                 "Map an IRI prefix to a local directory (IRI=DIR); repeatable. Nothing is "
                 "ever fetched from the network.")
      ->type_name("IRI=DIR");
  cmd.add_option("--root", root,
                 "Resolve the app model's iri-map paths against DIR instead of the current "
                 "directory")
      ->type_name("DIR");
  cmd.add_flag("--strict", strict, "Treat warnings (dropped keys, undefined types) as findings");
}

app::LoadOptions LoadFlags::to_options() const {
  app::LoadOptions o;
  for (const std::string& m : maps) {
    auto eq = m.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == m.size()) {
      throw Error("usage", "--map expects IRI=DIR, got '" + m + "'");
    }
    o.maps.emplace_back(m.substr(0, eq), m.substr(eq + 1));
  }
  if (!root.empty()) o.root = root;
  return o;
}

size_t print_diagnostics(const DiagnosticSink& sink) {
  for (const Diagnostic& d : sink.diagnostics()) std::cerr << format(d) << '\n';
  return sink.diagnostics().size();
}

}  // namespace mospec::cli

int main(int argc, char** argv) {
  using namespace mospec::cli;
  CLI::App app{
      "mospec: composable JSON-LD models of contact-rich robot tasks -> verified, "
      "generated controllers"};
  app.name("mospec");
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Help for every command");
  std::vector<std::pair<CLI::App*, Action>> commands;
  Action rdf = add_rdf_command(app);
  commands.emplace_back(app.get_subcommand("rdf"), rdf);
  Action validate = add_validate_command(app);
  commands.emplace_back(app.get_subcommand("validate"), validate);
  Action stats = add_stats_command(app);
  commands.emplace_back(app.get_subcommand("stats"), stats);
  Action sim = add_sim_command(app);
  commands.emplace_back(app.get_subcommand("sim"), sim);
  Action import_urdf = add_import_urdf_command(app);
  commands.emplace_back(app.get_subcommand("import-urdf"), import_urdf);
  Action generate = add_generate_command(app);
  commands.emplace_back(app.get_subcommand("generate"), generate);
  Action build = add_build_command(app);
  commands.emplace_back(app.get_subcommand("build"), build);
  Action ir = add_ir_command(app);
  commands.emplace_back(app.get_subcommand("ir"), ir);
  Action run = add_run_command(app);
  commands.emplace_back(app.get_subcommand("run"), run);
  Action plot = add_plot_command(app);
  commands.emplace_back(app.get_subcommand("plot"), plot);
  Action trials = add_trials_command(app);
  commands.emplace_back(app.get_subcommand("trials"), trials);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "mospec: " << e.what() << "\n(run 'mospec --help' for usage)\n";
    return kExitBadInput;
  }
  try {
    for (auto& [cmd, action] : commands) {
      if (cmd->parsed()) return action();
    }
  } catch (const mospec::Error& e) {
    std::cerr << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "mospec: internal error: " << e.what() << '\n';
    return kExitBadInput;
  }
  return kExitBadInput;
}
