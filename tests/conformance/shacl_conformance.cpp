// shacl-conformance: runs a W3C SHACL test manifest (sht:Validate entries,
// mf:include followed recursively) against mospec's validator, offline.
// Entries whose mf:result is sht:Failure (an ill-formed shapes graph, or a
// validation that must fail) pass only if mospec refuses them with an error.
//
//   shacl-conformance MANIFEST [--verbose] [--only NAME] [--skip-if-missing]
//
// Each test's report is compared with the expected sh:ValidationReport by
// graph isomorphism after the normalisation the suite's index.html
// prescribes: only the report vocabulary is kept, and sh:resultMessage only
// where the expected report names the same message.
//
// Prints one line per failure and per skipped test, then exactly
// "shacl: N passed, M failed, K skipped"; exits 0 iff nothing failed. With
// --skip-if-missing a missing manifest exits 77 (ctest's skip code).
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "rdf/dataset.hpp"
#include "rdf/isomorphism.hpp"
#include "rdf/turtle.hpp"
#include "shacl/report.hpp"
#include "shacl/shapes.hpp"
#include "shacl/validate.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"
#include "vocab/w3c.hpp"

namespace fs = std::filesystem;
namespace vocab = mospec::vocab;
using mospec::rdf::Dataset;
using mospec::rdf::Quad;
using mospec::rdf::TermId;

namespace {

constexpr int kSkipReturnCode = 77;
constexpr std::string_view kMf = "http://www.w3.org/2001/sw/DataAccess/tests/test-manifest#";
constexpr std::string_view kSht = "http://www.w3.org/ns/shacl-test#";

std::string file_iri(const fs::path& p) {
  return "file://" + fs::absolute(p).lexically_normal().string();
}

fs::path path_of(std::string_view iri) {
  if (iri.substr(0, 7) != "file://") return {};
  return fs::path(std::string(iri.substr(7)));
}

struct Args {
  std::string manifest;
  bool verbose = false;
  bool skip_if_missing = false;
  std::string only;
};

// A Turtle file read into its own dataset (and kept: shapes refer to it).
struct Graph {
  mospec::SourceFiles files;
  Dataset data;
};

std::unique_ptr<Graph> load(const fs::path& path) {
  auto g = std::make_unique<Graph>();
  uint32_t id = g->files.add(path.string());
  mospec::rdf::read_turtle(mospec::read_file(path.string()), file_iri(path), g->data, id,
                           path.string());
  return g;
}

TermId iri(const Dataset& d, std::string_view s) {
  return d.terms().find_iri(s);
}

std::vector<TermId> objects(const Dataset& d, TermId s, TermId p) {
  std::vector<TermId> out;
  if (s.is_any() || p.is_any()) return out;
  d.for_each(s, p, TermId::any(), TermId::any(), [&](const Quad& q, uint32_t) {
    out.push_back(q.object);
    return true;
  });
  return out;
}

std::vector<TermId> list_members(const Dataset& d, TermId head) {
  std::vector<TermId> out;
  TermId first = iri(d, vocab::rdf::first), rest = iri(d, vocab::rdf::rest),
         nil = iri(d, vocab::rdf::nil);
  std::set<uint32_t> seen;
  while (!head.is_any() && head != nil && seen.insert(head.index).second) {
    auto f = objects(d, head, first);
    auto r = objects(d, head, rest);
    if (f.size() != 1 || r.size() != 1) break;
    out.push_back(f[0]);
    head = r[0];
  }
  return out;
}

// Copies the triple (s, p, o) of `from` into `to`.
void copy(const Dataset& from, Dataset& to, const Quad& q) {
  to.add(Quad{to.terms().import(from.terms(), q.subject),
              to.terms().import(from.terms(), q.predicate),
              to.terms().import(from.terms(), q.object)});
}

// Every triple below a blank node (a path structure), recursively.
void copy_closure(const Dataset& from, Dataset& to, TermId node, std::set<uint32_t>& seen) {
  if (!from.terms()[node].is_blank() || !seen.insert(node.index).second) return;
  from.for_each(node, TermId::any(), TermId::any(), TermId::any(), [&](const Quad& q, uint32_t) {
    copy(from, to, q);
    copy_closure(from, to, q.object, seen);
    return true;
  });
}

// The report rooted at `root` in `from`, reduced to the compared vocabulary.
// With `messages`, sh:resultMessage triples are kept only when their object
// is in the set (the expected report's messages); without, all are kept.
Dataset normalise(const Dataset& from, TermId root, const std::set<std::string>* messages) {
  Dataset out;
  const std::set<std::string> kept{std::string(vocab::rdf::type),
                                   std::string(vocab::sh::result),
                                   std::string(vocab::sh::conforms),
                                   std::string(vocab::sh::focusNode),
                                   std::string(vocab::sh::resultPath),
                                   std::string(vocab::sh::resultSeverity),
                                   std::string(vocab::sh::sourceConstraint),
                                   std::string(vocab::sh::sourceConstraintComponent),
                                   std::string(vocab::sh::sourceShape),
                                   std::string(vocab::sh::value),
                                   std::string(vocab::sh::resultMessage)};
  const mospec::rdf::TermTable& t = from.terms();
  auto keep = [&](const Quad& q) {
    std::string p(t[q.predicate].value);
    if (kept.count(p) == 0) return false;
    if (p == vocab::sh::resultMessage && messages != nullptr)
      return messages->count(mospec::rdf::to_ntriples(t, q.object)) != 0;
    return true;
  };
  std::set<uint32_t> seen;
  TermId result = iri(from, vocab::sh::result), path = iri(from, vocab::sh::resultPath);
  from.for_each(root, TermId::any(), TermId::any(), TermId::any(), [&](const Quad& q, uint32_t) {
    if (keep(q)) copy(from, out, q);
    return true;
  });
  for (TermId r : objects(from, root, result)) {
    from.for_each(r, TermId::any(), TermId::any(), TermId::any(), [&](const Quad& q, uint32_t) {
      if (keep(q)) copy(from, out, q);
      return true;
    });
    for (TermId p : objects(from, r, path)) copy_closure(from, out, p, seen);
  }
  return out;
}

std::set<std::string> result_messages(const Dataset& d) {
  std::set<std::string> out;
  TermId p = iri(d, vocab::sh::resultMessage);
  if (p.is_any()) return out;
  d.for_each(TermId::any(), p, TermId::any(), TermId::any(), [&](const Quad& q, uint32_t) {
    out.insert(mospec::rdf::to_ntriples(d.terms(), q.object));
    return true;
  });
  return out;
}

class Runner {
 public:
  explicit Runner(const Args& args) : args_(args) {}

