#include "jsonld/expand.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <memory_resource>
#include <string>
#include <string_view>

#include "jsonld/context.hpp"
#include "jsonld/loader.hpp"

namespace mospec::jsonld {
namespace {

class Expand : public ::testing::Test {
 protected:
  // Expands `text` as the document "doc.json" with base http://example.org/doc.
  json::Value run(std::string_view text, std::string_view name = "doc.json") {
    const uint32_t id = loader_.files().add(std::string(name));
    json::Value doc = json::parse(text, id, name);
    opts_.loader = &loader_;
    opts_.diagnostics = &sink_;
    if (opts_.base.empty()) opts_.base = "http://example.org/doc";
    return expand(doc, opts_);
  }

  // Expands `text` and compares with `expected` (JSON-LD object comparison of
  // json::Value: member order ignored, array order kept).
  void expect_expands(std::string_view text, std::string_view expected) {
    json::Value got = run(text);
    json::Value want = json::parse(expected);
    EXPECT_EQ(got, want) << "got:  " << json::dump(got) << "\nwant: " << json::dump(want);
  }

  // Expands `text` expecting failure with `code`; returns the error.
  Diagnostic expect_error(std::string_view text, const std::string& code) {
    try {
      run(text);
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), code) << e.what();
      return e.diagnostic();
    }
    ADD_FAILURE() << "expanded without error: " << text;
    return {};
  }

  MappedDocumentLoader loader_;
  DiagnosticSink sink_;
  Options opts_;
};

// ---------------------------------------------------------------------------
// Type-scoped contexts

TEST_F(Expand, TypeScopedContextsApplyForEveryTypeInCodePointOrder) {
  // "A" sorts before "B", so B's definition of p wins whatever the array order.
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/",
                 "B": {"@context": {"p": "http://b/p"}},
                 "A": {"@context": {"p": "http://a/p", "q": "http://a/q"}}},
    "@type": ["B", "A"], "p": 1, "q": 2})",
                 R"([{"@type": ["http://ex/B", "http://ex/A"],
                      "http://b/p": [{"@value": 1}], "http://a/q": [{"@value": 2}]}])");
}

TEST_F(Expand, TypeScopedLookupUsesContextBeforeTypeScoping) {
  // A's scoped context redefines B; B's own scoped context and its IRI still
  // come from the context as it was before any type-scoped context.
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/",
                 "A": {"@context": {"B": {"@id": "http://other/B",
                                          "@context": {"p": "http://other/p"}}}},
                 "B": {"@context": {"p": "http://b/p"}}},
    "@type": ["A", "B"], "p": 1})",
                 R"([{"@type": ["http://ex/A", "http://ex/B"], "http://b/p": [{"@value": 1}]}])");
}

TEST_F(Expand, TypeScopedContextDoesNotPropagateToNestedNodes) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/", "T": {"@context": {"q": "http://t/q"}}},
    "@type": "T",
    "q": [{"q": "inner"}, {"@value": "v"}, {"@id": "http://ex/n"}]})",
                 R"([{"@type": ["http://ex/T"],
                      "http://t/q": [{"http://ex/q": [{"@value": "inner"}]},
                                     {"@value": "v"}, {"@id": "http://ex/n"}]}])");
}

TEST_F(Expand, TypeScopedContextWithPropagateTrueReachesNestedNodes) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/",
                 "T": {"@context": {"@propagate": true, "q": "http://t/q"}}},
    "@type": "T", "q": {"q": "inner"}})",
                 R"([{"@type": ["http://ex/T"],
                      "http://t/q": [{"http://t/q": [{"@value": "inner"}]}]}])");
}

// ---------------------------------------------------------------------------
// Property-scoped contexts, @nest, @included, @reverse

TEST_F(Expand, PropertyScopedContextWithBase) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/",
                 "p": {"@context": {"@base": "http://other.org/dir/"}}},
    "@id": "rel", "p": {"@id": "inner"}})",
                 R"([{"@id": "http://example.org/rel",
                      "http://ex/p": [{"@id": "http://other.org/dir/inner"}]}])");
}

TEST_F(Expand, PropertyScopedContextPropagatesToNestedNodes) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/", "p": {"@context": {"q": "http://p/q"}}},
    "p": {"q": {"q": 1}}})",
                 R"([{"http://ex/p": [{"http://p/q": [{"http://p/q": [{"@value": 1}]}]}]}])");
}

