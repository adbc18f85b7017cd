// jsonld-conformance: runs a W3C JSON-LD 1.1 test manifest (toRdf or expand)
// against mospec's processor, offline.
//
//   jsonld-conformance MANIFEST [--verbose] [--only ID] [--skip-if-missing]
//                               [--include-optional]
//
// Prints one line per failure and per skipped test, then exactly
// "jsonld-<kind>: N passed, M failed, K skipped"; exits 0 iff nothing failed.
// With --skip-if-missing a missing manifest exits 77 (ctest's skip code).
// --include-optional also runs tests that `require` an optional feature
// (rdfDirection modes, generalized RDF), which are otherwise skipped.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "json/json.hpp"
#include "jsonld/expand.hpp"
#include "jsonld/loader.hpp"
#include "jsonld/to_rdf.hpp"
#include "rdf/dataset.hpp"
#include "rdf/isomorphism.hpp"
#include "rdf/nquads.hpp"
#include "support/arena.hpp"
#include "support/diagnostics.hpp"

namespace fs = std::filesystem;
using mospec::Error;
using mospec::json::Value;

namespace {

constexpr int kSkipReturnCode = 77;

enum class Kind { ToRdf, Expand };

struct Args {
  std::string manifest;
  bool verbose = false;
  bool skip_if_missing = false;
  bool include_optional = false;
  std::string only;
};

std::string str(const Value* v) {
  return v != nullptr && v->is_string() ? std::string(v->as_string()) : std::string();
}

bool has_type(const Value& test, std::string_view type) {
  const Value* types = test.get("@type");
  if (types == nullptr) return false;
  if (types->is_string()) return types->as_string() == type;
  if (!types->is_array()) return false;
  for (const Value& t : types->as_array()) {
    if (t.is_string() && t.as_string() == type) return true;
  }
  return false;
}

std::string lower(std::string s) {
  for (char& c : s) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return s;
}

// JSON-LD object comparison (suite README): member order never matters,
// array order matters only under @list, language tags compare case-blind.
bool jsonld_equal(const Value& a, const Value& b, bool ordered, bool language = false) {
  if (a.kind() != b.kind()) return false;
  switch (a.kind()) {
    case mospec::json::Kind::Null:
      return true;
    case mospec::json::Kind::Boolean:
      return a.as_bool() == b.as_bool();
    case mospec::json::Kind::Number:
      return a.as_number() == b.as_number();
    case mospec::json::Kind::String:
      return language ? lower(std::string(a.as_string())) == lower(std::string(b.as_string()))
                      : a.as_string() == b.as_string();
    case mospec::json::Kind::Object: {
      const auto& ao = a.as_object();
      const auto& bo = b.as_object();
      if (ao.size() != bo.size()) return false;
      for (size_t i = 0; i < ao.size(); ++i) {
        const Value* other = bo.find(ao.key(i));
        if (other == nullptr) return false;
        const std::string_view key = ao.key(i);
        // @json literal values are plain JSON: their arrays keep their order.
        bool json_literal = key == "@value" && a.get("@type") && str(a.get("@type")) == "@json";
        if (!jsonld_equal(ao.value(i), *other, key == "@list" || json_literal,
                          key == "@language")) {
          return false;
        }
      }
      return true;
    }
    case mospec::json::Kind::Array: {
      const auto& aa = a.as_array();
      const auto& ba = b.as_array();
      if (aa.size() != ba.size()) return false;
      if (ordered) {
        for (size_t i = 0; i < aa.size(); ++i) {
          if (!jsonld_equal(aa[i], ba[i], ordered, language)) return false;
        }
        return true;
      }
      // The relation is an equivalence, so greedy matching finds a bijection
      // whenever one exists.
      std::vector<bool> used(ba.size(), false);
      for (const Value& item : aa) {
        bool found = false;
        for (size_t j = 0; j < ba.size() && !found; ++j) {
          if (!used[j] && jsonld_equal(item, ba[j], false, language)) used[j] = found = true;
        }
        if (!found) return false;
      }
      return true;
    }
  }
  return false;
}

std::string read_text(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) throw Error("io", "cannot read '" + path + "'");
  std::string text;
  char buffer[65536];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
  std::fclose(f);
  return text;
}

std::string truncate(std::string s, size_t max = 300) {
  if (s.size() > max) s = s.substr(0, max) + "...";
  return s;
}

class Runner {
 public:
  Runner(Args args, Kind kind, std::string label)
      : args_(std::move(args)), kind_(kind), label_(std::move(label)) {}

