#include "jsonld/context.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "jsonld/loader.hpp"

namespace mospec::jsonld {
namespace {

// Serves remote contexts from memory and counts loads.
class MemoryLoader : public DocumentLoader {
 public:
  void add(std::string iri, std::string text) { docs_[std::move(iri)] = std::move(text); }
  RemoteDocument load(std::string_view iri, SourceLoc, bool for_context) override {
    ++loads;
    auto it = docs_.find(std::string(iri));
    if (it == docs_.end()) {
      throw Error(for_context ? DiagnosticCode("loading remote context failed")
                              : DiagnosticCode("loading document failed"),
                  "no document at " + std::string(iri));
    }
    const uint32_t id = files_.add(it->first);
    RemoteDocument d;
    d.document_url = it->first;
    d.content_type = "application/ld+json";
    d.document = std::make_shared<const json::Value>(json::parse(it->second, id, it->first));
    d.file_id = id;
    return d;
  }
  int loads = 0;

 private:
  std::map<std::string, std::string> docs_;
};

class ContextTest : public ::testing::Test {
 protected:
  ContextTest() {
    options.loader = &loader;
    options.diagnostics = &sink;
  }

  ContextPtr process(const std::string& text, ContextPtr active = nullptr,
                     bool override_protected = false) {
    if (!active) active = ActiveContext::initial("http://example.org/doc/base", options);
    const uint32_t id = loader.files().add("ctx.jsonld");
    json::Value v = json::parse(text, id, "ctx.jsonld");
    return process_context(active, v, "http://example.org/doc/base", options, nullptr,
                           override_protected);
  }

  // The error code of processing `text` ("" when it succeeds).
  std::string error_of(const std::string& text, ContextPtr active = nullptr) {
    try {
      process(text, std::move(active));
    } catch (const Error& e) {
      last_error = e;
      return e.code();
    }
    return "";
  }

  MemoryLoader loader;
  DiagnosticSink sink;
  Options options;
  std::optional<Error> last_error;
};

TEST_F(ContextTest, SimpleTermsPrefixesAndVocab) {
  ContextPtr c = process(R"({
    "@vocab": "http://vocab.org/",
    "ex": "http://example.com/",
    "name": "ex:name",
    "age": {"@id": "http://example.com/age", "@type": "http://www.w3.org/2001/XMLSchema#integer"},
    "ex:knows": {"@type": "@id"},
    "plain": {},
    "gone": null
  })");
  EXPECT_EQ(c->vocab(), "http://vocab.org/");
  ASSERT_NE(c->find("ex"), nullptr);
  EXPECT_TRUE(c->find("ex")->prefix);
  EXPECT_EQ(c->find("name")->iri, "http://example.com/name");
  EXPECT_FALSE(c->find("name")->prefix);  // IRI does not end with a gen-delim
  EXPECT_EQ(c->find("age")->type, "http://www.w3.org/2001/XMLSchema#integer");
  EXPECT_EQ(c->find("ex:knows")->iri, "http://example.com/knows");
  EXPECT_EQ(c->find("ex:knows")->type, "@id");
  EXPECT_EQ(c->find("plain")->iri, "http://vocab.org/plain");
  ASSERT_NE(c->find("gone"), nullptr);
  EXPECT_FALSE(c->find("gone")->iri.has_value());
  EXPECT_EQ(c->find("missing"), nullptr);
  EXPECT_EQ(c->find("age")->where, (SourceLoc{c->find("age")->where.file, 5, 5}));
}

TEST_F(ContextTest, KeywordAliasesAndContainers) {
  ContextPtr c = process(R"({
    "id": "@id", "type": "@type",
    "list": {"@id": "http://e/list", "@container": "@list"},
    "map": {"@id": "http://e/map", "@container": ["@graph", "@index", "@set"], "@index": "http://e/i"},
    "types": {"@id": "http://e/types", "@container": "@type"},
    "@type": {"@container": "@set"}
  })");
  EXPECT_EQ(c->find("id")->iri, "@id");
  EXPECT_EQ(c->find("type")->iri, "@type");
  EXPECT_EQ(c->find("list")->container, (std::set<std::string>{"@list"}));
  EXPECT_EQ(c->find("map")->container, (std::set<std::string>{"@graph", "@index", "@set"}));
  EXPECT_EQ(c->find("map")->index, "http://e/i");
  EXPECT_EQ(c->find("types")->type, "@id");  // CTD 19.4 default
  EXPECT_EQ(c->find("@type")->iri, "@type");
  EXPECT_EQ(c->find("@type")->container, (std::set<std::string>{"@set"}));
}