TEST_F(Expand, KeywordAliasesAddedOrRemovedByScopedAndEmbeddedContexts) {
  // Aliases defined only in a property-scoped context, over contexts without any.
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/", "p": {"@context": {"kind": "@type", "val": "@value"}}},
    "p": [{"kind": "T", "q": 1}, {"val": "v"}]})",
                 R"([{"http://ex/p": [{"@type": ["http://ex/T"], "http://ex/q": [{"@value": 1}]},
                                      {"@value": "v"}]}])");
  // An alias of the outer context, mapped to null by an embedded context.
  expect_expands(
      R"({
    "@context": {"@vocab": "http://ex/", "kind": "@type"},
    "kind": "A", "r": {"@context": {"kind": null}, "kind": "B", "s": 2}})",
      R"([{"@type": ["http://ex/A"], "http://ex/r": [{"http://ex/s": [{"@value": 2}]}]}])");
  sink_.clear();
}

TEST_F(Expand, ScopedContextsMetAgainExpandAlikeWithAndWithoutACache) {
  // Each node meets the same type-scoped and property-scoped contexts over the
  // same active context, and the last one over another (its own @context,
  // whose @vocab reaches only the key no scoped context defines).
  const std::string doc = R"({
    "@context": {"@vocab": "http://ex/",
                 "T": {"@context": {"q": {"@id": "http://t/q", "@type": "@id"}}},
                 "p": {"@context": {"r": {"@id": "http://p/r", "@type": "@id"}}}},
    "@graph": [
      {"@id": "n1", "@type": "T", "q": "a", "p": {"r": "b"}},
      {"@id": "n2", "@type": "T", "q": "c", "p": {"r": "d"}},
      {"@context": {"@vocab": "http://other/"}, "@id": "n3", "@type": "T", "q": "e",
       "p": {"r": "f", "s": 1}}]})";
  const std::string want = R"([
    {"@id": "http://example.org/n1", "@type": ["http://ex/T"],
     "http://t/q": [{"@id": "http://example.org/a"}],
     "http://ex/p": [{"http://p/r": [{"@id": "http://example.org/b"}]}]},
    {"@id": "http://example.org/n2", "@type": ["http://ex/T"],
     "http://t/q": [{"@id": "http://example.org/c"}],
     "http://ex/p": [{"http://p/r": [{"@id": "http://example.org/d"}]}]},
    {"@id": "http://example.org/n3", "@type": ["http://ex/T"],
     "http://t/q": [{"@id": "http://example.org/e"}],
     "http://ex/p": [{"http://p/r": [{"@id": "http://example.org/f"}],
                      "http://other/s": [{"@value": 1}]}]}])";
  expect_expands(doc, want);
  opts_.context_cache = std::make_shared<ContextCache>();
  expect_expands(doc, want);
  expect_expands(doc, want);  // and again, from the cache's earlier results
  sink_.clear();
}

TEST_F(Expand, NestUnfoldsIntoTheNode) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/", "meta": "@nest",
                 "n": {"@id": "http://ex/n", "@nest": "meta"}},
    "@id": "http://ex/a",
    "meta": [{"p": 1, "meta": {"q": 2}}, {"n": 3}]})",
                 R"([{"@id": "http://ex/a", "http://ex/p": [{"@value": 1}],
                      "http://ex/q": [{"@value": 2}], "http://ex/n": [{"@value": 3}]}])");
}

TEST_F(Expand, NestRejectsValueObjects) {
  Diagnostic d = expect_error(R"({"@context": {"@vocab": "http://ex/", "m": "@nest"},
    "m": {"@value": 1}})",
                              "invalid @nest value");
  EXPECT_EQ(d.file, "doc.json");
  EXPECT_EQ(d.line, 2u);
  EXPECT_EQ(d.column, 10u);
}

TEST_F(Expand, Included) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/"},
    "@id": "http://ex/a",
    "@included": [{"@id": "http://ex/b", "p": 1}]})",
                 R"([{"@id": "http://ex/a",
                      "@included": [{"@id": "http://ex/b", "http://ex/p": [{"@value": 1}]}]}])");
  expect_error(R"({"@context": {"@vocab": "http://ex/"}, "@included": [{"@value": 1}]})",
               "invalid @included value");
}

