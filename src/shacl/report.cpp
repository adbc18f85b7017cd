#include "shacl/report.hpp"

#include <algorithm>
#include <functional>
#include <numeric>
#include <tuple>

#include "json/json.hpp"
#include "vocab/w3c.hpp"

namespace mospec::shacl {

namespace {

using rdf::TermId;

std::string_view severity_iri(Level level) {
  switch (level) {
    case Level::Info:
      return vocab::sh::Info;
    case Level::Warning:
      return vocab::sh::Warning;
    default:
      return vocab::sh::Violation;
  }
}

std::string path_key(const rdf::TermTable& t, const sparql::PathPtr& p) {
  return p ? path_to_sparql(t, *p) : std::string();
}

std::string term_key(const rdf::TermTable& t, TermId id) {
  return id.is_any() ? std::string() : rdf::to_ntriples(t, id);
}

// Turtle for a term: sh:/rdf:/xsd: IRIs compacted, everything else as in N-Triples.
std::string turtle_term(const rdf::TermTable& t, TermId id) {
  const rdf::Term& term = t[id];
  if (term.is_iri()) {
    for (auto [ns, prefix] :
         {std::pair{vocab::sh::ns, "sh:"}, {vocab::rdf::ns, "rdf:"}, {vocab::xsd::ns, "xsd:"}}) {
      if (term.value.substr(0, ns.size()) != ns) continue;
      std::string_view local = term.value.substr(ns.size());
      bool simple = !local.empty() && std::all_of(local.begin(), local.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '_';
      });
      if (simple) return prefix + std::string(local);
    }
  }
  return rdf::to_ntriples(t, id);
}

void turtle_path(std::string& out, const rdf::TermTable& t, const sparql::Path& p,
                 const std::string& indent) {
  using K = sparql::Path::Kind;
  auto list = [&](const std::vector<sparql::PathPtr>& items) {
    out += "( ";
    for (const auto& item : items) {
      turtle_path(out, t, *item, indent);
      out += ' ';
    }
    out += ')';
  };
  auto wrapped = [&](std::string_view predicate) {
    out += "[ ";
    out += predicate;
    out += ' ';
    if (p.kind == K::Alternative)
      list(p.items);
    else
      turtle_path(out, t, *p.items[0], indent);
    out += " ]";
  };
  switch (p.kind) {
    case K::Predicate:
      out += turtle_term(t, p.predicate);
      return;
    case K::Sequence:
      list(p.items);
      return;
    case K::Alternative:
      wrapped("sh:alternativePath");
      return;
    case K::Inverse:
      wrapped("sh:inversePath");
      return;
    case K::ZeroOrMore:
      wrapped("sh:zeroOrMorePath");
      return;
    case K::OneOrMore:
      wrapped("sh:oneOrMorePath");
      return;
    case K::ZeroOrOne:
      wrapped("sh:zeroOrOnePath");
      return;
    case K::NegatedSet:
      out += "[]";
      return;
  }
}

// The message a human reads first: untagged, else English, else any.
std::string pick_message(const Report& r, const Result& x) {
  const rdf::TermTable& t = r.terms;
  for (std::string_view want : {std::string_view(), std::string_view("en")})
    for (TermId m : x.messages)
      if (t[m].language == want) return std::string(t[m].value);
  if (!x.messages.empty()) return std::string(t[x.messages[0]].value);
  return x.default_message;
}

std::string quote(std::string_view text) {
  std::string out = "\"";
  rdf::append_escaped_literal(out, text);
  out += '"';
  return out;
}

}  // namespace

std::string result_component_iri(const Report& report, const Result& r) {
  if (r.component == Component::SparqlComponent && !r.component_node.is_any())
    return std::string(report.terms[r.component_node].value);
  return std::string(component_iri(r.component));
}

std::string_view diagnostic_level(Level level) {
  switch (level) {
    case Level::Info:
      return "info";
    case Level::Warning:
      return "warning";
    case Level::Violation:
      return "error";
    case Level::Other:
      return "other";
  }
  return "error";
}