TEST_F(ContextTest, LanguageDirectionBaseAndReverse) {
  ContextPtr c = process(R"({
    "@base": "../other/", "@language": "en", "@direction": "rtl",
    "label": {"@id": "http://e/label", "@language": null, "@direction": "ltr"},
    "parent": {"@reverse": "http://e/child", "@container": "@set"},
    "nested": {"@id": "http://e/n", "@nest": "@nest"}
  })");
  EXPECT_EQ(c->base(), "http://example.org/other/");
  EXPECT_EQ(c->original_base(), "http://example.org/doc/base");
  EXPECT_EQ(c->default_language(), "en");
  EXPECT_EQ(c->default_direction(), "rtl");
  EXPECT_TRUE(c->find("label")->language->is_null());
  EXPECT_EQ(c->find("label")->direction->as_string(), "ltr");
  EXPECT_TRUE(c->find("parent")->reverse);
  EXPECT_EQ(c->find("parent")->iri, "http://e/child");
  EXPECT_EQ(c->find("nested")->nest, "@nest");

  ContextPtr n = process("null", c);
  EXPECT_EQ(n->base(), "http://example.org/doc/base");
  EXPECT_EQ(n->find("label"), nullptr);
  EXPECT_FALSE(n->default_language());
}

TEST_F(ContextTest, ScopedContextsStoredUnprocessed) {
  loader.add("http://ctx.org/links.jsonld", R"({"@context": {"link": "http://e/link"}})");
  ContextPtr c = process(R"({
    "@vocab": "http://e/",
    "Robot": {"@context": {"joint": {"@type": "@id"}}},
    "links": {"@context": "http://ctx.org/links.jsonld"}
  })");
  const TermDefinition* robot = c->find("Robot");
  ASSERT_NE(robot, nullptr);
  ASSERT_NE(robot->local_context, nullptr);
  EXPECT_EQ(*robot->local_context, json::parse(R"({"joint": {"@type": "@id"}})"));
  EXPECT_EQ(robot->base_url, "http://example.org/doc/base");
  EXPECT_EQ(c->find("joint"), nullptr);  // not applied until expansion uses it
  EXPECT_EQ(c->find("links")->local_context->as_string(), "http://ctx.org/links.jsonld");
  EXPECT_EQ(loader.loads, 1);  // loaded once to validate it (CTD 21.3)
  // A scoped context that cannot be processed fails where it is defined.
  EXPECT_EQ(error_of(R"({"t": {"@id": "http://e/t", "@context": "http://ctx.org/none"}})"),
            "invalid scoped context");
}

TEST_F(ContextTest, ProtectedTerms) {
  ContextPtr c = process(
      R"({"@protected": true, "p": "http://e/p", "q": {"@id": "http://e/q", "@protected": false}})");
  EXPECT_TRUE(c->find("p")->protected_);
  EXPECT_FALSE(c->find("q")->protected_);
  EXPECT_TRUE(c->has_protected_terms());
  // Identical redefinition keeps the protected definition.
  ContextPtr same = process(R"({"p": "http://e/p"})", c);
  EXPECT_TRUE(same->find("p")->protected_);
  EXPECT_EQ(error_of(R"({"p": "http://e/other"})", c), "protected term redefinition");
  EXPECT_NE(std::string(last_error->what()).find("ctx.jsonld:1:2: error: term \"p\" is protected"),
            std::string::npos)
      << last_error->what();
  EXPECT_EQ(error_of("null", c), "invalid context nullification");
  EXPECT_EQ(error_of(R"([null])", c), "invalid context nullification");
  // Unprotected terms may change; override_protected (property-scoped) allows it.
  EXPECT_EQ(process(R"({"q": "http://e/q2"})", c)->find("q")->iri, "http://e/q2");
  EXPECT_EQ(process(R"({"p": "http://e/p2"})", c, true)->find("p")->iri, "http://e/p2");
  EXPECT_FALSE(process("null", c, true)->has_protected_terms());
}

TEST_F(ContextTest, PropagateKeepsPreviousContext) {
  ContextPtr base = process(R"({"a": "http://e/a"})");
  ContextPtr c = process(R"({"@propagate": false, "b": "http://e/b"})", base);
  EXPECT_EQ(c->previous(), base);
  EXPECT_NE(c->find("a"), nullptr);
  ContextPtr d = process(R"({"c": "http://e/c"})", c);
  EXPECT_EQ(d->previous(), base);  // kept until expansion reverts
}

TEST_F(ContextTest, ErrorCodes) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"(5)", "invalid local context"},
      {R"([[{}]])", "invalid local context"},
      {R"({"@version": "1.1"})", "invalid @version value"},
      {R"({"@version": 1.0})", "invalid @version value"},
      {R"({"@import": 5})", "invalid @import value"},
      {R"({"@base": 5})", "invalid base IRI"},
      {R"({"@vocab": 5})", "invalid vocab mapping"},
      {R"({"@language": 5})", "invalid default language"},
      {R"({"@direction": "up"})", "invalid base direction"},
      {R"({"@propagate": "no"})", "invalid @propagate value"},
      {R"({"@protected": 1})", "invalid @protected value"},
      {R"({"": "http://e/"})", "invalid term definition"},
      {R"({"t": 5})", "invalid term definition"},
      {R"({"t": {"@id": "http://e/t", "@foo": 1}})", "invalid term definition"},
      {R"({"@id": "http://e/id"})", "keyword redefinition"},
      {R"({"@type": {"@id": "http://e/t"}})", "keyword redefinition"},
      {R"({"t": {"@id": 5}})", "invalid IRI mapping"},
      {R"({"t": {"@id": "relative"}})", "invalid IRI mapping"},
      {R"({"t": {}})", "invalid IRI mapping"},  // no @vocab
      {R"({"ex:t": {"@id": "http://other/t"}, "ex": "http://e/"})", "invalid IRI mapping"},
      {R"({"a": "b:x", "b": "a:y"})", "cyclic IRI mapping"},
      {R"({"a": {"@id": "@context"}})", "invalid keyword alias"},
      {R"({"t": {"@id": "http://e/t", "@type": 5}})", "invalid type mapping"},
      {R"({"t": {"@id": "http://e/t", "@type": "_:b"}})", "invalid type mapping"},
      {R"({"t": {"@id": "http://e/t", "@type": "http://e/T", "@container": "@type"}})",
       "invalid type mapping"},
      {R"({"t": {"@reverse": "http://e/r", "@id": "http://e/t"}})", "invalid reverse property"},
      {R"({"t": {"@reverse": "http://e/r", "@container": "@list"}})", "invalid reverse property"},
      {R"({"t": {"@reverse": 5}})", "invalid IRI mapping"},
      {R"({"t": {"@id": "http://e/t", "@container": "@foo"}})", "invalid container mapping"},
      {R"({"t": {"@id": "http://e/t", "@container": ["@list", "@set"]}})",
       "invalid container mapping"},
      {R"({"t": {"@id": "http://e/t", "@container": ["@index", "@language"]}})",
       "invalid container mapping"},
      {R"({"t": {"@id": "http://e/t", "@container": ["@graph", "@id", "@index"]}})",
       "invalid container mapping"},
      {R"({"t": {"@id": "http://e/t", "@index": "http://e/i"}})", "invalid term definition"},
      {R"({"t": {"@id": "http://e/t", "@container": "@index", "@index": "@id"}})",
       "invalid term definition"},
      {R"({"t": {"@id": "http://e/t", "@language": 5}})", "invalid language mapping"},
      {R"({"t": {"@id": "http://e/t", "@direction": "up"}})", "invalid base direction"},
      {R"({"t": {"@id": "http://e/t", "@nest": "@id"}})", "invalid @nest value"},
      {R"({"t": {"@id": "http://e/t", "@prefix": "yes"}})", "invalid @prefix value"},
      {R"({"t:x": {"@prefix": true}})", "invalid term definition"},
      {R"({"t": {"@id": "@type", "@prefix": true}})", "invalid term definition"},
      {R"({"t": {"@id": "http://e/t", "@context": {"@vocab": 5}}})", "invalid scoped context"},
      {R"({"t": {"@id": "http://e/t", "@protected": "yes"}})", "invalid @protected value"},
      {R"("http://nowhere.org/ctx")", "loading remote context failed"},
  };
  for (const auto& [text, code] : cases) {
    EXPECT_EQ(error_of(text), code) << text;
  }
}

TEST_F(ContextTest, JsonLd10Mode) {
  options.processing_mode = ProcessingMode::JsonLd10;
  EXPECT_EQ(error_of(R"({"@version": 1.1})"), "processing mode conflict");
  EXPECT_EQ(error_of(R"({"@import": "x"})"), "invalid context entry");
  EXPECT_EQ(error_of(R"({"@propagate": true})"), "invalid context entry");
  EXPECT_EQ(error_of(R"({"@type": {"@container": "@set"}})"), "keyword redefinition");
  EXPECT_EQ(error_of(R"({"t": {"@id": "http://e/t", "@container": "@id"}})"),
            "invalid container mapping");
  EXPECT_EQ(error_of(R"({"t": {"@id": "http://e/t", "@context": {}}})"), "invalid term definition");
  EXPECT_EQ(error_of(R"({"@vocab": "relative"})"), "invalid vocab mapping");
}

TEST_F(ContextTest, KeywordLikeTermsAreIgnoredWithAWarning) {
  ContextPtr c = process(R"({"@ignoreMe": "http://e/x", "t": {"@id": "@alsoIgnored"}})");
  EXPECT_EQ(c->find("@ignoreMe"), nullptr);
  EXPECT_EQ(c->find("t"), nullptr);
  ASSERT_EQ(sink.count(Severity::Warning), 2u);
  EXPECT_EQ(sink.diagnostics()[0].file, "ctx.jsonld");
  EXPECT_EQ(sink.diagnostics()[0].line, 1u);
  EXPECT_EQ(sink.diagnostics()[0].column, 2u);
  EXPECT_EQ(sink.diagnostics()[0].code, "keyword-like-term");
  EXPECT_EQ(sink.diagnostics()[1].code, "keyword-like-term");
}

TEST_F(ContextTest, VocabForms) {
  EXPECT_EQ(process(R"({"@vocab": "_:b"})")->vocab(), "_:b");
  EXPECT_EQ(process(R"({"@vocab": ""})")->vocab(), "http://example.org/doc/base");
  EXPECT_EQ(process(R"([{"@vocab": "http://v/"}, {"@vocab": "sub#"}])")->vocab(), "http://v/sub#");
  // @vocab is processed before the terms of its own context (CP 5.8).
  EXPECT_EQ(process(R"({"ex": "http://e/", "@vocab": "ex:"})")->vocab(), "ex:");
  EXPECT_EQ(process(R"([{"ex": "http://e/"}, {"@vocab": "ex:"}])")->vocab(), "http://e/");
  EXPECT_FALSE(process(R"([{"@vocab": "http://v/"}, {"@vocab": null}])")->vocab());
}

TEST_F(ContextTest, RemoteContexts) {
  loader.add("http://ctx.org/a.jsonld",
             R"({"@context": [{"@base": "http://ignored/", "a": "http://e/a"}, "b.jsonld"]})");
  loader.add("http://ctx.org/b.jsonld", R"({"@context": {"b": "http://e/b"}})");
  ContextPtr c = process(R"("http://ctx.org/a.jsonld")");
  EXPECT_EQ(c->find("a")->iri, "http://e/a");
  EXPECT_EQ(c->find("b")->iri, "http://e/b");           // relative to the remote document
  EXPECT_EQ(c->base(), "http://example.org/doc/base");  // @base ignored in remote contexts

  loader.add("http://ctx.org/self.jsonld", R"({"@context": ["self.jsonld"]})");
  EXPECT_EQ(error_of(R"("http://ctx.org/self.jsonld")"), "context overflow");
  loader.add("http://ctx.org/nocontext.jsonld", R"({"a": 1})");
  EXPECT_EQ(error_of(R"("http://ctx.org/nocontext.jsonld")"), "invalid remote context");
  loader.add("http://ctx.org/bad.jsonld", R"({"@context": {"t": 5}})");
  EXPECT_EQ(error_of(R"("http://ctx.org/bad.jsonld")"), "invalid term definition");
  // The error points into the remote file.
  EXPECT_EQ(last_error->diagnostic().file, "http://ctx.org/bad.jsonld");
  EXPECT_EQ(last_error->diagnostic().line, 1u);
  EXPECT_EQ(last_error->diagnostic().column, 20u);
}

// A context listed twice (or reached twice along different branches) is not a
// cycle; only one that includes itself through its own ancestors is.
TEST_F(ContextTest, RepeatedRemoteContextsAreNotCycles) {
  loader.add("http://ctx.org/base.jsonld", R"({"@context": {"a": "http://e/a"}})");
  loader.add("http://ctx.org/other.jsonld", R"({"@context": {"o": "http://e/o"}})");
  loader.add("http://ctx.org/both.jsonld",
             R"({"@context": ["base.jsonld", "other.jsonld", "base.jsonld"]})");
  ContextPtr c = process(R"(["http://ctx.org/base.jsonld", "http://ctx.org/base.jsonld"])");
  EXPECT_EQ(c->find("a")->iri, "http://e/a");
  // Diamond: both.jsonld and the top level each list base.jsonld.
  c = process(R"(["http://ctx.org/both.jsonld", "http://ctx.org/base.jsonld"])");
  EXPECT_EQ(c->find("a")->iri, "http://e/a");
  EXPECT_EQ(c->find("o")->iri, "http://e/o");

  // Each context listing the next one twice: 2^20 inclusions, refused after a bound.
  for (int i = 0; i < 20; ++i) {
    const std::string next = "http://ctx.org/d" + std::to_string(i + 1) + ".jsonld";
    loader.add("http://ctx.org/d" + std::to_string(i) + ".jsonld",
               R"({"@context": [")" + next + R"(", ")" + next + R"("]})");
  }
  loader.add("http://ctx.org/d20.jsonld", R"({"@context": {}})");
  EXPECT_EQ(error_of(R"("http://ctx.org/d0.jsonld")"), "context overflow");
  EXPECT_NE(last_error->diagnostic().message.find("remote contexts processed"), std::string::npos)
      << last_error->diagnostic().message;

  // A includes B includes A: the error is located where B names A, and says how.
  loader.add("http://ctx.org/A.jsonld", R"({"@context": ["B.jsonld"]})");
  loader.add("http://ctx.org/B.jsonld", "{\"@context\": [\n  \"A.jsonld\"]}");
  EXPECT_EQ(error_of(R"(["http://ctx.org/A.jsonld"])"), "context overflow");
  ASSERT_TRUE(last_error.has_value());
  EXPECT_EQ(last_error->diagnostic().file, "http://ctx.org/B.jsonld");
  EXPECT_EQ(last_error->diagnostic().line, 2u);
  EXPECT_EQ(last_error->diagnostic().message,
            "remote context http://ctx.org/A.jsonld includes itself (http://ctx.org/A.jsonld -> "
            "http://ctx.org/B.jsonld -> http://ctx.org/A.jsonld)");
}

// JSON-LD 1.0 names a context that includes itself by the 1.0 code.
TEST_F(ContextTest, ARecursiveInclusionInJsonLd10Mode) {
  options.processing_mode = ProcessingMode::JsonLd10;
  loader.add("http://ctx.org/A.jsonld", R"({"@context": ["B.jsonld"]})");
  loader.add("http://ctx.org/B.jsonld", R"({"@context": ["A.jsonld"]})");
  EXPECT_EQ(error_of(R"(["http://ctx.org/A.jsonld"])"), "recursive context inclusion");
}

TEST_F(ContextTest, Import) {
  loader.add("http://ctx.org/imp.jsonld",
             R"({"@context": {"a": "http://e/a", "b": "http://e/b"}})");
  loader.add("http://ctx.org/imp2.jsonld", R"({"@context": {"@import": "imp.jsonld"}})");
  loader.add("http://ctx.org/arr.jsonld", R"({"@context": ["imp.jsonld"]})");
  ContextPtr c = process(R"({"@import": "http://ctx.org/imp.jsonld", "b": "http://e/b2"})");
  EXPECT_EQ(c->find("a")->iri, "http://e/a");
  EXPECT_EQ(c->find("b")->iri, "http://e/b2");
  EXPECT_EQ(error_of(R"({"@import": "http://ctx.org/imp2.jsonld"})"), "invalid context entry");
  EXPECT_EQ(error_of(R"({"@import": "http://ctx.org/arr.jsonld"})"), "invalid remote context");
}

// A scoped context written in a remote context is kept by pointing into that
// context's document; one that came in through @import sits in a merged copy
// that processing drops, so it must be kept as a copy of its own. Either way
// it is still there once processing is over.
TEST_F(ContextTest, ScopedContextsOfRemoteAndImportedContextsOutliveProcessing) {
  loader.add("http://ctx.org/scoped.jsonld",
             R"({"@context": {"robot": {"@id": "http://e/robot",
                                       "@context": {"joint": {"@id": "http://e/joint",
                                                              "@type": "@id"}}}}})");
  loader.add("http://ctx.org/importing.jsonld",
             R"({"@context": {"@import": "scoped.jsonld", "arm": "http://e/arm"}})");
  const json::Value expected =
      json::parse(R"({"joint": {"@id": "http://e/joint", "@type": "@id"}})");
  for (const char* ctx :
       {R"("http://ctx.org/scoped.jsonld")", R"("http://ctx.org/importing.jsonld")"}) {
    ContextPtr c = process(ctx);
    const TermDefinition* robot = c->find("robot");
    ASSERT_NE(robot, nullptr) << ctx;
    ASSERT_NE(robot->local_context, nullptr) << ctx;
    EXPECT_EQ(*robot->local_context, expected) << ctx;
    // And it applies.
    ContextPtr scoped = process_context(c, *robot->local_context, robot->base_url, options);
    ASSERT_NE(scoped->find("joint"), nullptr) << ctx;
    EXPECT_EQ(scoped->find("joint")->type, "@id") << ctx;
  }
}

TEST_F(ContextTest, ExpandIri) {
  ContextPtr c = process(R"({
    "@vocab": "http://v/", "ex": "http://e/", "id": "@id", "nul": null,
    "exx": {"@id": "http://e/x", "@prefix": false}
  })");
  EXPECT_EQ(expand_iri(*c, "@type"), "@type");
  EXPECT_EQ(expand_iri(*c, "@unknown"), std::nullopt);
  EXPECT_EQ(expand_iri(*c, "id"), "@id");
  EXPECT_EQ(expand_iri(*c, "ex"), "http://e/");
  EXPECT_EQ(expand_iri(*c, "ex:foo"), "http://e/foo");
  EXPECT_EQ(expand_iri(*c, "exx:foo"), "exx:foo");  // not a prefix, but has a scheme
  EXPECT_EQ(expand_iri(*c, "nul"), std::nullopt);
  EXPECT_EQ(expand_iri(*c, "_:b0"), "_:b0");
  EXPECT_EQ(expand_iri(*c, "term"), "http://v/term");
  EXPECT_EQ(expand_iri(*c, "rel", true, false), "http://example.org/doc/rel");
  EXPECT_EQ(expand_iri(*c, "ex", true, false), "http://example.org/doc/ex");
  EXPECT_EQ(expand_iri(*c, "http://a/b"), "http://a/b");
}

TEST_F(ContextTest, LayersStayCorrectAcrossManyDerivations) {
  ContextPtr c = process(R"({"t0": "http://e/0", "keep": "http://e/keep"})");
  for (int i = 1; i < 20; ++i) {
    c = process("{\"t" + std::to_string(i) + "\": \"http://e/" + std::to_string(i) + "\", \"t" +
                    std::to_string(i - 1) + "\": \"http://e/re" + std::to_string(i - 1) + "\"}",
                c);
  }
  EXPECT_EQ(c->find("keep")->iri, "http://e/keep");
  EXPECT_EQ(c->find("t0")->iri, "http://e/re0");
  EXPECT_EQ(c->find("t18")->iri, "http://e/re18");
  EXPECT_EQ(c->find("t19")->iri, "http://e/19");
  EXPECT_EQ(c->terms().size(), 21u);
  // A keyword-like @id removes the earlier definition (CTD 6 then 14.2.2).
  ContextPtr d = process(R"({"keep": {"@id": "@ignored"}})", c);
  EXPECT_EQ(d->find("keep"), nullptr);
  EXPECT_NE(c->find("keep"), nullptr);
}

TEST_F(ContextTest, CacheReturnsTheSameContexts) {
  options.context_cache = std::make_shared<ContextCache>();
  loader.add("http://ctx.org/big.jsonld", R"({"@context": {"@vocab": "http://e/",
      "Robot": {"@context": {"joint": {"@type": "@id"}}}, "a": "http://e/a"}})");
  json::Value ref = json::parse(R"("http://ctx.org/big.jsonld")");
  ContextPtr i1 = ActiveContext::initial("http://doc1/", options);
  ContextPtr i2 = ActiveContext::initial("http://doc2/", options);
  ContextPtr c1 = process_context(i1, ref, "http://doc1/", options);
  ContextPtr c1b = process_context(i1, ref, "http://doc1/", options);
  EXPECT_EQ(c1, c1b);  // exact hit
  ContextPtr c2 = process_context(i2, ref, "http://doc2/", options);
  EXPECT_NE(c1, c2);
  EXPECT_EQ(c2->base(), "http://doc2/");
  EXPECT_EQ(c1->find("a"), c2->find("a"));  // remote hit shares the definitions
  const ContextCache::Stats& s = options.context_cache->stats();
  EXPECT_EQ(s.exact_hits, 1u);
  EXPECT_EQ(s.remote_hits, 1u);
  EXPECT_EQ(s.remote_misses, 1u);
  EXPECT_EQ(loader.loads, 1);

  // Type-scoped contexts passed from their definition hit by address.
  const TermDefinition* robot = c1->find("Robot");
  ContextPtr t1 =
      process_context(c1, *robot->local_context, robot->base_url, options, nullptr, false, false);
  ContextPtr t2 =
      process_context(c1, *robot->local_context, robot->base_url, options, nullptr, false, false);
  EXPECT_EQ(t1, t2);
  EXPECT_EQ(t1->previous(), c1);
  EXPECT_EQ(t1->find("joint")->type, "@id");
  // Equal content at another address still hits.
  json::Value copy = *robot->local_context;
  EXPECT_EQ(process_context(c1, copy, robot->base_url, options, nullptr, false, false), t1);
}

TEST_F(ContextTest, DeltaCacheAppliesOnlyWhereTheStateAnswersAlike) {
  options.context_cache = std::make_shared<ContextCache>();
  // "p" needs the prefix "ex" of whatever context it is applied to.
  loader.add("http://ctx.org/r.jsonld", R"({"@context": {"p": "ex:p", "q": {"@id": "ex:q",
      "@context": {"r": "ex:r"}}}})");
  ContextPtr one = process(R"({"ex": "http://one/"})");
  ContextPtr two = process(R"({"ex": "http://two/"})");
  ContextPtr one_again = process(R"({"ex": "http://one/", "unrelated": "http://u/"})");
  ContextPtr guarded = process(R"({"ex": "http://one/", "p": {"@id": "http://x/p",
      "@protected": true}})");
  const std::string ref = R"("http://ctx.org/r.jsonld")";
  EXPECT_EQ(process(ref, one)->find("p")->iri, "http://one/p");
  EXPECT_EQ(process(ref, two)->find("p")->iri, "http://two/p");  // other "ex": processed anew
  const size_t hits = options.context_cache->stats().delta_hits;
  ContextPtr c = process(ref, one_again);  // same "ex", another state: the delta applies
  EXPECT_EQ(options.context_cache->stats().delta_hits, hits + 1);
  EXPECT_EQ(c->find("p")->iri, "http://one/p");
  EXPECT_EQ(c->find("q")->iri, "http://one/q");
  EXPECT_EQ(c->find("unrelated")->iri, "http://u/");
  // A protected "p" underneath must still be reported.
  EXPECT_EQ(error_of(ref, guarded), "protected term redefinition");

  // Type-scoped contexts: the same content over different states.
  const std::string scoped = R"({"s": "ex:s"})";
  EXPECT_EQ(process(scoped, one)->find("s")->iri, "http://one/s");
  EXPECT_EQ(process(scoped, two)->find("s")->iri, "http://two/s");
  const size_t before = options.context_cache->stats().delta_hits;
  EXPECT_EQ(process(scoped, one_again)->find("s")->iri, "http://one/s");
  EXPECT_EQ(options.context_cache->stats().delta_hits, before + 1);
}

TEST_F(ContextTest, TermDefinitionEntriesAreCheckedInTheSpecsOrder) {
  // CTD 26 names the first entry that is no term-definition keyword, at its key.
  EXPECT_EQ(error_of(R"({"t": {"@id": "http://e/t", "@idd": 1, "@other": 2}})"),
            "invalid term definition");
  EXPECT_EQ(last_error->diagnostic().message, "term \"t\": unexpected entry \"@idd\"");
  EXPECT_EQ(last_error->diagnostic().line, 1u);
  EXPECT_EQ(last_error->diagnostic().column, 29u);
  // An invalid @type (CTD 12) is reported before an unexpected entry, wherever
  // the entries are written.
  EXPECT_EQ(error_of(R"({"t": {"x": 1, "@id": "http://e/t", "@type": 5}})"),
            "invalid type mapping");
  // Entries that are keywords of the right length but not of term definitions.
  EXPECT_EQ(error_of(R"({"t": {"@id": "http://e/t", "@value": "v"}})"), "invalid term definition");
  EXPECT_EQ(last_error->diagnostic().message, "term \"t\": unexpected entry \"@value\"");
  // Every term-definition keyword is accepted.
  ContextPtr c = process(R"({"ex": "http://e/", "t": {"@id": "ex:t", "@container": "@index",
      "@index": "ex:i", "@context": {}, "@nest": "@nest", "@protected": true, "@prefix": false,
      "@language": "en", "@direction": "ltr"}, "r": {"@reverse": "ex:r"}})");
  EXPECT_EQ(c->find("t")->iri, "http://e/t");
  EXPECT_EQ(c->find("t")->index, "ex:i");
  EXPECT_EQ(c->find("t")->nest, "@nest");
  EXPECT_TRUE(c->find("t")->protected_);
  EXPECT_TRUE(c->find("r")->reverse);
}

TEST_F(ContextTest, DeltaCacheKeepsTheFullAnswerForATermLookedUpTwice) {
  options.context_cache = std::make_shared<ContextCache>();
  // "ex" is first looked up only for its protection (CTD 6: its definition is
  // then dropped as keyword-like) and then for its IRI (the prefix of "p").
  // The delta recorded over a state without "ex" must therefore not apply
  // where "ex" is defined: there CTD 6 removes it.
  loader.add("http://ctx.org/w.jsonld",
             R"({"@context": {"ex": {"@id": "@ignoreMe"}, "p": "ex:p"}})");
  const std::string ref = R"("http://ctx.org/w.jsonld")";
  ContextPtr without = process(R"({"other": "http://o/"})");
  ContextPtr with = process(R"({"ex": "http://b/"})");
  ContextPtr a = process(ref, without);
  EXPECT_EQ(a->find("ex"), nullptr);
  EXPECT_EQ(a->find("p")->iri, "ex:p");
  const size_t hits = options.context_cache->stats().delta_hits;
  ContextPtr b = process(ref, with);
  EXPECT_EQ(options.context_cache->stats().delta_hits, hits);  // processed anew
  EXPECT_EQ(b->find("ex"), nullptr);
  EXPECT_EQ(b->find("p")->iri, "ex:p");
  sink.clear();
}

}  // namespace
}  // namespace mospec::jsonld

namespace mospec::jsonld {
namespace {

// The JSON-LD 1.1 keywords, each recognised, and near misses not.
TEST(Keywords, EveryKeywordAndNoNearMiss) {
  const std::vector<std::string> keywords = {
      "@base",   "@container", "@context", "@direction", "@graph",     "@id",
      "@import", "@included",  "@index",   "@json",      "@language",  "@list",
      "@nest",   "@none",      "@prefix",  "@propagate", "@protected", "@reverse",
      "@set",    "@type",      "@value",   "@version",   "@vocab"};
  for (const std::string& k : keywords) {
    EXPECT_TRUE(is_keyword(k)) << k;
    EXPECT_FALSE(is_keyword(k + "s")) << k;
    EXPECT_FALSE(is_keyword(k.substr(0, k.size() - 1))) << k;
    EXPECT_FALSE(is_keyword(k.substr(1))) << k;
    std::string upper = k;
    upper[1] = static_cast<char>(upper[1] - 'a' + 'A');
    EXPECT_FALSE(is_keyword(upper)) << k;
  }
  EXPECT_FALSE(is_keyword(""));
  EXPECT_FALSE(is_keyword("@"));
  EXPECT_FALSE(is_keyword("@ignoreMe"));
}

}  // namespace
}  // namespace mospec::jsonld
