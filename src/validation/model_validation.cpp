#include "validation/model_validation.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <span>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "jsonld/context.hpp"
#include "jsonld/to_rdf.hpp"
#include "rdf/nquads.hpp"
#include "rdf/turtle.hpp"
#include "shacl/validate.hpp"
#include "support/io.hpp"
#include "vocab/metamodels.hpp"
#include "vocab/w3c.hpp"

namespace mospec::validation {

using namespace mospec::shacl;

namespace fs = std::filesystem;
using rdf::TermId;

namespace {

// Calls f(line number, line) for each line of a text file (without its '\n').
template <class F>
void for_each_line(const std::string& text, F&& f) {
  size_t start = 0;
  uint32_t line_no = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    f(++line_no, text.substr(start, end - start));
    start = end + 1;
  }
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string file_url(const std::string& path) {
  std::error_code ec;
  fs::path abs = fs::weakly_canonical(fs::absolute(path), ec);
  return "file://" + abs.generic_string();
}

// An Error re-issued at `at` (a location in the model's files) when it has no
// location of its own.
[[noreturn]] void rethrow_at(const Error& e, const SourceFiles& files, SourceLoc at,
                             const std::string& prefix) {
  const Diagnostic& d = e.diagnostic();
  if (!d.file.empty() && d.line != 0) throw e;
  std::string message = prefix;
  message += d.message;
  if (at.known()) throw Error(e.code(), message, files.path(at.file), at.line, at.column);
  throw Error(e.code(), message);
}

}  // namespace

ShapeSyntax shape_syntax(const std::string& path, std::string_view content) {
  const std::string ext = lower_extension(path);
  if (ext == ".ttl" || ext == ".turtle") return ShapeSyntax::Turtle;
  if (ext == ".trig") return ShapeSyntax::TriG;
  if (ext == ".nt" || ext == ".nq") return ShapeSyntax::NQuads;
  if (ext == ".json" || ext == ".jsonld") return ShapeSyntax::JsonLd;
  for (char c : content) {
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') continue;
    return c == '{' || c == '[' ? ShapeSyntax::JsonLd : ShapeSyntax::Turtle;
  }
  return ShapeSyntax::Turtle;
}

void read_shape_file(const ShapeFile& file, jsonld::MappedDocumentLoader& loader,
                     rdf::Dataset& into, DiagnosticSink* diagnostics) {
  SourceFiles& files = loader.files();
  const std::string what = "shape file '" + file.path + "'" +
                           (file.iri.empty() ? std::string() : " (<" + file.iri + ">)") + ": ";
  std::string text;
  try {
    text = read_file(file.path);
  } catch (const Error& e) {
    // read_file names the path; say which shape file it was and where it is named.
    std::string m = e.diagnostic().message;
    if (m.rfind("cannot read ", 0) == 0) m.erase(0, 12);
    std::string message = "cannot read shape file ";
    message += m;
    if (!file.iri.empty()) message.append(" (named as <").append(file.iri).append(">)");
    Error plain("io", message);
    rethrow_at(plain, files, file.named_at, "");
  }
  const std::string base = file.iri.empty() ? file_url(file.path) : file.iri;
  const ShapeSyntax syntax = shape_syntax(file.path, text);
  if (syntax == ShapeSyntax::JsonLd) {
    jsonld::RemoteDocument doc = loader.load_file(file.path, base);
    jsonld::Options opts;
    opts.base = doc.document_url;
    opts.loader = &loader;
    opts.diagnostics = diagnostics;
    try {
      jsonld::load_into(*doc.document, into, opts);
    } catch (const Error& e) {
      rethrow_at(e, files, file.named_at, what);
    }
    return;
  }
  const uint32_t id = files.add(file.path);
  switch (syntax) {
    case ShapeSyntax::Turtle:
      rdf::read_turtle(text, base, into, id, file.path);
      break;
    case ShapeSyntax::TriG:
      rdf::read_trig(text, base, into, id, file.path);
      break;
    default:
      rdf::read_nquads(text, into, id, file.path);
      break;
  }
}

std::vector<ShapeFile> shape_files(app::LoadedModel& model, const std::vector<std::string>& extra,
                                   bool use_app_constraints) {
  std::vector<ShapeFile> out;
  std::unordered_set<std::string> seen;
  if (use_app_constraints) {
    // Where each constraints IRI is written: the app node's constraints quad.
    const rdf::Dataset& ds = model.dataset();
    const rdf::TermTable& t = ds.terms();
    TermId constraints_p = t.find_iri(std::string(app::kAppNs) + "constraints");
    auto named_at = [&](const std::string& iri) {
      SourceLoc loc;
      TermId o = t.find_iri(iri);
      if (constraints_p.is_any() || o.is_any()) return loc;
      ds.scan(TermId::any(), constraints_p, o, TermId::any(), [&](const rdf::Quad&, uint32_t i) {
        loc = ds.location(i);
        return !loc.known();
      });
      return loc;
    };
    for (const app::AppInfo& info : model.apps()) {
      for (const std::string& iri : info.constraints) {
        if (!seen.insert(iri).second) continue;
        SourceLoc at = named_at(iri);
        std::string path = model.loader().resolve(iri);
        if (path.empty()) {
          std::string message = "shape file <" + iri +
                                "> is not mapped to a local path (add an iri-map entry to " +
                                info.file + " or pass --map IRI=DIR)";
          if (at.known())
            throw Error("io", message, model.files().path(at.file), at.line, at.column);
          throw Error("io", message);
        }
        // The sandbox and control-character checks of imports and contexts.
        model.loader().resolve_for_loading(iri, at, "io", "shape file");
        out.push_back(ShapeFile{path, iri, at});
      }
    }
  }
  for (const std::string& path : extra) {
    if (!seen.insert("file:" + path).second) continue;
    out.push_back(ShapeFile{path, std::string(), SourceLoc{}});
  }
  return out;
}

// ---- strict checks ---------------------------------------------------------

std::vector<std::string> context_term_iris(app::LoadedModel& model) {
  jsonld::MappedDocumentLoader& loader = model.loader();
  jsonld::Options opts;
  opts.loader = &loader;
  opts.context_cache = std::make_shared<jsonld::ContextCache>();
  std::unordered_set<std::string> iris;
  std::unordered_set<const jsonld::ActiveContext*> visited;
  std::unordered_set<std::string> scoped;

  // Terms of an active context and of the scoped contexts its definitions hold.
  std::function<void(const jsonld::ContextPtr&, int)> collect = [&](const jsonld::ContextPtr& ctx,
                                                                    int depth) {
    if (!ctx || !visited.insert(ctx.get()).second) return;
    for (const std::string& term : ctx->terms()) {
      const jsonld::TermDefinition* def = ctx->find(term);
      if (def == nullptr) continue;
      if (def->iri) iris.insert(*def->iri);
      // Each distinct scoped context once (they nest and repeat, so walking
      // every definition's context would grow exponentially).
      if (def->local_context && depth < 8 &&
          scoped.insert(json::dump(*def->local_context) + '\n' + def->base_url).second) {
        try {
          collect(
              jsonld::process_context(ctx, *def->local_context,
                                      def->base_url.empty() ? ctx->base() : def->base_url, opts),
              depth + 1);
        } catch (const Error&) {
          // A scoped context that does not process contributes no terms; the
          // loader reported anything wrong with it when the model was read.
        }
      }
    }
  };
  // Every @context entry of a document, each processed from an initial context.
  std::function<void(const json::Value&, const std::string&)> walk = [&](const json::Value& v,
                                                                         const std::string& base) {
    if (v.is_array()) {
      for (const json::Value& item : v.as_array()) walk(item, base);
      return;
    }
    if (!v.is_object()) return;
    const json::Object& o = v.as_object();
    for (size_t i = 0; i < o.size(); ++i) {
      if (o.key(i) == "@context") {
        try {
          collect(jsonld::process_context(jsonld::ActiveContext::initial(base, opts), o.value(i),
                                          base, opts),
                  0);
        } catch (const Error&) {
        }
      } else {
        walk(o.value(i), base);
      }
    }
  };
  for (const app::ModelFile& file : model.model_files()) {
    try {
      jsonld::RemoteDocument doc = loader.load_file(file.path, file.iri);
      walk(*doc.document, doc.document_url);
    } catch (const Error&) {
    }
  }
  std::vector<std::string> out(iris.begin(), iris.end());
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> read_unshaped_terms(const std::string& path) {
  const std::string text = read_file(path);
  std::vector<std::string> out;
  std::unordered_map<std::string, std::string> prefixes;
  for_each_line(text, [&](uint32_t line_no, std::string line) {
    // A comment starts at a '#' that begins the line or follows a blank (an
    // IRI's fragment '#' does neither).
    for (size_t k = 0; k < line.size(); ++k) {
      if (line[k] == '#' && (k == 0 || line[k - 1] == ' ' || line[k - 1] == '\t')) {
        line.erase(k);
        break;
      }
    }
    const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    while (!line.empty() && blank(line.back())) line.pop_back();
    size_t first = 0;
    while (first < line.size() && blank(line[first])) ++first;
    line.erase(0, first);
    if (line.empty()) return;
    const auto bad = [&](const std::string& why) {
      throw Error("unshaped-terms", why, path, line_no, static_cast<uint32_t>(first + 1));
    };
    if (line.rfind("@prefix ", 0) == 0) {
      // @prefix NAME: <IRI> .
      const size_t colon = line.find(':'), open = line.find('<'), close = line.find('>');
      if (colon == std::string::npos || open == std::string::npos || close == std::string::npos ||
          !(colon < open && open < close) ||
          line.substr(close + 1).find_first_not_of(" .") != std::string::npos)
        bad("expected '@prefix NAME: <IRI> .', got '" + line + "'");
      std::string name = line.substr(8, colon - 8);
      while (!name.empty() && name.front() == ' ') name.erase(0, 1);
      prefixes[name] = line.substr(open + 1, close - open - 1);
      return;
    }
    if (line.find_first_of(" \t") != std::string::npos)
      bad("one class IRI or CURIE per line (a reason goes after '#'), got '" + line + "'");
    if (line.front() == '<' && line.back() == '>') {
      out.push_back(line.substr(1, line.size() - 2));
      return;
    }
    const size_t colon = line.find(':');
    if (colon == std::string::npos)
      bad("'" + line + "' is neither an IRI nor a CURIE (NAME:local, NAME declared by @prefix)");
    auto it = prefixes.find(line.substr(0, colon));
    if (line.compare(colon, 3, "://") == 0) {
      out.push_back(line);
    } else if (it == prefixes.end()) {
      bad("prefix '" + line.substr(0, colon) + "' of '" + line +
          "' is not declared (add '@prefix " + line.substr(0, colon) + ": <IRI> .' above it)");
    } else {
      out.push_back(it->second + line.substr(colon + 1));
    }
  });
  return out;
}

namespace {

// Every predicate IRI a path names (inverse and negated ones included).
void path_predicates(const sparql::Path& path, const rdf::TermTable& terms,
                     std::unordered_set<std::string>& out) {
  if (path.kind == sparql::Path::Kind::Predicate && terms[path.predicate].is_iri())
    out.emplace(terms[path.predicate].value);
  for (const std::vector<TermId>* set : {&path.negated, &path.negated_inverse})
    for (TermId p : *set)
      if (terms[p].is_iri()) out.emplace(terms[p].value);
  for (const sparql::PathPtr& item : path.items)
    if (item) path_predicates(*item, terms, out);
}

// Where an unshaped term is first used, and how often: the finding is located
// at its earliest located use and names the node there.
struct TermUse {
  SourceLoc first;
  TermId node = TermId::any();
  size_t count = 0;

  void saw(SourceLoc loc, TermId subject) {
    if (node.is_any() ||
        (loc.known() && (!first.known() || std::tie(loc.file, loc.line, loc.column) <
                                               std::tie(first.file, first.line, first.column)))) {
      first = loc;
      node = subject;
    }
  }
  // "<what> <T> of <node> <problem> (N <unit>s<qualifier>): <fix>, or list it
  // as structural in metamodels/mospec/unshaped-terms.txt".
  std::string message(const rdf::TermTable& dt, std::string_view what, TermId term,
                      std::string_view problem, std::string_view unit, std::string_view qualifier,
                      std::string_view fix) const {
    std::string m(what);
    m.append(" <").append(dt[term].value).append("> of ");
    if (dt[node].is_iri())
      m.append("<").append(dt[node].value).append(">");
    else
      m.append("a blank node");
    m.append(" ").append(problem).append(" (").append(std::to_string(count)).append(" ");
    m.append(unit).append(count == 1 ? "" : "s").append(qualifier);
    m.append("): ").append(fix).append(
        ", or list it as structural in "
        "metamodels/mospec/unshaped-terms.txt");
    return m;
  }
};

// unshaped-term for properties: predicates of mospec's metamodels (the apps'
// own application/ terms aside) that the model uses and that no shape's
// sh:path names, unless `exempt` lists them.
template <typename Located>
void unpathed_properties(app::LoadedModel& model, const Shapes& shapes,
                         const std::unordered_set<std::string>& exempt,
                         std::vector<Diagnostic>& out, const Located& located) {
  const std::string base(vocab::kMetamodels);
  const std::string app_ns(app::kAppNs);
  std::unordered_set<std::string> pathed;
  for (const Shape& s : shapes.shapes())
    if (s.path) path_predicates(*s.path, shapes.graph().terms(), pathed);
  const rdf::Dataset& data = model.dataset();
  const rdf::TermTable& dt = data.terms();
  std::unordered_map<uint32_t, bool> verdict;  // predicate -> reported
  std::unordered_map<uint32_t, TermUse> uses;
  std::vector<TermId> order;
  for (size_t i = 0; i < data.size(); ++i) {
    const rdf::Quad& q = data.quads()[i];
    auto [v, fresh] = verdict.try_emplace(q.predicate.index, false);
    if (fresh) {
      const std::string_view p = dt[q.predicate].value;
      v->second = dt[q.predicate].is_iri() && p.substr(0, base.size()) == base &&
                  p.substr(0, app_ns.size()) != app_ns && exempt.count(std::string(p)) == 0 &&
                  pathed.count(std::string(p)) == 0;
    }
    if (!v->second) continue;
    auto [it, first_use] = uses.try_emplace(q.predicate.index);
    if (first_use) order.push_back(q.predicate);
    ++it->second.count;
    it->second.saw(data.location(i), q.subject);
  }
  for (TermId t : order) {
    const TermUse& u = uses[t.index];
    out.push_back(located(u.first, "unshaped-term",
                          u.message(dt, "property", t, "is constrained by no shape's sh:path",
                                    "use", "", "add a shape whose path names it")));
  }
}

// unshaped-term: classes of mospec's metamodels that type a node of the model
// and that no shape covers, unless metamodels/mospec/unshaped-terms.txt lists
// them. Only when the vocabulary resolves to mospec's metamodels.
template <typename Located>
void unshaped_terms(app::LoadedModel& model, const Shapes& shapes, std::vector<Diagnostic>& out,
                    const Located& located) {
  const std::string base(vocab::kMetamodels);
  jsonld::MappedDocumentLoader& loader = model.loader();
  const std::string manifest = loader.resolve(base + "mospec/shape-files.txt");
  std::error_code ec;
  if (manifest.empty() || !fs::is_regular_file(manifest, ec)) return;
  std::unordered_set<std::string> exempt;
  const std::string list = loader.resolve(base + "mospec/unshaped-terms.txt");
  if (!list.empty() && fs::is_regular_file(list, ec))
    for (std::string& iri : read_unshaped_terms(list)) exempt.insert(std::move(iri));
  unpathed_properties(model, shapes, exempt, out, located);

  // Target classes of the active shapes, and rdfs:subClassOf from the data and
  // the shapes graphs (a node of a subclass is selected by its superclass's
  // target).
  std::unordered_set<std::string> targets;
  const rdf::Dataset& sg = shapes.graph();
  const rdf::TermTable& st = sg.terms();
  for (const Shape& s : shapes.shapes()) {
    if (s.deactivated) continue;
    for (TermId c : s.target_classes)
      if (st[c].is_iri()) targets.insert(std::string(st[c].value));
  }
  std::unordered_map<std::string, std::vector<std::string>> supers;
  const rdf::Dataset& data_graph = model.dataset();
  for (const rdf::Dataset* g : {&data_graph, &sg}) {
    const TermId sub = g->terms().find_iri(vocab::rdfs::subClassOf);
    if (sub.is_any()) continue;
    g->scan(TermId::any(), sub, TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t) {
      const rdf::Term &s = g->terms()[q.subject], &o = g->terms()[q.object];
      if (s.is_iri() && o.is_iri()) supers[std::string(s.value)].emplace_back(o.value);
      return true;
    });
  }
  const auto covered = [&](const std::string& cls) {
    std::vector<std::string> todo{cls};
    std::unordered_set<std::string> seen{cls};
    while (!todo.empty()) {
      std::string c = std::move(todo.back());
      todo.pop_back();
      if (targets.count(c) != 0) return true;
      if (auto it = supers.find(c); it != supers.end())
        for (const std::string& s : it->second)
          if (seen.insert(s).second) todo.push_back(s);
    }
    return false;
  };

  const rdf::Dataset& data = model.dataset();
  const rdf::TermTable& dt = data.terms();
  const TermId type = dt.find_iri(vocab::rdf::type);
  if (type.is_any()) return;
  std::unordered_map<uint32_t, bool> verdict;  // class -> reported
  std::unordered_map<uint32_t, TermUse> uses;
  std::unordered_map<uint32_t, std::unordered_set<uint32_t>> nodes;
  std::vector<TermId> order;
  data.scan(TermId::any(), type, TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t i) {
    const rdf::Term& o = dt[q.object];
    if (!o.is_iri() || o.value.substr(0, base.size()) != base) return true;
    auto [v, fresh] = verdict.try_emplace(q.object.index, false);
    if (fresh) {
      const std::string cls(o.value);
      v->second = exempt.count(cls) == 0 && !covered(cls);
    }
    if (!v->second) return true;
    auto [it, first_use] = uses.try_emplace(q.object.index);
    if (first_use) order.push_back(q.object);
    if (nodes[q.object.index].insert(q.subject.index).second) ++it->second.count;
    it->second.saw(data.location(i), q.subject);
    return true;
  });
  for (TermId t : order) {
    const TermUse& u = uses[t.index];
    out.push_back(located(u.first, "unshaped-term",
                          u.message(dt, "type", t, "is covered by no shape", "node", " typed so",
                                    "add a shape that targets it")));
  }
}

}  // namespace