TEST_F(Expand, ReverseProperties) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/", "child": {"@reverse": "http://ex/parent"}},
    "@id": "http://ex/a", "child": {"@id": "http://ex/b"}})",
                 R"([{"@id": "http://ex/a",
                      "@reverse": {"http://ex/parent": [{"@id": "http://ex/b"}]}}])");
  // Reversed twice is forward.
  expect_expands(R"({"@context": {"likedBy": {"@reverse": "http://ex/likes"}},
    "@id": "http://ex/a",
    "@reverse": {"http://ex/knows": {"@id": "http://ex/c"},
                 "likedBy": {"@id": "http://ex/d"}}})",
                 R"([{"@id": "http://ex/a", "http://ex/likes": [{"@id": "http://ex/d"}],
                      "@reverse": {"http://ex/knows": [{"@id": "http://ex/c"}]}}])");
  expect_error(R"({"@context": {"r": {"@reverse": "http://ex/r"}}, "r": "lit"})",
               "invalid reverse property value");
}

// ---------------------------------------------------------------------------
// Containers and values

TEST_F(Expand, IndexAndPropertyValuedIndexMaps) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/",
                 "byIndex": {"@container": "@index"},
                 "byProp": {"@container": "@index", "@index": "tag"}},
    "byIndex": {"x": "v", "@none": "w"},
    "byProp": {"t1": {"@id": "http://ex/n"}}})",
                 R"([{"http://ex/byIndex": [{"@value": "v", "@index": "x"}, {"@value": "w"}],
                      "http://ex/byProp": [{"@id": "http://ex/n",
                                            "http://ex/tag": [{"@value": "t1"}]}]}])");
  expect_error(R"({"@context": {"@vocab": "http://ex/",
                 "byProp": {"@container": "@index", "@index": "tag"}},
    "byProp": {"t1": "a literal"}})",
               "invalid value object");
}

TEST_F(Expand, IdAndTypeMaps) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/",
                 "ids": {"@container": "@id"}, "types": {"@container": "@type"},
                 "T": {"@context": {"p": "http://t/p"}}},
    "ids": {"n1": {"p": 1}},
    "types": {"T": {"p": 2}, "@none": {"@id": "http://ex/z"}}})",
                 R"([{"http://ex/ids": [{"@id": "http://example.org/n1",
                                         "http://ex/p": [{"@value": 1}]}],
                      "http://ex/types": [{"@type": ["http://ex/T"],
                                           "http://t/p": [{"@value": 2}]},
                                          {"@id": "http://ex/z"}]}])");
}

TEST_F(Expand, LanguageMapsAndDirection) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/", "@direction": "ltr",
                 "label": {"@container": "@language"}},
    "label": {"en": ["a", null], "@none": "b"}})",
                 R"([{"http://ex/label": [
                      {"@value": "a", "@language": "en", "@direction": "ltr"},
                      {"@value": "b", "@direction": "ltr"}]}])");
  expect_error(R"({"@context": {"l": {"@id": "http://ex/l", "@container": "@language"}},
    "l": {"en": 5}})",
               "invalid language map value");
}

TEST_F(Expand, GraphContainers) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/",
                 "g": {"@container": "@graph"},
                 "gi": {"@container": ["@graph", "@index"]}},
    "g": {"p": 1},
    "gi": {"k": {"p": 2}}})",
                 R"([{"http://ex/g": [{"@graph": [{"http://ex/p": [{"@value": 1}]}]}],
                      "http://ex/gi": [{"@graph": [{"http://ex/p": [{"@value": 2}]}],
                                        "@index": "k"}]}])");
}

TEST_F(Expand, ListsAndSets) {
  expect_expands(R"({
    "@context": {"@vocab": "http://ex/", "l": {"@container": "@list"}},
    "l": [["a"], "b"], "s": {"@set": [1, 2]}})",
                 R"([{"http://ex/l": [{"@list": [{"@list": [{"@value": "a"}]}, {"@value": "b"}]}],
                      "http://ex/s": [{"@value": 1}, {"@value": 2}]}])");
  expect_error(R"({"http://ex/p": {"@list": [1], "@id": "x"}})", "invalid set or list object");
}

TEST_F(Expand, JsonLiteralsKeptAsIs) {
  expect_expands(R"({
    "@context": {"j": {"@id": "http://ex/j", "@type": "@json"}},
    "j": {"b": [1, {"@id": "not-expanded"}], "a": null}})",
                 R"([{"http://ex/j": [{"@value": {"b": [1, {"@id": "not-expanded"}], "a": null},
                                       "@type": "@json"}]}])");
}