size_t Report::count(Level level) const {
  return static_cast<size_t>(std::count_if(results.begin(), results.end(),
                                           [&](const Result& r) { return r.level == level; }));
}

void Report::sort() {
  struct Key {
    bool unlocated;
    uint32_t file, line, column;
    std::string focus, shape;
    Component component;
    std::string component_node, path, value;
    auto tie() const {
      return std::tie(unlocated, file, line, column, focus, shape, component, component_node, path,
                      value);
    }
  };
  std::vector<Key> keys;
  keys.reserve(results.size());
  for (const Result& r : results) {
    keys.push_back(Key{!r.focus_loc.known(), r.focus_loc.file, r.focus_loc.line, r.focus_loc.column,
                       term_key(terms, r.focus), term_key(terms, r.shape), r.component,
                       term_key(terms, r.component_node), path_key(terms, r.path),
                       term_key(terms, r.value)});
  }
  std::vector<size_t> order(results.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return keys[a].tie() < keys[b].tie(); });
  std::vector<Result> sorted;
  sorted.reserve(results.size());
  for (size_t i : order) sorted.push_back(std::move(results[i]));
  results = std::move(sorted);
}

std::string to_turtle(const Report& report) {
  const rdf::TermTable& t = report.terms;
  std::string out;
  out += "@prefix rdf: <" MOSPEC_VOCAB_RDF "> .\n";
  out += "@prefix sh: <" MOSPEC_VOCAB_SH "> .\n";
  out += "@prefix xsd: <" MOSPEC_VOCAB_XSD "> .\n\n";
  out += "[] a sh:ValidationReport ;\n";
  out += report.conforms() ? "  sh:conforms true" : "  sh:conforms false";
  for (size_t i = 0; i < report.results.size(); ++i) {
    const Result& r = report.results[i];
    out += i == 0 ? " ;\n  sh:result [\n" : " , [\n";
    out += "    a sh:ValidationResult ;\n";
    out += "    sh:focusNode " + turtle_term(t, r.focus) + " ;\n";
    if (r.path) {
      out += "    sh:resultPath ";
      turtle_path(out, t, *r.path, "    ");
      out += " ;\n";
    }
    if (!r.value.is_any()) out += "    sh:value " + turtle_term(t, r.value) + " ;\n";
    for (TermId m : r.messages) out += "    sh:resultMessage " + turtle_term(t, m) + " ;\n";
    if (r.messages.empty() && !r.default_message.empty()) {
      out += "    sh:resultMessage " + quote(r.default_message) + " ;\n";
    }
    out += "    sh:resultSeverity " +
           (r.level == Level::Other
                ? turtle_term(t, r.severity)
                : "sh:" + std::string(severity_iri(r.level).substr(vocab::sh::ns.size()))) +
           " ;\n";
    out += "    sh:sourceConstraintComponent " +
           (r.component == Component::SparqlComponent ? turtle_term(t, r.component_node)
                                                      : std::string(component_name(r.component))) +
           " ;\n";
    if (!r.source_constraint.is_any())
      out += "    sh:sourceConstraint " + turtle_term(t, r.source_constraint) + " ;\n";
    out += "    sh:sourceShape " + turtle_term(t, r.shape) + " ;\n";
    out += "  ]";
  }
  out += " .\n";
  return out;
}

