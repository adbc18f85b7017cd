// The code generator's Mustache subset (src/support/mustache.hpp): what it
// substitutes, when a section renders, kainjow's blank-line rule, and the
// templates it refuses.
#include "support/mustache.hpp"

#include <gtest/gtest.h>

#include <string>

#include "support/diagnostics.hpp"

namespace {

using mospec::mustache::Data;
using mospec::mustache::render;

TEST(Mustache, VariablesAreVerbatimAndMissingOnesEmpty) {
  Data d;
  d.put("x", "a < b && \"c\"");
  d.put("flag", true);
  EXPECT_EQ(render("[{{x}}|{{{x}}}|{{& x }}|{{missing}}|{{flag}}]", d),
            "[a < b && \"c\"|a < b && \"c\"|a < b && \"c\"||]");
  // "{{x}}}" is the variable and a brace, as kainjow reads it.
  EXPECT_EQ(render("{ {{x}}};", d), "{ a < b && \"c\"};");
}

TEST(Mustache, SectionsRenderPerItemAndLookOutwards) {
  Data d;
  d.put("outer", "O");
  Data items = Data::list();
  for (const char* name : {"a", "b"}) {
    Data item;
    item.put("name", name);
    items.append(std::move(item));
  }
  d.put("items", std::move(items));
  d.put("empty", Data::list());
  d.put("yes", true);
  d.put("no", false);
  EXPECT_EQ(render("{{#items}}{{name}}{{outer}},{{/items}}", d), "aO,bO,");
  EXPECT_EQ(render("{{#empty}}E{{/empty}}{{^empty}}none{{/empty}}", d), "none");
  EXPECT_EQ(render("{{#yes}}Y{{/yes}}{{#no}}N{{/no}}{{^no}}!N{{/no}}{{^missing}}!M{{/missing}}", d),
            "Y!N!M");
  EXPECT_EQ(render("{{#outer}}[{{outer}}]{{/outer}}", d), "[O]");
}

// A line that held the tag of a section that rendered and is left blank goes,
// line break and all; the lines of a section that did not render stay.
TEST(Mustache, BlankLinesOfRenderedSectionTagsGo) {
  Data d;
  d.put("yes", true);
  d.put("no", false);
  EXPECT_EQ(render("a\n  {{#yes}}\nb\n  {{/yes}}\nc\n", d), "a\nb\nc\n");
  EXPECT_EQ(render("a\n  {{#no}}\nb\n  {{/no}}\nc\n", d), "a\n  \nc\n");
  EXPECT_EQ(render("a\n{{#yes}}  {{/yes}}", d), "a\n");
  EXPECT_EQ(render("a\n{{#yes}}x{{/yes}}\n", d), "a\nx\n");
}

TEST(Mustache, MalformedTemplatesAreRefused) {
  const Data d;
  for (const char* bad : {"{{x", "{{#a}}", "{{/a}}", "{{#a}}{{/b}}", "{{> partial}}", "{{=<% %>=}}",
                          "{{a.b}}", "{{.}}"}) {
    try {
      render(bad, d);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const mospec::Error& e) {
      EXPECT_EQ(e.code(), "codegen-template") << bad;
    }
  }
}

}  // namespace
