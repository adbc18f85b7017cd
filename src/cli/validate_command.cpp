// `mospec validate`: load an app model, read the shape files it names (and any
// --shapes), and report SHACL results located in the model files.
#include <iostream>

#include "cli/commands.hpp"
#include "shacl/report.hpp"
#include "support/io.hpp"
#include "validation/model_validation.hpp"

namespace mospec::cli {

Action add_validate_command(CLI::App& app) {
  struct Flags {
    std::vector<std::string> inputs;
    std::vector<std::string> shapes;
    std::string format = "text";
    std::string output = "-";
    LoadFlags load;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "Validate app models against SHACL shapes: the shape files the app's 'constraints' "
      "list names (resolved through its iri-map) plus any --shapes. Exit 0: conforms; 1: "
      "violations (under --strict also warnings, infos, loader warnings and strict "
      "findings); 2: bad input.");
  cmd->add_option("inputs", flags->inputs, "App model (or JSON-LD model files)")
      ->required()
      ->type_name("APP");
  cmd->add_option("--shapes", flags->shapes,
                  "Also validate against this shape file (Turtle, TriG, N-Triples/N-Quads or "
                  "JSON-LD); repeatable")
      ->type_name("FILE");
  cmd->add_option("--format", flags->format, "Report syntax")
      ->check(CLI::IsMember({"text", "turtle", "jsonld"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", flags->output, "Report file ('-' = standard output)")
      ->type_name("FILE");
  flags->load.add_to(*cmd);
  flags->load.add_budget_to(*cmd);

  return [flags]() {
    for (const std::string& input : flags->inputs) refuse_world_file_as_model(input);
    app::LoadedModel model = app::load(flags->inputs, flags->load.to_options());
    size_t warnings = print_diagnostics(model.diagnostics());

    validation::ModelValidationOptions options;
    options.extra_shapes = flags->shapes;
    options.strict = flags->load.strict;
    options.vocabulary_shapes = !flags->load.listed_shapes_only;
    options.sparql_limits.seconds = flags->load.sparql_seconds;
    options.sparql_limits.steps = flags->load.sparql_steps;
    validation::ModelValidation v = validation::validate_model(model, options);
    warnings += print_diagnostics(v.shape_diagnostics);
    for (const Diagnostic& d : v.strict_findings) std::cerr << format(d) << '\n';

    const shacl::Report& report = v.report;
    std::string text;
    if (flags->format == "turtle") {
      text = shacl::to_turtle(report);
    } else if (flags->format == "jsonld") {
      text = shacl::to_jsonld(report);
    } else {
      text = shacl::to_text(report, &model.files(), &model.files());
    }
    write_output(flags->output, text);

    const size_t violations =
        report.count(shacl::Level::Violation) + report.count(shacl::Level::Other);
    if (flags->load.strict) {
      const size_t findings = report.results.size() + warnings + v.strict_findings.size();
      if (findings > 0) {
        std::string line = "mospec: ";
        line.append(std::to_string(findings)).append(" finding(s) under --strict (");
        line.append(std::to_string(report.results.size())).append(" result(s), ");
        line.append(std::to_string(warnings)).append(" loader warning(s), ");
        line.append(std::to_string(v.strict_findings.size())).append(" strict finding(s))");
        std::cerr << line << '\n';
        return kExitFindings;
      }
      return kExitOk;
    }
    return violations > 0 ? kExitFindings : kExitOk;
  };
}

}  // namespace mospec::cli