std::string to_text(const Report& report, const SourceFiles* data_files,
                    const SourceFiles* shape_files) {
  const rdf::TermTable& t = report.terms;
  std::string out;
  size_t followers = 0;
  for (const Result& r : report.results) {
    // The project's diagnostic shape: the finding at the model's node, then
    // a note at the shape that fired and at the other nodes involved.
    const auto file = [](const SourceFiles* files, SourceLoc loc) {
      if (!loc.known()) return std::string();
      std::string path = files != nullptr ? files->path(loc.file) : std::string();
      return path.empty() ? std::string("<input>") : path;
    };
    std::string message =
        rdf::to_ntriples(t, r.focus) + ": " + pick_message(report, r) + r.hint + " [";
    message += r.component == Component::SparqlComponent ? rdf::to_ntriples(t, r.component_node)
                                                         : std::string(component_name(r.component));
    if (r.path) message += ", path " + path_to_sparql(t, *r.path);
    if (!r.value.is_any()) message += ", value " + rdf::to_ntriples(t, r.value);
    message += "]";
    std::string level = r.level == Level::Other ? rdf::to_ntriples(t, r.severity)
                                                : std::string(diagnostic_level(r.level));
    if (r.follows >= 0 && static_cast<size_t>(r.follows) < report.results.size()) {
      const Result& cause = report.results[static_cast<size_t>(r.follows)];
      message +=
          " (likely a consequence of the " +
          std::string(cause.level == Level::Other ? "result" : diagnostic_level(cause.level)) +
          " at " +
          (cause.focus_loc.known() ? format_place(file(data_files, cause.focus_loc),
                                                  cause.focus_loc.line, cause.focus_loc.column)
                                   : rdf::to_ntriples(t, cause.focus)) +
          ", about " + rdf::to_ntriples(t, cause.value) + ": fix that first)";
      level = "note";
      ++followers;
    }
    out +=
        format(file(data_files, r.focus_loc), r.focus_loc.line, r.focus_loc.column, level, message);
    out += '\n';
    out += format(file(shape_files, r.shape_loc), r.shape_loc.line, r.shape_loc.column, "note",
                  "the shape that fired: " +
                      (t[r.shape].is_iri() ? rdf::to_ntriples(t, r.shape) : std::string("[]")));
    out += '\n';
    if (r.value_loc.known()) {
      out += format(file(data_files, r.value_loc), r.value_loc.line, r.value_loc.column, "note",
                    "the value " + rdf::to_ntriples(t, r.value) + " is here");
      out += '\n';
    }
    for (const Result::Related& x : r.related) {
      if (!x.where.known()) continue;
      out += format(file(data_files, x.where), x.where.line, x.where.column, "note",
                    x.name + " " + rdf::to_ntriples(t, x.node) + " is here");
      out += '\n';
    }
  }
  auto plural = [](size_t n, std::string_view one, std::string_view many) {
    return std::to_string(n) + " " + std::string(n == 1 ? one : many);
  };
  out += "shacl: " + plural(report.count(Level::Violation), "violation", "violations") + ", " +
         plural(report.count(Level::Warning), "warning", "warnings") + ", " +
         plural(report.count(Level::Info), "info", "infos");
  if (size_t other = report.count(Level::Other); other != 0)
    out += ", " + plural(other, "result of another severity", "results of other severities");
  if (followers != 0)
    out += " (" + std::to_string(followers) + " of them likely consequences of another, as noted)";
  out += "\n";
  return out;
}