  int run() {
    dir_ = fs::path(args_.manifest).parent_path().string();
    if (dir_.empty()) dir_ = ".";
    Value manifest = *manifest_loader_.load_file(args_.manifest).document;
    base_iri_ = str(manifest.get("baseIri"));
    if (base_iri_.empty()) base_iri_ = "https://w3c.github.io/json-ld-api/tests/";
    const Value* sequence = manifest.get("sequence");
    if (sequence == nullptr || !sequence->is_array()) {
      std::cerr << args_.manifest << ": error: manifest has no \"sequence\" array\n";
      return 2;
    }
    bool matched_only = args_.only.empty();
    for (const Value& test : sequence->as_array()) {
      std::string id = str(test.get("@id"));
      if (!args_.only.empty()) {
        if (id != args_.only && id != "#" + args_.only && id != "#t" + args_.only) continue;
        matched_only = true;
      }
      run_test(test, id);
    }
    if (!matched_only) {
      std::cerr << "jsonld-conformance: no test with id '" << args_.only << "' in "
                << args_.manifest << "\n";
      return 2;
    }
    std::cout << label_ << ": " << passed_ << " passed, " << failed_ << " failed, " << skipped_
              << " skipped" << std::endl;
    return failed_ == 0 ? 0 : 1;
  }

 private:
  void skip(const std::string& id, const std::string& name, const std::string& reason) {
    ++skipped_;
    std::cout << "SKIP " << id << " " << name << ": " << reason << "\n";
  }
  void fail(const std::string& id, const std::string& name, const std::string& reason,
            const std::string& detail = {}) {
    ++failed_;
    std::cout << "FAIL " << id << " " << name << ": " << reason << "\n";
    if (args_.verbose && !detail.empty()) std::cout << detail << "\n";
  }
  void pass(const std::string& id, const std::string& name) {
    ++passed_;
    if (args_.verbose) std::cout << "PASS " << id << " " << name << "\n";
  }

  // Why a test does not apply, or empty when it does.
  static std::string not_applicable(const Value& test, const Value* option, Kind kind,
                                    bool include_optional) {
    if (!has_type(test, kind == Kind::ToRdf ? "jld:ToRDFTest" : "jld:ExpandTest")) {
      return "not a " + std::string(kind == Kind::ToRdf ? "toRdf" : "expand") + " test";
    }
    std::string requires_ = str(test.get("requires"));
    if (requires_.empty() && option != nullptr) requires_ = str(option->get("requires"));
    if (!requires_.empty() && !include_optional) return "requires optional feature " + requires_;
    if (option != nullptr) {
      if (str(option->get("specVersion")) == "json-ld-1.0") {
        return "specVersion json-ld-1.0 only (mospec implements JSON-LD 1.1)";
      }
      const Value* normative = option->get("normative");
      if (normative != nullptr && normative->is_bool() && !normative->as_bool()) {
        return "non-normative test";
      }
    }
    return {};
  }

  void run_test(const Value& test, const std::string& id) {
    const std::string name = str(test.get("name"));
    const Value* option = test.get("option");
    if (std::string reason = not_applicable(test, option, kind_, args_.include_optional);
        !reason.empty()) {
      skip(id, name, reason);
      return;
    }
    const bool negative = has_type(test, "jld:NegativeEvaluationTest");
    const bool syntax = has_type(test, "jld:PositiveSyntaxTest");
    const std::string input = str(test.get("input"));

    // Each test starts with a fresh loader: files are few and small, and a test
    // must not see another's state.
    mospec::jsonld::MappedDocumentLoader loader;
    loader.map(base_iri_, dir_);
    mospec::jsonld::Options options;
    options.loader = &loader;
    std::string expected_code = str(test.get("expectErrorCode"));
    try {
      mospec::jsonld::RemoteDocument doc = loader.load(base_iri_ + input, {}, false);
      options.base = doc.document_url;
      if (option != nullptr) apply_options(*option, loader, options);

      if (kind_ == Kind::Expand) {
        Value result = mospec::jsonld::expand(*doc.document, options);
        if (negative) {
          fail(id, name, "expected error '" + expected_code + "', got a result",
               mospec::json::dump(result, 2));
          return;
        }
        Value expected = mospec::json::parse(read_text(dir_ + "/" + str(test.get("expect"))));
        if (!jsonld_equal(result, expected, false)) {
          fail(id, name, "result differs: " + truncate(mospec::json::dump(result)),
               "expected:\n" + mospec::json::dump(expected, 2) + "\nactual:\n" +
                   mospec::json::dump(result, 2));
          return;
        }
        // The loader expands into an arena and drops the tree without
        // destroying it, which is sound only if all of it is in the arena.
        mospec::Arena arena(512);
        const Value in_arena = mospec::jsonld::expand(*doc.document, options, &arena);
        if (!(in_arena == result) || !mospec::json::lives_in(in_arena, &arena)) {
          fail(id, name, "expanded into an arena, the result differs or is not all in the arena",
               mospec::json::dump(in_arena, 2));
          return;
        }
      } else {
        mospec::rdf::Dataset result;
        mospec::jsonld::load_into(*doc.document, result, options);
        if (negative) {
          fail(id, name,
               "expected error '" + expected_code + "', got " + std::to_string(result.size()) +
                   " quads",
               mospec::rdf::to_nquads(result));
          return;
        }
        if (!syntax) {
          std::string expect = str(test.get("expect"));
          mospec::rdf::Dataset expected;
          mospec::rdf::read_nquads(read_text(dir_ + "/" + expect), expected, 0, expect);
          if (!mospec::rdf::isomorphic(result, expected)) {
            fail(id, name,
                 "dataset not isomorphic (" + std::to_string(result.size()) + " quads, expected " +
                     std::to_string(expected.size()) + ")",
                 "result:\n" + mospec::rdf::to_nquads(result) + "expected:\n" +
                     mospec::rdf::to_nquads(expected) +
                     mospec::rdf::describe_difference(result, expected));
            return;
          }
        }
      }
      pass(id, name);
    } catch (const Error& e) {
      // A document that is not JSON fails to load, in the API's terms.
      std::string code = e.code() == "invalid json" ? "loading document failed" : e.code();
      if (negative && code == expected_code) {
        pass(id, name);
        if (args_.verbose) std::cout << "  (" << e.what() << ")\n";
      } else if (negative) {
        fail(id, name, "expected error '" + expected_code + "', got '" + code + "': " + e.what());
      } else {
        fail(id, name, std::string("unexpected error: ") + e.what());
      }
    } catch (const std::exception& e) {
      fail(id, name, std::string("unexpected exception (not mospec::Error): ") + e.what());
    }
  }

