#include "cli/pipeline.hpp"

#include <filesystem>
#include <iostream>

#include "shacl/report.hpp"
#include "validation/model_validation.hpp"

namespace mospec::cli {

void PipelineFlags::add_to(CLI::App& cmd) {
  cmd.add_option("app", inputs, "App model")->required()->type_name("APP");
  cmd.add_option("--bind", binds,
                 "Bind a kinematic chain to a robot arm (CHAIN=right|left); mospec's own robot "
                 "descriptions are bound by default")
      ->type_name("CHAIN=ARM");
  load.add_to(cmd);
}

std::string resolve_app(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    if (std::filesystem::is_directory(path, ec)) {
      std::string trimmed = path;
      while (trimmed.size() > 1 && trimmed.back() == '/') trimmed.pop_back();
      if (std::filesystem::is_regular_file(trimmed + ".json", ec)) return trimmed + ".json";
    }
    return path;
  }
  if (std::filesystem::is_regular_file(path + ".json", ec)) return path + ".json";
  return path;
}

std::optional<ir::Program> load_validate_lower(const PipelineFlags& flags, int& exit_code,
                                               SourceFiles* files, const AfterPass& after_pass) {
  ir::LowerOptions options;
  for (const std::string& b : flags.binds) {
    const auto eq = b.find('=');
    const std::string arm = eq == std::string::npos ? "" : b.substr(eq + 1);
    if (eq == std::string::npos || eq == 0 || (arm != "right" && arm != "left")) {
      throw Error("usage", "--bind expects CHAIN=right|left, got '" + b + "'");
    }
    options.ports[b.substr(0, eq)] = arm == "right" ? 0 : 1;
  }
  std::vector<std::string> inputs;
  for (const std::string& i : flags.inputs) inputs.push_back(resolve_app(i));
  app::LoadedModel model = app::load(inputs, flags.load.to_options());
  const size_t warnings = print_diagnostics(model.diagnostics());
  validation::ModelValidationOptions vopt;
  vopt.strict = flags.load.strict;
  vopt.vocabulary_shapes = !flags.load.listed_shapes_only;
  validation::ModelValidation v = validation::validate_model(model, vopt);
  print_diagnostics(v.shape_diagnostics);
  const size_t violations =
      v.report.count(shacl::Level::Violation) + v.report.count(shacl::Level::Other);
  const bool strict_fail =
      flags.load.strict && (warnings + v.strict_findings.size() + v.report.results.size() > 0);
  if (violations > 0 || strict_fail) {
    for (const Diagnostic& d : v.strict_findings) std::cerr << format(d) << '\n';
    std::cerr << shacl::to_text(v.report, &model.files(), &model.files());
    std::cerr << "mospec: the model does not validate; nothing was generated\n";
    exit_code = kExitFindings;
    return std::nullopt;
  }
  if (after_pass) {
    options.after_pass = [&](std::string_view pass, const ir::Program& p) {
      after_pass(pass, p, model.files());
    };
  }
  try {
    ir::Program program = ir::lower(model, options);
    if (files) *files = model.files();
    exit_code = kExitOk;
    return program;
  } catch (const ir::LowerError& e) {
    std::cerr << e.what() << '\n';
    std::cerr << "mospec: the model cannot be lowered (" << e.diagnostics().size()
              << " error(s)); nothing was generated\n";
    exit_code = kExitFindings;
    return std::nullopt;
  } catch (const ir::VerifyError& e) {
    std::cerr << e.what() << '\n';
    std::cerr << "mospec: internal error: lowering made a program that does not verify (a bug in "
                 "mospec, not in the model; please report it with the model)\n";
    exit_code = kExitBadInput;
    return std::nullopt;
  }
}

}  // namespace mospec::cli