  void manifest(const fs::path& path) {
    fs::path canonical = fs::weakly_canonical(path);
    if (!visited_.insert(canonical.string()).second) return;
    std::unique_ptr<Graph> g;
    try {
      g = load(canonical);
    } catch (const mospec::Error& e) {
      fail(canonical.string(), std::string("cannot read manifest: ") + e.what());
      return;
    }
    const Dataset& d = g->data;
    TermId self = iri(d, file_iri(canonical));
    for (TermId inc : objects(d, self, iri(d, std::string(kMf) + "include")))
      manifest(path_of(d.terms()[inc].value));
    for (TermId entries : objects(d, self, iri(d, std::string(kMf) + "entries")))
      for (TermId entry : list_members(d, entries)) test(canonical, *g, entry);
  }

  int finish() const {
    std::cout << "shacl: " << passed_ << " passed, " << failed_ << " failed, " << skipped_
              << " skipped" << std::endl;
    return failed_ == 0 ? 0 : 1;
  }

 private:
  std::string name_of(const fs::path& manifest, const Dataset& d, TermId entry) const {
    std::string_view value = d.terms()[entry].value;
    fs::path p = path_of(value);
    if (p.empty()) return std::string(value);
    std::error_code ec;
    fs::path rel = fs::relative(p, root_, ec);
    (void)manifest;
    return ec ? p.string() : rel.string();
  }

  void test(const fs::path& manifest_path, const Graph& manifest, TermId entry) {
    const Dataset& m = manifest.data;
    std::string name = name_of(manifest_path, m, entry);
    if (!args_.only.empty() && name.find(args_.only) == std::string::npos) return;
    auto types = objects(m, entry, iri(m, vocab::rdf::type));
    bool validate = false;
    for (TermId t : types)
      validate = validate || m.terms()[t].value == std::string(kSht) + "Validate";
    if (!validate) {
      skip(name, "not an sht:Validate test");
      return;
    }
    auto actions = objects(m, entry, iri(m, std::string(kMf) + "action"));
    auto results = objects(m, entry, iri(m, std::string(kMf) + "result"));
    if (actions.size() != 1 || results.size() != 1) {
      fail(name, "malformed manifest entry (needs one mf:action and one mf:result)");
      return;
    }
    auto data_iris = objects(m, actions[0], iri(m, std::string(kSht) + "dataGraph"));
    auto shape_iris = objects(m, actions[0], iri(m, std::string(kSht) + "shapesGraph"));
    if (data_iris.size() != 1 || shape_iris.size() != 1) {
      fail(name, "malformed mf:action (needs one sht:dataGraph and one sht:shapesGraph)");
      return;
    }
    if (m.terms()[results[0]].is_iri()) {
      // sht:Failure: the shapes graph is ill-formed or validation must fail;
      // the test passes only if mospec refuses (throws a located error).
      const std::string expected(m.terms()[results[0]].value);
      if (expected != std::string(kSht) + "Failure") {
        fail(name, "unknown mf:result <" + expected + "> (expected a report or sht:Failure)");
        return;
      }
      expect_failure(name, m, data_iris[0], shape_iris[0]);
      return;
    }
    try {
      fs::path data_path = path_of(m.terms()[data_iris[0]].value);
      fs::path shapes_path = path_of(m.terms()[shape_iris[0]].value);
      std::unique_ptr<Graph> data = load(data_path);
      std::unique_ptr<Graph> separate_shapes;
      const Graph* shapes_graph = data.get();
      if (fs::weakly_canonical(shapes_path) != fs::weakly_canonical(data_path)) {
        separate_shapes = load(shapes_path);
        shapes_graph = separate_shapes.get();
      }
      auto shapes = mospec::shacl::Shapes::compile(shapes_graph->data, &shapes_graph->files);
      mospec::shacl::Report report = mospec::shacl::validate(shapes, data->data);
      Dataset actual_full = mospec::shacl::to_dataset(report);

      Dataset expected = normalise(m, results[0], nullptr);
      std::set<std::string> messages = result_messages(expected);
      TermId report_type = iri(actual_full, vocab::sh::ValidationReport);
      std::vector<TermId> roots;
      actual_full.for_each(TermId::any(), iri(actual_full, vocab::rdf::type), report_type,
                           TermId::any(), [&](const Quad& q, uint32_t) {
                             roots.push_back(q.subject);
                             return true;
                           });
      Dataset actual = normalise(actual_full, roots.at(0), &messages);
      if (mospec::rdf::isomorphic(expected, actual)) {
        ++passed_;
        if (args_.verbose) std::cout << "PASS " << name << "\n";
      } else {
        fail(name, "report differs from the expected report:\n" +
                       mospec::rdf::describe_difference(expected, actual) +
                       (args_.verbose ? "\nactual report:\n" + mospec::shacl::to_turtle(report)
                                      : std::string()));
      }
    } catch (const mospec::Error& e) {
      // SHACL 5.3.1 makes $shapesGraph optional: a processor without it must
      // report a failure, which is what mospec does.
      if (e.code() == "unsupported-shacl" &&
          std::string_view(e.what()).find("$shapesGraph is not supported") != std::string::npos)
        skip(name, "uses $shapesGraph, which SHACL 5.3.1 lets a processor refuse (mospec does)");
      else
        fail(name, std::string("error: ") + e.what());
    } catch (const std::exception& e) {
      fail(name, std::string("exception: ") + e.what());
    }
  }