std::vector<Diagnostic> strict_checks(app::LoadedModel& model, const Shapes& shapes,
                                      const std::vector<ShapeFile>& automatic) {
  std::vector<Diagnostic> out;
  const SourceFiles& files = model.files();
  auto located = [&](SourceLoc loc, DiagnosticCode code, std::string message) {
    return mospec::located(Severity::Warning, loc, files, code, std::move(message));
  };

  // Shapes with targets that select nothing.
  const rdf::Dataset& data = model.dataset();
  std::vector<size_t> counts = count_focus_nodes(shapes, data);
  for (uint32_t i = 0; i < shapes.shapes().size(); ++i) {
    const Shape& s = shapes[i];
    if (!s.has_targets() || s.deactivated || counts[i] != 0) continue;
    // A file mospec added because the model uses part of it: its other
    // shapes are not the author's choice.
    const bool added =
        s.where.known() && std::any_of(automatic.begin(), automatic.end(), [&](const ShapeFile& f) {
          return f.automatic && files.path(s.where.file) == f.path;
        });
    if (added) continue;
    out.push_back(located(
        s.where, "shape-unused",
        "shape " + shapes.describe(i) + " has targets but selects no focus node in the model"));
  }

  // rdf:type values that nothing defines.
  std::unordered_set<std::string> defined;
  for (std::string& iri : context_term_iris(model)) defined.insert(std::move(iri));
  const rdf::Dataset& sg = shapes.graph();
  const rdf::TermTable& st = sg.terms();
  for (const rdf::Quad& q : sg.quads())
    if (st[q.subject].is_iri()) defined.insert(std::string(st[q.subject].value));
  for (std::string_view p : {vocab::sh::targetClass, vocab::sh::class_}) {
    TermId pid = st.find_iri(p);
    if (pid.is_any()) continue;
    sg.scan(TermId::any(), pid, TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t) {
      if (st[q.object].is_iri()) defined.insert(std::string(st[q.object].value));
      return true;
    });
  }
  const rdf::TermTable& dt = data.terms();
  TermId type = dt.find_iri(vocab::rdf::type);
  if (!type.is_any()) {
    struct Use {
      SourceLoc first;
      size_t count = 0;
    };
    std::unordered_map<uint32_t, Use> uses;
    std::vector<TermId> order;
    data.scan(
        TermId::any(), type, TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t i) {
          const rdf::Term& o = dt[q.object];
          if (!o.is_iri() || defined.count(std::string(o.value)) != 0) return true;
          auto [it, fresh] = uses.try_emplace(q.object.index);
          if (fresh) order.push_back(q.object);
          ++it->second.count;
          SourceLoc loc = data.location(i);
          SourceLoc& first = it->second.first;
          if (loc.known() && (!first.known() || std::tie(loc.file, loc.line, loc.column) <
                                                    std::tie(first.file, first.line, first.column)))
            first = loc;
          return true;
        });
    for (TermId t : order) {
      const Use& u = uses[t.index];
      std::string message = "type <" + std::string(dt[t].value) +
                            "> is defined by no loaded JSON-LD context or shape (used " +
                            std::to_string(u.count) + (u.count == 1 ? " time)" : " times)");
      out.push_back(located(u.first, "undefined-type", std::move(message)));
    }
  }
  unshaped_terms(model, shapes, out, located);
  std::stable_sort(out.begin(), out.end(), [&](const Diagnostic& a, const Diagnostic& b) {
    return std::tie(a.file, a.line, a.column, a.message) <
           std::tie(b.file, b.line, b.column, b.message);
  });
  return out;
}