rdf::Dataset to_dataset(const Report& report) {
  rdf::Dataset ds;
  rdf::TermTable& t = ds.terms();
  auto iri = [&](std::string_view s) { return t.iri(s); };
  auto in = [&](TermId id) { return t.import(report.terms, id); };
  // Import every report term first so that fresh blank nodes cannot collide.
  std::vector<std::vector<TermId>> imported;
  for (const Result& r : report.results) {
    std::vector<TermId> ids{in(r.focus), in(r.shape)};
    ids.push_back(r.value.is_any() ? TermId::any() : in(r.value));
    ids.push_back(r.severity.is_any() ? TermId::any() : in(r.severity));
    ids.push_back(r.source_constraint.is_any() ? TermId::any() : in(r.source_constraint));
    for (TermId m : r.messages) ids.push_back(in(m));
    imported.push_back(std::move(ids));
  }
  const std::string prefix = t.fresh_blank_prefix();
  size_t next = 0;
  auto fresh = [&] { return t.blank(prefix + std::to_string(next++)); };
  const TermId type = iri(vocab::rdf::type), first = iri(vocab::rdf::first),
               rest = iri(vocab::rdf::rest), nil = iri(vocab::rdf::nil);
  auto add = [&](TermId s, TermId p, TermId o) { ds.add(rdf::Quad{s, p, o}); };
  std::function<TermId(const sparql::Path&)> path = [&](const sparql::Path& p) -> TermId {
    using K = sparql::Path::Kind;
    auto make_list = [&](const std::vector<sparql::PathPtr>& items) {
      TermId head = nil;
      for (size_t i = items.size(); i-- > 0;) {
        TermId cell = fresh();
        add(cell, first, path(*items[i]));
        add(cell, rest, head);
        head = cell;
      }
      return head;
    };
    auto wrapped = [&](std::string_view predicate, TermId object) {
      TermId node = fresh();
      add(node, iri(predicate), object);
      return node;
    };
    switch (p.kind) {
      case K::Predicate:
        return in(p.predicate);
      case K::Sequence:
        return make_list(p.items);
      case K::Alternative:
        return wrapped(vocab::sh::alternativePath, make_list(p.items));
      case K::Inverse:
        return wrapped(vocab::sh::inversePath, path(*p.items[0]));
      case K::ZeroOrMore:
        return wrapped(vocab::sh::zeroOrMorePath, path(*p.items[0]));
      case K::OneOrMore:
        return wrapped(vocab::sh::oneOrMorePath, path(*p.items[0]));
      case K::ZeroOrOne:
        return wrapped(vocab::sh::zeroOrOnePath, path(*p.items[0]));
      case K::NegatedSet:
        return fresh();
    }
    return fresh();
  };
  TermId root = fresh();
  add(root, type, iri(vocab::sh::ValidationReport));
  add(root, iri(vocab::sh::conforms),
      t.literal(report.conforms() ? "true" : "false", vocab::xsd::boolean));
  for (size_t i = 0; i < report.results.size(); ++i) {
    const Result& r = report.results[i];
    const std::vector<TermId>& ids = imported[i];
    TermId node = fresh();
    add(root, iri(vocab::sh::result), node);
    add(node, type, iri(vocab::sh::ValidationResult));
    add(node, iri(vocab::sh::focusNode), ids[0]);
    add(node, iri(vocab::sh::sourceShape), ids[1]);
    if (!ids[2].is_any()) add(node, iri(vocab::sh::value), ids[2]);
    add(node, iri(vocab::sh::resultSeverity),
        ids[3].is_any() ? iri(severity_iri(r.level)) : ids[3]);
    if (!ids[4].is_any()) add(node, iri(vocab::sh::sourceConstraint), ids[4]);
    add(node, iri(vocab::sh::sourceConstraintComponent), iri(result_component_iri(report, r)));
    for (size_t m = 5; m < ids.size(); ++m) add(node, iri(vocab::sh::resultMessage), ids[m]);
    if (r.messages.empty() && !r.default_message.empty())
      add(node, iri(vocab::sh::resultMessage), t.literal(r.default_message));
    if (r.path) add(node, iri(vocab::sh::resultPath), path(*r.path));
  }
  return ds;
}