TEST_F(Expand, ValueObjectErrors) {
  expect_error(R"({"http://ex/p": {"@value": "x", "@type": "http://ex/t", "@language": "en"}})",
               "invalid value object");
  expect_error(R"({"http://ex/p": {"@value": 1, "@language": "en"}})",
               "invalid language-tagged value");
  expect_error(R"({"http://ex/p": {"@value": "x", "@type": "_:b"}})", "invalid typed value");
  expect_error(R"({"http://ex/p": {"@value": [1]}})", "invalid value object value");
  expect_error(R"({"http://ex/p": {"@value": "x", "@language": 1}})",
               "invalid language-tagged string");
  expect_error(R"({"http://ex/p": {"@value": "x", "@direction": "up"}})", "invalid base direction");
  expect_error(R"({"http://ex/p": {"@value": "x", "@index": 1}})", "invalid @index value");
  expect_error(R"({"@type": {"a": 1}})", "invalid type value");
  expect_error(R"({"@context": {"id": "@id"}, "@id": "a", "id": "b"})", "colliding keywords");
  expect_error(R"({"@reverse": {"@id": "x"}})", "invalid reverse property map");
}

TEST_F(Expand, InvalidIdNamesKeyAndLocation) {
  Diagnostic d = expect_error("{\n  \"@id\": 5\n}", "invalid @id value");
  EXPECT_EQ(d.file, "doc.json");
  EXPECT_EQ(d.line, 2u);
  EXPECT_EQ(d.column, 10u);
  EXPECT_NE(d.message.find("\"@id\""), std::string::npos) << d.message;
}

TEST_F(Expand, ProcessingMode10IgnoresNewKeywords) {
  opts_.processing_mode = ProcessingMode::JsonLd10;
  expect_expands(R"({"@id": "http://ex/a", "@included": [{"@id": "http://ex/b"}],
    "http://ex/p": {"@value": "x", "@direction": "rtl"}})",
                 R"([{"@id": "http://ex/a", "http://ex/p": [{"@value": "x"}]}])");
}

TEST_F(Expand, ResultShapeAndExpandContext) {
  // A lone @graph is unwrapped; null and free-floating values give [].
  expect_expands(R"({"@graph": [{"@id": "http://ex/a", "http://ex/p": 1}]})",
                 R"([{"@id": "http://ex/a", "http://ex/p": [{"@value": 1}]}])");
  expect_expands("null", "[]");
  expect_expands(R"({"@id": "http://ex/a"})", "[]");
  opts_.expand_context = json::parse(R"({"@context": {"p": "http://ex/p"}})");
  expect_expands(R"({"p": 1})", R"([{"http://ex/p": [{"@value": 1}]}])");
}

TEST_F(Expand, OrderedSortsKeys) {
  opts_.ordered = true;
  json::Value out = run(R"({"http://ex/b": 1, "http://ex/a": 2, "@id": "http://ex/n"})");
  const json::Object& node = out.as_array().at(0).as_object();
  ASSERT_EQ(node.size(), 3u);
  EXPECT_EQ(node.key(0), "@id");
  EXPECT_EQ(node.key(1), "http://ex/a");
  EXPECT_EQ(node.key(2), "http://ex/b");
}

// ---------------------------------------------------------------------------
// Source locations

TEST_F(Expand, OutputKeepsSourceLocations) {
  json::Value out = run("[\n  {\"@id\": \"http://ex/a\",\n   \"http://ex/p\": \"v\"}\n]");
  const json::Value& node = out.as_array().at(0);
  EXPECT_EQ(node.location().line, 2u);
  EXPECT_EQ(node.location().column, 3u);
  EXPECT_EQ(loader_.files().path(node.location().file), "doc.json");
  const json::Value* id = node.get("@id");
  ASSERT_NE(id, nullptr);
  EXPECT_EQ(id->location().line, 2u);
  EXPECT_EQ(id->location().column, 11u);
  const json::Value& value = node.get("http://ex/p")->as_array().at(0);
  EXPECT_EQ(value.location().line, 3u);
  EXPECT_EQ(value.location().column, 19u);
  EXPECT_EQ(value.get("@value")->location().column, 19u);
}

// ---------------------------------------------------------------------------
// Silent drops made visible

TEST_F(Expand, DroppedKeyIsReportedAtTheKey) {
  json::Value out = run(R"({
  "@context": {"@base": "https://example.org/models/", "name": "http://ex/name"},
  "@id": "chain-rightarm",
  "name": "c",
  "kinematic-chain": "chain-leftarm"
})");
  ASSERT_EQ(sink_.diagnostics().size(), 1u);
  const Diagnostic& d = sink_.diagnostics()[0];
  EXPECT_EQ(d.severity, Severity::Warning);
  EXPECT_EQ(d.code, "dropped-key");
  EXPECT_EQ(d.file, "doc.json");
  EXPECT_EQ(d.line, 5u);
  EXPECT_EQ(d.column, 3u);
  EXPECT_EQ(d.message,
            "key \"kinematic-chain\" expands to no IRI and is dropped "
            "(node <https://example.org/models/chain-rightarm>)");
  EXPECT_EQ(format(d),
            "doc.json:5:3: warning: key \"kinematic-chain\" expands to no IRI and is dropped "
            "(node <https://example.org/models/chain-rightarm>)");
  // The key stays dropped: reporting does not change the result.
  EXPECT_EQ(out, json::parse(R"([{"@id": "https://example.org/models/chain-rightarm",
                                  "http://ex/name": [{"@value": "c"}]}])"));
}

// A misspelt property or type: the warning names the nearest defined term.
TEST_F(Expand, ADroppedKeyOrUndefinedTypeSuggestsTheNearestTerm) {
  run(R"({
  "@context": {"@base": "https://example.org/models/", "lower-threshold": "http://ex/lower",
               "Constraint": "http://ex/Constraint"},
  "@id": "c",
  "@type": "Constriant",
  "lower-treshold": 0.6,
  "gain": 2
})");
  ASSERT_EQ(sink_.diagnostics().size(), 3u);
  std::vector<std::string> messages;
  for (const Diagnostic& d : sink_.diagnostics()) messages.push_back(d.message);
  std::sort(messages.begin(), messages.end());
  EXPECT_EQ(messages[0],
            "@type value \"Constriant\" is not a defined term and resolves against the base to "
            "<https://example.org/models/Constriant>; did you mean \"Constraint\"? "
            "(node <https://example.org/models/c>)");
  // Nothing defined is near "gain": no suggestion.
  EXPECT_EQ(messages[1],
            "key \"gain\" expands to no IRI and is dropped (node <https://example.org/models/c>)");
  EXPECT_EQ(messages[2],
            "key \"lower-treshold\" expands to no IRI and is dropped; did you mean "
            "\"lower-threshold\"? (node <https://example.org/models/c>)");
}

TEST_F(Expand, DroppedKeysInNestedAndAnonymousNodes) {
  run(R"({"http://ex/p": {"oops": 1}, "@id": "http://ex/a", "@bogus": 2})");
  ASSERT_EQ(sink_.diagnostics().size(), 2u);
  EXPECT_EQ(sink_.diagnostics()[0].message,
            "key \"oops\" expands to no IRI and is dropped (node without @id)");
  EXPECT_EQ(sink_.diagnostics()[0].column, 18u);
  EXPECT_EQ(sink_.diagnostics()[1].message,
            "key \"@bogus\" expands to no IRI and is dropped (node <http://ex/a>)");
}

TEST_F(Expand, UndefinedTypeIsReportedAtTheValue) {
  json::Value out = run(R"({
  "@context": {"@base": "https://example.org/models/",
               "Point": "http://ex/Point", "ex": "http://ex/"},
  "@id": "rot-wrench",
  "@type": ["Point", "ex:Frame", "http://ex/Abs", "RotateWrenchToProximalWithPose"]
})");
  ASSERT_EQ(sink_.diagnostics().size(), 1u);
  const Diagnostic& d = sink_.diagnostics()[0];
  EXPECT_EQ(d.code, "undefined-type");
  EXPECT_EQ(d.severity, Severity::Warning);
  EXPECT_EQ(d.file, "doc.json");
  EXPECT_EQ(d.line, 5u);
  EXPECT_EQ(d.column, 51u);
  EXPECT_EQ(d.message,
            "@type value \"RotateWrenchToProximalWithPose\" is not a defined term and resolves "
            "against the base to <https://example.org/models/RotateWrenchToProximalWithPose> "
            "(node <https://example.org/models/rot-wrench>)");
  const json::Value& types = *out.as_array().at(0).get("@type");
  EXPECT_EQ(types.as_array().at(3).as_string(),
            "https://example.org/models/RotateWrenchToProximalWithPose");
}

TEST_F(Expand, KeywordLikeIdIsKeptAsNullAndReported) {
  json::Value out = run(R"({"http://ex/p": {"@id": "@ignoreMe", "http://ex/q": 1}})");
  EXPECT_EQ(out, json::parse(R"([{"http://ex/p": [{"@id": null,
                                                    "http://ex/q": [{"@value": 1}]}]}])"));
  ASSERT_EQ(sink_.diagnostics().size(), 1u);
  EXPECT_EQ(sink_.diagnostics()[0].code, "dropped-id");
  EXPECT_EQ(sink_.diagnostics()[0].column, 25u);
}

// toRdf drops an @id that is no well-formed IRI (the W3C suites expect that);
// it is reported where it is written, escaped, never silently.
TEST_F(Expand, MalformedIdsAreReported) {
  run(R"({"@context": {"ex": "http://ex/", "ref": {"@id": "ex:ref", "@type": "@id"}},
    "@graph": [{"@id": "http://ex/a b", "ex:p": 1},
               {"@id": "http://ex/ok", "ref": ["http://ex/c\"d", "http://ex/fine", "ex:e\\f"]},
               {"@id": "http://ex/ok2", "ex:q": {"@id": "http://ex/<g>"}}]})");
  ASSERT_EQ(sink_.diagnostics().size(), 4u);
  for (const auto& d : sink_.diagnostics()) {
    EXPECT_EQ(d.code, "malformed-id");
    EXPECT_EQ(d.severity, mospec::Severity::Warning);
  }
  std::vector<std::string> messages;
  for (const auto& d : sink_.diagnostics()) {
    messages.push_back(std::to_string(d.line) + ":" + std::to_string(d.column) + " " + d.message);
  }
  std::sort(messages.begin(), messages.end());
  EXPECT_EQ(
      messages[0],
      "2:24 @id value \"http://ex/a b\" is not a well-formed IRI (it contains a space "
      "(U+0020; write %20)); JSON-LD drops it and the triples that use it (node <http://ex/a b>)");
  EXPECT_EQ(messages[1],
            "3:48 @id value \"http://ex/c\\\"d\" is not a well-formed IRI (it contains '\"' "
            "(U+0022), which IRIs exclude); JSON-LD drops it and the triples that use it");
  EXPECT_EQ(messages[2],
            "3:84 @id value \"ex:e\\\\f\" is not a well-formed IRI (it contains '\\' (U+005C), "
            "which IRIs exclude); JSON-LD drops it and the triples that use it");
  EXPECT_EQ(messages[3],
            "4:57 @id value \"http://ex/<g>\" is not a well-formed IRI (it contains '<' "
            "(U+003C), which IRIs exclude); JSON-LD drops it and the triples that use it (node "
            "<http://ex/<g>>)");
}

TEST_F(Expand, DroppedKeyInsideNestIsReportedForItsNode) {
  run(R"({"@context": {"@vocab": "http://ex/", "meta": "@nest", "x": null},
    "@id": "http://ex/a", "meta": {"x": 1}})");
  ASSERT_EQ(sink_.diagnostics().size(), 1u);
  EXPECT_EQ(sink_.diagnostics()[0].message,
            "key \"x\" expands to no IRI and is dropped (node <http://ex/a>)");
  EXPECT_EQ(sink_.diagnostics()[0].line, 2u);
  EXPECT_EQ(sink_.diagnostics()[0].column, 36u);
}

TEST_F(Expand, DroppedKeyNamesBlankNodesAndReverseMaps) {
  run(R"({"@id": "_:b1", "k1": 1, "@reverse": {"k2": {"@id": "http://ex/b"}}})");
  ASSERT_EQ(sink_.diagnostics().size(), 2u);
  EXPECT_EQ(sink_.diagnostics()[0].message,
            "key \"k2\" expands to no IRI and is dropped (in @reverse)");
  EXPECT_EQ(sink_.diagnostics()[1].message,
            "key \"k1\" expands to no IRI and is dropped (node _:b1)");
}

TEST_F(Expand, UndefinedTypeInTypeMapKey) {
  run(R"({"@context": {"t": {"@id": "http://ex/t", "@container": "@type"}},
    "t": {"Widget": {"@id": "http://ex/w"}}})");
  ASSERT_EQ(sink_.diagnostics().size(), 1u);
  EXPECT_EQ(sink_.diagnostics()[0].code, "undefined-type");
  EXPECT_EQ(sink_.diagnostics()[0].line, 2u);
  EXPECT_EQ(sink_.diagnostics()[0].column, 11u);
}

TEST_F(Expand, ErrorsWithoutLoaderNameTheInput) {
  opts_.base = "http://example.org/doc";
  json::Value doc = json::parse("{\"@id\": true}");
  try {
    expand(doc, opts_);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid @id value");
    EXPECT_EQ(std::string(e.what()),
              "<input>:1:9: error: \"@id\" must be a string, found a boolean");
  }
}

TEST_F(Expand, ProcessingMode10Errors) {
  opts_.processing_mode = ProcessingMode::JsonLd10;
  expect_error(R"({"@context": {"type": "@type"}, "@type": "http://ex/A", "type": "http://ex/B"})",
               "colliding keywords");
  expect_error(R"({"http://ex/p": {"@reverse": "x"}})", "invalid @reverse value");
}

TEST_F(Expand, VocabRelativeTypeIsNotReported) {
  run(R"({"@context": {"@vocab": "http://ex/"}, "@id": "http://ex/a", "@type": "Thing"})");
  EXPECT_TRUE(sink_.diagnostics().empty());
}

TEST_F(Expand, NoSinkNoReports) {
  opts_.base = "http://example.org/doc";
  opts_.diagnostics = nullptr;
  json::Value doc = json::parse(R"({"@id": "a", "@type": "T", "k": 1})");
  json::Value out = expand(doc, opts_);
  EXPECT_EQ(out, json::parse(R"([{"@id": "http://example.org/a",
                                  "@type": ["http://example.org/T"]}])"));
}

// Options::property_prefix_seen: set for a property of the result in the
// watched namespace wherever it is (nested node, @reverse, property-valued
// index), never for one only mentioned as a value or a type.
TEST_F(Expand, PropertyPrefixSeenOnlyForPropertiesInTheNamespace) {
  auto seen = [this](std::string_view text) {
    bool flag = false;
    opts_.property_prefix = "http://app/";
    opts_.property_prefix_seen = &flag;
    run(text);
    return flag;
  };
  EXPECT_FALSE(seen(R"({"@id": "http://app/x", "@type": "http://app/T",
                        "http://ex/p": {"@id": "http://app/y"}})"));
  EXPECT_TRUE(seen(R"({"http://ex/p": {"http://ex/q": {"http://app/import": "m"}}})"));
  EXPECT_TRUE(seen(R"({"@id": "http://ex/a", "@reverse": {"http://app/import": {"@id": "b"}}})"));
  EXPECT_TRUE(seen(R"({"@context": {"r": {"@reverse": "http://app/import"}},
                       "@id": "http://ex/a", "r": {"@id": "http://ex/b"}})"));
  EXPECT_TRUE(seen(R"({"@context": {"@version": 1.1,
                         "m": {"@id": "http://ex/m", "@container": "@index",
                               "@index": "http://app/k"}},
                       "m": {"i": {"@id": "http://ex/n"}}})"));
}

// ---------------------------------------------------------------------------
// The paper authors' models

TEST(ExpandUpstream, ModelsReportUndefinedTypesAndDroppedKeys) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(MOSPEC_SHARED_DIR) / "upstream" / "motion-spec-ral";
  if (!fs::exists(root / "models")) {
    GTEST_SKIP() << "upstream models not found under " << root;
  }
  MappedDocumentLoader loader;
  loader.map("https://comp-rob2b.github.io/metamodels/", (root / "comp-rob2b/metamodels").string());
  DiagnosticSink sink;
  Options opts;
  opts.loader = &loader;
  opts.diagnostics = &sink;
  size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root / "models")) {
    if (entry.path().extension() != ".json") continue;
    RemoteDocument doc = loader.load_file(entry.path().string());
    opts.base = doc.document_url;
    json::Value out = expand(*doc.document, opts);
    EXPECT_TRUE(out.is_array());
    ++files;
  }
  EXPECT_GT(files, 20u);
  bool rotate = false;
  bool chain = false;
  for (const Diagnostic& d : sink.diagnostics()) {
    if (d.code == "undefined-type" &&
        d.message.find("\"RotateWrenchToProximalWithPose\"") != std::string::npos &&
        d.file.ends_with("01-right-arm/00-misc.json")) {
      rotate = true;
      EXPECT_EQ(d.line, 78u);
    }
    if (d.code == "dropped-key" && d.message.find("\"kinematic-chain\"") != std::string::npos &&
        d.file.ends_with("04-sc0a-right-arm/07-scenario.json")) {
      chain = true;
      EXPECT_EQ(d.line, 56u);
      EXPECT_EQ(d.column, 13u);
    }
  }
  EXPECT_TRUE(rotate) << "no undefined-type for RotateWrenchToProximalWithPose";
  EXPECT_TRUE(chain) << "no dropped-key for kinematic-chain";
}

// ---------------------------------------------------------------------------
// Output in an arena

// The path of the first object or array of `v` that does not live in `mem`,
// or "" when all do.
std::string outside(const json::Value& v, json::Resource* mem, const std::string& path = "$") {
  if (v.is_array()) {
    if (v.as_array().get_allocator().resource() != mem) return path;
    for (size_t i = 0; i < v.as_array().size(); ++i) {
      std::string p = outside(v.as_array()[i], mem, path + "[" + std::to_string(i) + "]");
      if (!p.empty()) return p;
    }
  }
  if (v.is_object()) {
    const json::Object& o = v.as_object();
    if (o.resource() != mem) return path;
    for (size_t i = 0; i < o.size(); ++i) {
      std::string p = outside(o.value(i), mem, path + "." + std::string(o.key(i)));
      if (!p.empty()) return p;
    }
  }
  return "";
}

TEST_F(Expand, OutputBuiltInAnArenaEqualsTheHeapOutputAndStaysInIt) {
  // Every kind of output the expander builds: node, value, list, set, graph
  // and @json objects, language, index, id and type maps, reverse
  // properties, nested properties, and scalars copied from the input.
  constexpr std::string_view kDoc = R"({
    "@context": {
      "@vocab": "http://example.org/vocab#",
      "list": {"@container": "@list"},
      "set": {"@container": "@set"},
      "label": {"@container": "@language"},
      "byIndex": {"@container": "@index"},
      "byId": {"@container": "@id"},
      "byType": {"@container": "@type"},
      "graph": {"@container": "@graph"},
      "data": {"@type": "@json"},
      "ref": {"@type": "@id"},
      "parent": {"@reverse": "http://example.org/vocab#child"},
      "nested": "@nest"
    },
    "@id": "http://example.org/a-node-with-a-long-identifier",
    "@type": "Thing",
    "list": [1, "two", {"@id": "http://example.org/three"}],
    "set": ["a", "b"],
    "label": {"en": "a label long enough to allocate", "de": ["eins", "zwei"]},
    "byIndex": {"first": {"name": "indexed"}},
    "byId": {"http://example.org/by-id": {"name": "by id"}},
    "byType": {"Kind": {"name": "by type"}},
    "graph": {"name": "in a graph"},
    "data": {"any": ["json", 1, true, null]},
    "ref": "http://example.org/referenced-node",
    "parent": {"@id": "http://example.org/the-parent"},
    "nested": {"inner": "a nested property value long enough"},
    "@included": [{"@id": "http://example.org/included"}],
    "plain": {"@value": "a typed value", "@type": "http://example.org/datatype"},
    "wide": {"p01": 1, "p02": 2, "p03": 3, "p04": 4, "p05": 5, "p06": 6, "p07": 7, "p08": 8,
             "p09": 9, "p10": 10, "p11": 11, "p12": 12, "p13": 13, "p14": 14, "p15": 15,
             "p16": 16, "p17": 17, "p18": 18}
  })";
  const json::Value on_heap = run(kDoc);
  std::pmr::monotonic_buffer_resource arena;
  {
    const uint32_t id = loader_.files().add("arena.json");
    const json::Value doc = json::parse(kDoc, id, "arena.json");
    const json::Value in_arena = expand(doc, opts_, &arena);
    EXPECT_EQ(in_arena, on_heap) << json::dump(in_arena) << "\n" << json::dump(on_heap);
    EXPECT_EQ(outside(in_arena, &arena), "");
    // Strings, keys and key indexes too: the loader drops such a tree with its
    // arena, without destroying it.
    EXPECT_TRUE(json::lives_in(in_arena, &arena));
  }
}

}  // namespace
}  // namespace mospec::jsonld