  // Loads, compiles and validates; passes iff mospec reports an error.
  void expect_failure(const std::string& name, const Dataset& m, TermId data_iri,
                      TermId shapes_iri) {
    // Reading the files is the runner's business: an unreadable test file is
    // a failure of the run, not the refusal the test expects.
    std::unique_ptr<Graph> data, separate_shapes;
    const Graph* shapes_graph = nullptr;
    try {
      fs::path data_path = path_of(m.terms()[data_iri].value);
      fs::path shapes_path = path_of(m.terms()[shapes_iri].value);
      data = load(data_path);
      shapes_graph = data.get();
      if (fs::weakly_canonical(shapes_path) != fs::weakly_canonical(data_path)) {
        separate_shapes = load(shapes_path);
        shapes_graph = separate_shapes.get();
      }
    } catch (const mospec::Error& e) {
      fail(name, std::string("cannot read the test's graphs: ") + e.what());
      return;
    }
    try {
      auto shapes = mospec::shacl::Shapes::compile(shapes_graph->data, &shapes_graph->files);
      mospec::shacl::Report report = mospec::shacl::validate(shapes, data->data);
      fail(name, "expects a failure (sht:Failure), but validation succeeded" +
                     std::string(report.conforms() ? " (conforms)" : " (with results)"));
    } catch (const mospec::Error& e) {
      ++passed_;
      if (args_.verbose) std::cout << "PASS " << name << " (refused: " << e.what() << ")\n";
    } catch (const std::exception& e) {
      fail(name, std::string("expects a failure, got an exception that is not a mospec error: ") +
                     e.what());
    }
  }

  void fail(const std::string& name, const std::string& reason) {
    ++failed_;
    std::cout << "FAIL " << name << ": " << reason << "\n";
  }
  void skip(const std::string& name, const std::string& reason) {
    ++skipped_;
    std::cout << "SKIP " << name << ": " << reason << "\n";
  }

 public:
  fs::path root_;

 private:
  const Args& args_;
  std::set<std::string> visited_;
  int passed_ = 0, failed_ = 0, skipped_ = 0;
};

int usage() {
  std::cerr << "usage: shacl-conformance MANIFEST [--verbose] [--only NAME] [--skip-if-missing]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--verbose") {
      args.verbose = true;
    } else if (a == "--skip-if-missing") {
      args.skip_if_missing = true;
    } else if (a == "--only" && i + 1 < argc) {
      args.only = argv[++i];
    } else if (!a.empty() && a[0] == '-') {
      return usage();
    } else if (args.manifest.empty()) {
      args.manifest = a;
    } else {
      return usage();
    }
  }
  if (args.manifest.empty()) return usage();
  if (!fs::exists(args.manifest)) {
    if (args.skip_if_missing) {
      std::cout << "shacl: skipped: " << args.manifest << " not found (../shared is absent)\n";
      return kSkipReturnCode;
    }
    std::cerr << "shacl-conformance: " << args.manifest << ": no such file\n";
    return 2;
  }
  Runner runner(args);
  runner.root_ = fs::weakly_canonical(fs::path(args.manifest)).parent_path();
  runner.manifest(args.manifest);
  return runner.finish();
}