namespace {

// JSON-LD for one term of the report: {"@id"} for IRIs and blank nodes,
// a value object for literals (xsd:string without "@type").
json::Value jsonld_term(const rdf::TermTable& t, TermId id) {
  const rdf::Term& term = t[id];
  json::Object o;
  if (term.is_iri()) {
    o.set("@id", json::Value(std::string(term.value)));
  } else if (term.is_blank()) {
    o.set("@id", json::Value("_:" + std::string(term.value)));
  } else {
    o.set("@value", json::Value(std::string(term.value)));
    if (!term.language.empty()) {
      o.set("@language", json::Value(std::string(term.language)));
      if (!term.direction.empty()) o.set("@direction", json::Value(std::string(term.direction)));
    } else if (t[term.datatype].value != vocab::xsd::string) {
      o.set("@type", json::Value(std::string(t[term.datatype].value)));
    }
  }
  return json::Value(std::move(o));
}

json::Value sh_id(std::string_view iri) {
  json::Object o;
  std::string compact = "sh:";
  compact.append(iri.substr(vocab::sh::ns.size()));
  o.set("@id", json::Value(std::move(compact)));
  return json::Value(std::move(o));
}

json::Value jsonld_path(const rdf::TermTable& t, const sparql::Path& p) {
  using K = sparql::Path::Kind;
  auto list = [&](const std::vector<sparql::PathPtr>& items) {
    json::Array a;
    for (const auto& item : items) a.push_back(jsonld_path(t, *item));
    json::Object o;
    o.set("@list", json::Value(std::move(a)));
    return json::Value(std::move(o));
  };
  auto wrapped = [&](std::string_view predicate, json::Value inner) {
    json::Object o;
    std::string key = "sh:";
    key.append(predicate.substr(vocab::sh::ns.size()));
    o.set(std::move(key), std::move(inner));
    return json::Value(std::move(o));
  };
  switch (p.kind) {
    case K::Predicate:
      return jsonld_term(t, p.predicate);
    case K::Sequence:
      return list(p.items);
    case K::Alternative:
      return wrapped(vocab::sh::alternativePath, list(p.items));
    case K::Inverse:
      return wrapped(vocab::sh::inversePath, jsonld_path(t, *p.items[0]));
    case K::ZeroOrMore:
      return wrapped(vocab::sh::zeroOrMorePath, jsonld_path(t, *p.items[0]));
    case K::OneOrMore:
      return wrapped(vocab::sh::oneOrMorePath, jsonld_path(t, *p.items[0]));
    case K::ZeroOrOne:
      return wrapped(vocab::sh::zeroOrOnePath, jsonld_path(t, *p.items[0]));
    case K::NegatedSet:
      break;
  }
  return json::Value(json::Object{});
}

}  // namespace

std::string to_jsonld(const Report& report) {
  const rdf::TermTable& t = report.terms;
  json::Object context;
  context.set("sh", json::Value(std::string(vocab::sh::ns)));
  context.set("xsd", json::Value(std::string(vocab::xsd::ns)));
  json::Object root;
  root.set("@context", json::Value(std::move(context)));
  root.set("@type", json::Value("sh:ValidationReport"));
  root.set("sh:conforms", json::Value(report.conforms()));
  json::Array results;
  for (const Result& r : report.results) {
    json::Object o;
    o.set("@type", json::Value("sh:ValidationResult"));
    o.set("sh:focusNode", jsonld_term(t, r.focus));
    if (r.path) o.set("sh:resultPath", jsonld_path(t, *r.path));
    if (!r.value.is_any()) o.set("sh:value", jsonld_term(t, r.value));
    json::Array messages;
    for (TermId m : r.messages) messages.push_back(jsonld_term(t, m));
    if (r.messages.empty() && !r.default_message.empty()) {
      json::Object m;
      m.set("@value", json::Value(r.default_message));
      messages.push_back(json::Value(std::move(m)));
    }
    if (!messages.empty()) o.set("sh:resultMessage", json::Value(std::move(messages)));
    o.set("sh:resultSeverity",
          r.level == Level::Other ? jsonld_term(t, r.severity) : sh_id(severity_iri(r.level)));
    o.set("sh:sourceConstraintComponent", r.component == Component::SparqlComponent
                                              ? jsonld_term(t, r.component_node)
                                              : sh_id(component_iri(r.component)));
    if (!r.source_constraint.is_any())
      o.set("sh:sourceConstraint", jsonld_term(t, r.source_constraint));
    o.set("sh:sourceShape", jsonld_term(t, r.shape));
    results.push_back(json::Value(std::move(o)));
  }
  if (!results.empty()) root.set("sh:result", json::Value(std::move(results)));
  return json::dump(json::Value(std::move(root)), 2) + "\n";
}

}  // namespace mospec::shacl