// ---- shapes that come with the vocabulary ----------------------------------

namespace {

// Whether a shapes file's targets select any node of `data`.
bool selects_a_node(const rdf::Dataset& shapes, const rdf::Dataset& data) {
  const rdf::TermTable& st = shapes.terms();
  const rdf::TermTable& dt = data.terms();
  const TermId type = dt.find_iri(vocab::rdf::type);
  const auto in_data = [&](TermId shapes_term) {
    return st[shapes_term].is_iri() ? dt.find_iri(st[shapes_term].value) : TermId::any();
  };
  const auto typed = [&](TermId cls) {
    const TermId c = in_data(cls);
    return !c.is_any() && !type.is_any() && data.count(TermId::any(), type, c, TermId::any(), 1);
  };
  const TermId s_type = st.find_iri(vocab::rdf::type);
  const TermId node_shape = st.find_iri(vocab::sh::NodeShape);
  const TermId rdfs_class = st.find_iri(vocab::rdfs::Class);
  bool selected = false;
  for (const rdf::Quad& q : shapes.quads()) {
    const std::string_view p = st[q.predicate].value;
    if (p == vocab::sh::targetClass) {
      selected = typed(q.object);
    } else if (p == vocab::sh::targetSubjectsOf || p == vocab::sh::targetObjectsOf) {
      const TermId pd = in_data(q.object);
      selected = !pd.is_any() && data.count(TermId::any(), pd, TermId::any(), TermId::any(), 1);
    } else if (p == vocab::sh::targetNode) {
      const TermId n = in_data(q.object);
      selected = !n.is_any() && (data.count(n, TermId::any(), TermId::any(), TermId::any(), 1) ||
                                 data.count(TermId::any(), TermId::any(), n, TermId::any(), 1));
    } else if (q.predicate == s_type && q.object == node_shape && !rdfs_class.is_any() &&
               shapes.count(q.subject, s_type, rdfs_class, TermId::any(), 1)) {
      selected = typed(q.subject);  // an implicit class target
    }
    if (selected) return true;
  }
  return false;
}

// Whether every IRI node shape of `file` is already a node shape of `already`.
bool already_read(const rdf::Dataset& file, const rdf::Dataset& already) {
  const rdf::TermTable& ft = file.terms();
  const rdf::TermTable& at = already.terms();
  const TermId f_type = ft.find_iri(vocab::rdf::type), f_shape = ft.find_iri(vocab::sh::NodeShape);
  const TermId a_type = at.find_iri(vocab::rdf::type), a_shape = at.find_iri(vocab::sh::NodeShape);
  if (f_type.is_any() || f_shape.is_any()) return false;
  bool any = false, all = true;
  file.scan(TermId::any(), f_type, f_shape, TermId::any(), [&](const rdf::Quad& q, uint32_t) {
    if (!ft[q.subject].is_iri()) return true;
    any = true;
    const TermId s = at.find_iri(ft[q.subject].value);
    if (s.is_any() || a_type.is_any() || a_shape.is_any() ||
        !already.count(s, a_type, a_shape, TermId::any(), 1))
      all = false;
    return all;
  });
  return any && all;
}

// Copies `document` (one document read by rdf::read_turtle or read_trig into
// an empty dataset) into `into` as reading the same text into `into` would:
// terms are interned in the reader's order (a literal's datatype first, then
// subject, predicate, object, graph of each statement in turn), and every
// blank node's label gets `into`'s next fresh prefix in place of the one the
// reader gave it ("rN_", which ends at the label's first '_'). Quads already
// in `into` keep their first location, as Dataset::add does.
void merge_document(const rdf::Dataset& document, rdf::Dataset& into) {
  const rdf::TermTable& from = document.terms();
  rdf::TermTable& to = into.terms();
  const std::string prefix = to.fresh_blank_prefix();
  std::vector<TermId> mapped(from.size(), TermId::any());
  std::string label;
  auto map = [&](TermId t) {
    TermId& m = mapped[t.index];
    if (!m.is_any()) return m;
    const rdf::Term& term = from[t];
    if (term.is_blank()) {
      const size_t stem = term.value.find('_');
      label = prefix;
      label.append(stem == std::string_view::npos ? term.value : term.value.substr(stem + 1));
      m = to.blank(label);
    } else {
      m = to.import(from, t);
    }
    return m;
  };
  const std::span<const rdf::Quad> quads = document.quads();
  for (size_t i = 0; i < quads.size(); ++i) {
    const rdf::Quad& q = quads[i];
    const TermId s = map(q.subject), p = map(q.predicate), o = map(q.object), g = map(q.graph);
    into.add(rdf::Quad{s, p, o, g}, document.location(i));
  }
}

}  // namespace

