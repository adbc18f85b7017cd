// `mospec stats`: the size of an app's models per domain, counted the way the
// paper's Table I counts them.
//
// Counting method (it reproduces Table I exactly for the authors' four apps):
//  - every model file the app imports is counted once (duplicate imports and the
//    app file itself are not counted);
//  - a file's domain follows its file name without the "NN-" prefix and the
//    extension: world-model -> world model; map -> 3D-1D maps; constraints and
//    motion-specification -> constraints; constraint-handler -> controllers;
//    solver-specification and scenario -> solver specification. Other files
//    (the "misc" files with units, gravity and other shared facts) are listed
//    but not counted;
//  - entities: the length of the file's top-level "@graph" array (a file
//    without "@graph" is one entity when it has members besides "@context");
//  - lines: that "@graph" array written as JSON with 4-space indentation, one
//    member or element per line (what Python's json.dumps(indent=4) writes).
//    Number formatting and escaping never change the line count.
#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "cli/commands.hpp"
#include "json/json.hpp"
#include "support/io.hpp"

namespace mospec::cli {
namespace {

// Table I's columns, in the paper's order.
constexpr std::array<std::string_view, 5> kDomains = {"world model", "constraints", "controllers",
                                                      "3D-1D maps", "solver specification"};

// The domain index of a model file, or -1 when it is not counted.
int domain_of(const std::string& path) {
  std::string stem = std::filesystem::path(path).stem().string();
  // Drop a leading "NN-" ordering prefix.
  size_t i = 0;
  while (i < stem.size() && std::isdigit(static_cast<unsigned char>(stem[i]))) ++i;
  if (i > 0 && i < stem.size() && stem[i] == '-') stem = stem.substr(i + 1);
  if (stem == "world-model") return 0;
  if (stem == "constraints" || stem == "motion-specification") return 1;
  if (stem == "constraint-handler") return 2;
  if (stem == "map") return 3;
  if (stem == "solver-specification" || stem == "scenario") return 4;
  return -1;
}

struct Count {
  size_t entities = 0;
  size_t lines = 0;
};

size_t line_count(const std::string& text) {
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
}

Count count_file(const std::string& path) {
  json::Value doc = json::parse(read_file(path), 0, path);
  Count c;
  const json::Value* graph = doc.get("@graph");
  if (graph != nullptr) {
    c.entities = graph->is_array() ? graph->as_array().size() : 1;
    c.lines = line_count(json::dump(*graph, 4));
    return c;
  }
  if (doc.is_object()) {
    json::Object rest = doc.as_object();
    rest.erase("@context");
    if (rest.empty()) return c;
    c.entities = 1;
    c.lines = line_count(json::dump(json::Value(std::move(rest)), 4));
  }
  return c;
}

std::string cell(const Count& c) {
  return std::to_string(c.entities) + "/" + std::to_string(c.lines);
}

}  // namespace

Action add_stats_command(CLI::App& app) {
  struct Flags {
    std::vector<std::string> inputs;
    std::string format = "table";
    bool files = false;
    LoadFlags load;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "stats",
      "Size of an app's models per domain as entities/lines (the paper's Table I): entities "
      "are the elements of each imported file's top-level @graph, lines that @graph written "
      "with 4-space indentation. The domain follows the file name (NN-world-model, NN-map, "
      "NN-constraints, NN-motion-specification, NN-constraint-handler, "
      "NN-solver-specification, NN-scenario); other files (NN-misc) are not counted.");
  cmd->add_option("inputs", flags->inputs, "App model(s)")->required()->type_name("APP");
  cmd->add_option("--format", flags->format,
                  "'table': one row per domain; 'row': one line of entities/lines cells in "
                  "Table I's column order")
      ->check(CLI::IsMember({"table", "row"}))
      ->capture_default_str();
  cmd->add_flag("--files", flags->files, "Also list every imported file with its domain and count");
  flags->load.add_to(*cmd, /*strict=*/true, /*validates=*/false);

  return [flags]() {
    for (const std::string& input : flags->inputs) refuse_world_file_as_model(input);
    app::LoadedModel model = app::load(flags->inputs, flags->load.to_options());
    size_t warnings = print_diagnostics(model.diagnostics());
    if (flags->load.strict && warnings > 0) {
      std::cerr << "mospec: " << warnings << " finding(s) under --strict; no output written\n";
      return kExitFindings;
    }
    std::array<Count, kDomains.size()> totals{};
    std::ostringstream per_file;
    for (const app::ModelFile& f : model.model_files()) {
      if (f.is_app) continue;
      int d = domain_of(f.path);
      Count c = count_file(f.path);
      if (d >= 0) {
        totals[static_cast<size_t>(d)].entities += c.entities;
        totals[static_cast<size_t>(d)].lines += c.lines;
      }
      per_file << "  " << std::left << std::setw(22)
               << (d >= 0 ? kDomains[static_cast<size_t>(d)] : std::string_view("(not counted)"))
               << std::right << std::setw(10) << cell(c) << "  " << f.path << '\n';
    }
    std::ostringstream out;
    if (flags->format == "row") {
      for (size_t i = 0; i < totals.size(); ++i) out << (i ? "\t" : "") << cell(totals[i]);
      out << '\n';
    } else {
      out << std::left << std::setw(22) << "domain" << std::right << std::setw(10) << "entities"
          << std::setw(8) << "lines" << '\n';
      for (size_t i = 0; i < totals.size(); ++i) {
        out << std::left << std::setw(22) << kDomains[i] << std::right << std::setw(10)
            << totals[i].entities << std::setw(8) << totals[i].lines << '\n';
      }
    }
    if (flags->files) out << "files:\n" << per_file.str();
    std::cout << out.str();
    return kExitOk;
  };
}

}  // namespace mospec::cli
