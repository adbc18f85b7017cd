// Helpers for the SHACL tests: Turtle snippets with the usual prefixes.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "rdf/dataset.hpp"
#include "rdf/turtle.hpp"
#include "shacl/report.hpp"
#include "shacl/shapes.hpp"
#include "shacl/validate.hpp"
#include "support/diagnostics.hpp"

namespace mospec::shacl::test_util {

inline const std::string kPrefixes =
    "@prefix sh: <http://www.w3.org/ns/shacl#> .\n"
    "@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .\n"
    "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .\n"
    "@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .\n"
    "@prefix ex: <http://example.org/> .\n";
// Lines that kPrefixes takes, so tests can name the line of their own text.
inline constexpr uint32_t kPrefixLines = 5;

struct Graph {
  SourceFiles files;
  rdf::Dataset data;
};

// Reads Turtle (prefixed with kPrefixes) as file `name`.
inline std::unique_ptr<Graph> turtle(const std::string& body,
                                     const std::string& name = "shapes.ttl") {
  auto g = std::make_unique<Graph>();
  uint32_t id = g->files.add(name);
  rdf::read_turtle(kPrefixes + body, "http://example.org/base", g->data, id, name);
  return g;
}

// Validates `data` against `shapes` (both Turtle bodies).
inline Report check(const std::string& shapes, const std::string& data) {
  auto s = turtle(shapes);
  auto d = turtle(data, "data.ttl");
  Shapes compiled = Shapes::compile(s->data, &s->files);
  return validate(compiled, d->data);
}

// Validates one graph that holds both shapes and data.
inline Report check_one(const std::string& both) {
  auto g = turtle(both);
  Shapes compiled = Shapes::compile(g->data, &g->files);
  return validate(compiled, g->data);
}

// Compiles and validates `body` as one graph, expecting a refusal; returns the
// error (a test failure, and a placeholder error, when there is none).
inline Error refused(const std::string& body) {
  auto g = turtle(body);
  try {
    Shapes shapes = Shapes::compile(g->data, &g->files);
    validate(shapes, g->data);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error for\n" << body;
  return Error(DiagnosticCode(), "");  // no error: no code
}

// The report as `mospec validate` prints it, for failure messages.
inline std::string text(const Report& r) {
  return to_text(r, nullptr);
}

}  // namespace mospec::shacl::test_util