std::vector<ShapeFile> vocabulary_shape_files(app::LoadedModel& model, rdf::Dataset& into,
                                              DiagnosticSink* diagnostics,
                                              std::span<const ShapeFile> read_before) {
  std::vector<ShapeFile> out;
  const std::string base(vocab::kMetamodels);
  const std::string manifest = model.loader().resolve(base + "mospec/shape-files.txt");
  std::error_code ec;
  if (manifest.empty() || !fs::is_regular_file(manifest, ec)) return out;
  std::vector<std::string> listed;
  for_each_line(read_file(manifest), [&](uint32_t, std::string line) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty() && line[0] != '#') listed.push_back(std::move(line));
  });
  for (const std::string& line : listed) {
    ShapeFile f;
    f.iri = base + line;
    f.path = model.loader().resolve(f.iri);
    f.automatic = true;
    if (f.path.empty()) continue;
    // A file the app lists is in `into` already: no need to read it to see so.
    if (std::any_of(read_before.begin(), read_before.end(),
                    [&](const ShapeFile& r) { return r.path == f.path; }))
      continue;
    rdf::Dataset shapes;
    read_shape_file(f, model.loader(), shapes, diagnostics);
    if (!selects_a_node(shapes, model.dataset()) || already_read(shapes, into)) continue;
    // The document's blank nodes need labels fresh in `into`, where `shapes`
    // could reuse labels: a Turtle or TriG file is copied over with its label
    // prefix replaced (the dataset `into` gets is the one reading the file
    // into it would give); any other syntax is read again.
    const std::string ext = lower_extension(f.path);
    if (ext == ".ttl" || ext == ".turtle" || ext == ".trig")
      merge_document(shapes, into);
    else
      read_shape_file(f, model.loader(), into, diagnostics);
    out.push_back(std::move(f));
  }
  return out;
}