  void apply_options(const Value& option, mospec::jsonld::MappedDocumentLoader& loader,
                     mospec::jsonld::Options& options) {
    if (std::string base = str(option.get("base")); !base.empty()) options.base = base;
    if (str(option.get("processingMode")) == "json-ld-1.0") {
      options.processing_mode = mospec::jsonld::ProcessingMode::JsonLd10;
    }
    if (std::string ctx = str(option.get("expandContext")); !ctx.empty()) {
      // The suite gives expandContext relative to the manifest.
      options.expand_context = *loader.load(base_iri_ + ctx, {}, true).document;
    }
    if (const Value* g = option.get("produceGeneralizedRdf"); g != nullptr && g->is_bool()) {
      options.produce_generalized_rdf = g->as_bool();
    }
    std::string direction = str(option.get("rdfDirection"));
    if (direction == "i18n-datatype") {
      options.rdf_direction = mospec::jsonld::RdfDirection::I18nDatatype;
    } else if (direction == "compound-literal") {
      options.rdf_direction = mospec::jsonld::RdfDirection::CompoundLiteral;
    }
    // The remote-document options (contentType, httpLink, redirectTo, httpStatus)
    // appear only in the remote-doc manifest, which this runner does not run.
    for (std::string_view unsupported : {"contentType", "httpLink", "redirectTo", "httpStatus"}) {
      if (option.get(unsupported) != nullptr) {
        // The runner's own limit, not a finding of mospec's (no diagnostic code).
        throw std::runtime_error("option '" + std::string(unsupported) +
                                 "' is not emulated by this runner");
      }
    }
  }

  Args args_;
  Kind kind_;
  std::string label_;
  std::string dir_;
  std::string base_iri_;
  mospec::jsonld::MappedDocumentLoader manifest_loader_;
  int passed_ = 0;
  int failed_ = 0;
  int skipped_ = 0;
};

int usage() {
  std::cerr << "usage: jsonld-conformance MANIFEST [--verbose] [--only ID] [--skip-if-missing]\n"
               "                          [--include-optional]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  for (int i = 1; i < argc; ++i) {
    std::string_view a = argv[i];
    if (a == "--verbose" || a == "-v") {
      args.verbose = true;
    } else if (a == "--include-optional") {
      args.include_optional = true;
    } else if (a == "--skip-if-missing") {
      args.skip_if_missing = true;
    } else if (a == "--only") {
      if (++i >= argc) return usage();
      args.only = argv[i];
    } else if (a.starts_with("-")) {
      return usage();
    } else if (args.manifest.empty()) {
      args.manifest = a;
    } else {
      return usage();
    }
  }
  if (args.manifest.empty()) return usage();
  std::string file = fs::path(args.manifest).filename().string();
  std::string kind_name = file.substr(0, file.find("-manifest"));
  Kind kind;
  if (kind_name == "toRdf") {
    kind = Kind::ToRdf;
  } else if (kind_name == "expand") {
    kind = Kind::Expand;
  } else {
    std::cerr << "jsonld-conformance: " << args.manifest
              << ": only toRdf-manifest.jsonld and expand-manifest.jsonld are supported\n";
    return 2;
  }
  std::error_code ec;
  if (!fs::exists(args.manifest, ec)) {
    if (args.skip_if_missing) {
      std::cout << "jsonld-" << kind_name << ": skipped: " << args.manifest
                << " not found (the W3C suite lives in ../shared beside the checkout)\n";
      return kSkipReturnCode;
    }
    std::cerr << "jsonld-conformance: " << args.manifest << ": no such file\n";
    return 2;
  }
  try {
    return Runner(args, kind, "jsonld-" + kind_name).run();
  } catch (const Error& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
}