// ---- one cause, one error -------------------------------------------------

void note_follow_on_results(shacl::Report& report, const rdf::Dataset& data) {
  const rdf::TermId any = rdf::TermId::any();
  const rdf::TermTable& rt = report.terms;
  const auto in_data = [&](rdf::TermId r) {
    return r.is_any() || !rt[r].is_iri() ? any : data.terms().find_iri(rt[r].value);
  };
  const auto undefined = [&](rdf::TermId value) {
    if (value.is_any() || !rt[value].is_iri()) return false;
    const rdf::TermId d = in_data(value);
    return d.is_any() || data.count(d, any, any) == 0;
  };
  // The cause of each undefined value: the result of mos:DefinedReferences,
  // which says exactly that. (Other IRIs no file defines, units and classes,
  // are no cause of anything.)
  const std::string defined_references = vocab::term(vocab::mospec_shapes::ns, "DefinedReferences");
  std::map<uint32_t, int> cause_of_value;  // report term index -> result index
  for (size_t i = 0; i < report.results.size(); ++i) {
    const shacl::Result& r = report.results[i];
    if (rt[r.shape].is_iri() && rt[r.shape].value == defined_references && undefined(r.value))
      cause_of_value.emplace(r.value.index, static_cast<int>(i));
  }
  std::set<int> causes;
  for (const auto& [value, i] : cause_of_value) {
    shacl::Result& r = report.results[static_cast<size_t>(i)];
    const std::string nearest = rdf::nearest_subject_iri(data, rt[r.value].value);
    if (!nearest.empty()) r.hint = "; did you mean <" + nearest + ">?";
    causes.insert(i);
  }
  for (size_t i = 0; i < report.results.size(); ++i) {
    shacl::Result& r = report.results[i];
    if (causes.count(static_cast<int>(i))) continue;
    if (auto it = cause_of_value.find(r.value.index);
        it != cause_of_value.end() && undefined(r.value)) {
      r.follows = it->second;
      continue;
    }
    // A node the cause's focus names (a handler's motion, a constraint's
    // quantity): what is reported about it likely follows from the dangling
    // reference beside it (a motion whose guard has no controller, because
    // the handler's controller is misspelt).
    const rdf::TermId focus = in_data(r.focus);
    if (focus.is_any()) continue;
    for (int c : causes) {
      const rdf::TermId cause_focus = in_data(report.results[static_cast<size_t>(c)].focus);
      if (!cause_focus.is_any() && data.count(cause_focus, any, focus) != 0) {
        r.follows = c;
        break;
      }
    }
  }
}

// ---- the pipeline ----------------------------------------------------------

ModelValidation validate_model(app::LoadedModel& model, const ModelValidationOptions& options) {
  ModelValidation out;
  out.files = shape_files(model, options.extra_shapes, options.use_app_constraints);
  out.shapes_graph = std::make_unique<rdf::Dataset>();
  for (const ShapeFile& f : out.files)
    read_shape_file(f, model.loader(), *out.shapes_graph, &out.shape_diagnostics);
  if (options.vocabulary_shapes && options.use_app_constraints) {
    for (ShapeFile& f :
         vocabulary_shape_files(model, *out.shapes_graph, &out.shape_diagnostics, out.files))
      out.files.push_back(std::move(f));
  }
  if (out.files.empty())
    throw Error("usage",
                "no shapes to validate against: the app names no constraints and its vocabulary "
                "does not resolve to mospec's metamodels; pass --shapes FILE");
  out.shapes = std::make_unique<Shapes>(Shapes::compile(*out.shapes_graph, &model.files()));
  ValidateOptions validate_options;
  validate_options.sparql_limits = options.sparql_limits;
  out.report = validate(*out.shapes, model.dataset(), validate_options);
  note_follow_on_results(out.report, model.dataset());
  if (options.strict) out.strict_findings = strict_checks(model, *out.shapes, out.files);
  return out;
}

}  // namespace mospec::validation
