#include "json/json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory_resource>
#include <optional>
#include <string>
#include <vector>

#include "counting_resource.hpp"

namespace mospec::json {
namespace {

// Parses `text` expecting failure; returns the located message.
Diagnostic parse_error(std::string_view text) {
  try {
    parse(text, 1, "doc.json");
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid json");
    return e.diagnostic();
  }
  ADD_FAILURE() << "parsed without error: " << text;
  return {};
}

void expect_error(std::string_view text, const std::string& message, uint32_t line,
                  uint32_t column) {
  const Diagnostic d = parse_error(text);
  EXPECT_EQ(d.message, message) << text;
  EXPECT_EQ(d.file, "doc.json") << text;
  EXPECT_EQ(d.line, line) << text;
  EXPECT_EQ(d.column, column) << text;
}

TEST(JsonParse, Scalars) {
  EXPECT_TRUE(parse("null").is_null());
  EXPECT_EQ(parse("true"), Value(true));
  EXPECT_EQ(parse(" false "), Value(false));
  EXPECT_EQ(parse("12").as_number(), 12);
  EXPECT_EQ(parse("-0.5e2").as_number(), -50);
  EXPECT_EQ(parse("1E+2").as_number(), 100);
  EXPECT_EQ(parse("\"a\"").as_string(), "a");
  EXPECT_TRUE(std::signbit(parse("-0").as_number()));
}

TEST(JsonParse, NumbersFollowJavaScript) {
  EXPECT_EQ(parse("1e400").as_number(), std::numeric_limits<double>::infinity());
  EXPECT_EQ(parse("-1e400").as_number(), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(parse("1e-400").as_number(), 0.0);
  EXPECT_EQ(parse("0.1").as_number(), 0.1);
  EXPECT_EQ(parse("9007199254740993").as_number(), 9007199254740992.0);
}

TEST(JsonParse, Escapes) {
  EXPECT_EQ(parse(R"("\"\\\/\b\f\n\r\t")").as_string(), "\"\\/\b\f\n\r\t");
  EXPECT_EQ(parse(R"("\u0041\u00e9\u20AC")").as_string(), "A\xC3\xA9\xE2\x82\xAC");
  EXPECT_EQ(parse(R"("\uD83D\uDE00")").as_string(), "\xF0\x9F\x98\x80");
  EXPECT_EQ(parse(R"("\u0000")").as_string(), std::string(1, '\0'));
  EXPECT_EQ(parse("\"\xF0\x9F\x98\x80 raw\"").as_string(), "\xF0\x9F\x98\x80 raw");
}

// A quote, a backslash, a control character or a multi-byte character at
// every offset of a string's run of ordinary bytes (the parser copies the
// run in one go).
TEST(JsonParse, StringsAtEveryWordOffset) {
  for (size_t at = 0; at < 20; ++at) {
    const std::string before(at, 'a');
    const std::string after(19 - at, 'b');
    EXPECT_EQ(parse("\"" + before + "\"").as_string(), before) << at;
    EXPECT_EQ(parse("\"" + before + "\\n" + after + "\"").as_string(), before + "\n" + after) << at;
    EXPECT_EQ(parse("\"" + before + "\xC3\xA9" + after + "\"").as_string(),
              before + "\xC3\xA9" + after)
        << at;
    EXPECT_EQ(parse_error("\"" + before + "\x01" + after + "\"").column, at + 2) << at;
    EXPECT_EQ(parse_error("\"" + before + "\x7F" + after).message, "unterminated string") << at;
    // 0x7F and bytes just below '"' and '\\' are ordinary.
    const std::string edge = before + "\x7F!#[]" + after;
    EXPECT_EQ(parse("\"" + edge + "\"").as_string(), edge) << at;
  }
}

TEST(JsonParse, StructureAndOrder) {
  const Value v = parse(R"({"b": [1, {"c": null}], "a": {}, "d": []})");
  ASSERT_TRUE(v.is_object());
  const Object& o = v.as_object();
  ASSERT_EQ(o.size(), 3u);
  EXPECT_EQ(o.key(0), "b");
  EXPECT_EQ(o.key(1), "a");
  EXPECT_EQ(o.key(2), "d");
  EXPECT_EQ(o.sorted_keys(), (std::vector<std::string_view>{"a", "b", "d"}));
  EXPECT_TRUE(v.get("b")->as_array()[1].get("c")->is_null());
  EXPECT_EQ(v.get("zz"), nullptr);
}

TEST(JsonParse, DuplicateKeysLastWins) {
  const Value v = parse("{\"a\": 1,\n \"b\": 2,\n  \"a\": 3}", 7);
  const Object& o = v.as_object();
  ASSERT_EQ(o.size(), 2u);
  EXPECT_EQ(o.key(0), "a");
  EXPECT_EQ(o.value(0).as_number(), 3);
  // The surviving key is located where it was written last.
  EXPECT_EQ(o.key_location(0), (SourceLoc{7, 3, 3}));
}

// The duplicate-key check used to scan the members so far: 100k keys took
// minutes. A duplicate far into a large object still wins and is located.
TEST(JsonParse, LargeObjectsParseInLinearTimeAndKeepDuplicateRules) {
  const size_t n = 100000;
  std::string text = "{";
  for (size_t i = 0; i < n; ++i) {
    const std::string k = std::to_string(i);
    text.append("\"k").append(k).append("\": ").append(k).append(",");
  }
  text += "\n\"k12345\": -1}";
  const Value v = parse(text, 3);
  const Object& o = v.as_object();
  ASSERT_EQ(o.size(), n);
  EXPECT_EQ(o.key(12345), "k12345");
  EXPECT_EQ(o.value(12345).as_number(), -1);
  EXPECT_EQ(o.key_location(12345), (SourceLoc{3, 2, 1}));
  EXPECT_EQ(o.value(n - 1).as_number(), static_cast<double>(n - 1));
  EXPECT_EQ(o.find("k99999")->as_number(), 99999);
}

// The parser builds each value in its final slot while deeper levels are
// parsed; those levels' buffers grow meanwhile (a new depth, more members or
// elements than before). Each value must come out whole and in place: a
// document whose every level is wider than the last one seen there, with a
// duplicate key whose replaced value is itself nested, dumps back as written.
TEST(JsonParse, NestedValuesSurviveDeeperLevelsGrowing) {
  // Level d (from 0): an array of d + 2 elements, the last an object with
  // d + 2 members, its last member nesting the next level.
  std::function<std::string(int)> level = [&](int d) -> std::string {
    if (d == 40) return "[\"leaf\",{\"x\":null}]";
    std::string s = "[";
    for (int i = 0; i < d + 1; ++i) s += std::to_string(d * 100 + i) + ",";
    s += "{";
    for (int i = 0; i < d + 1; ++i) {
      s += "\"m" + std::to_string(i) + "\":[" + std::to_string(i) + ",\"s" + std::to_string(i) +
           "-a-string-longer-than-fifteen-bytes\"],";
    }
    s += "\"next\":" + level(d + 1) + "}]";
    return s;
  };
  const std::string text = level(0);
  EXPECT_EQ(dump(parse(text)), text);

  // A duplicate key: the first value (deeply nested) is replaced by the last.
  const std::string dup = "{\"a\":" + level(30) + ",\"b\":[1],\"a\":" + level(35) + "}";
  const Value v = parse(dup);
  EXPECT_EQ(dump(v), "{\"a\":" + level(35) + ",\"b\":[1]}");
  EXPECT_EQ(v.get("a")->as_array()[0].location(),
            (SourceLoc{0, 1, static_cast<uint32_t>(dup.rfind("[3500") + 2)}));
}

// Lookups in large objects are indexed (JSON-LD expansion looked up every key
// of a 100k-key object in its result: minutes); the index follows set, erase
// and copies.
TEST(JsonValue, LargeObjectsStayIndexedThroughSetEraseAndCopy) {
  const size_t n = 100000;
  Object o;
  for (size_t i = 0; i < n; ++i) {
    const std::string k = std::to_string(i);
    EXPECT_EQ(o.find(k), nullptr);
    o.set(k, Value(static_cast<double>(i)));
  }
  ASSERT_EQ(o.size(), n);
  o.set("777", Value("replaced"));
  EXPECT_EQ(o.size(), n);
  EXPECT_EQ(o.find("777")->as_string(), "replaced");
  EXPECT_TRUE(o.erase("5"));  // O(n): once, not in a loop
  EXPECT_FALSE(o.erase("5"));
  EXPECT_EQ(o.find("5"), nullptr);
  EXPECT_EQ(o.find("99999")->as_number(), 99999);  // moved down one position
  const Object copy = o;
  EXPECT_EQ(copy.find("6")->as_number(), 6);
  EXPECT_EQ(copy.size(), n - 1);

  Object small;
  for (int i = 0; i < 40; ++i) small.set(std::to_string(i), Value(i));
  for (int i = 16; i < 40; ++i) EXPECT_TRUE(small.erase(std::to_string(i)));
  EXPECT_EQ(small.size(), 16u);  // back below the index's threshold
  EXPECT_EQ(small.find("15")->as_number(), 15);
  EXPECT_EQ(small.find("4")->as_number(), 4);
  EXPECT_EQ(small.find("16"), nullptr);
}

TEST(JsonParse, Locations) {
  const std::string text =
      "{\n"
      "  \"@context\": \"x\",\n"
      "  \"list\": [1, true,\n"
      "\t\"s\"]\n"
      "}";
  const Value v = parse(text, 4, "f.json");
  EXPECT_EQ(v.location(), (SourceLoc{4, 1, 1}));
  const Object& o = v.as_object();
  EXPECT_EQ(o.key_location(0), (SourceLoc{4, 2, 3}));
  EXPECT_EQ(o.value(0).location(), (SourceLoc{4, 2, 15}));
  EXPECT_EQ(o.key_location(1), (SourceLoc{4, 3, 3}));
  const Array& a = o.value(1).as_array();
  EXPECT_EQ(o.value(1).location(), (SourceLoc{4, 3, 11}));
  EXPECT_EQ(a[0].location(), (SourceLoc{4, 3, 12}));
  EXPECT_EQ(a[1].location(), (SourceLoc{4, 3, 15}));
  EXPECT_EQ(a[2].location(), (SourceLoc{4, 4, 2}));
}

// Runs of indentation are skipped whole and a string's plain bytes are copied
// a run at a time: columns, lines and contents stay exact around them.
TEST(JsonParse, LocationsAfterIndentationRunsAndMixedStrings) {
  const std::string text = "{\r\n" + std::string(40, ' ') + "\"k\":  \t \"" + std::string(50, 'a') +
                           "\\n\xC3\xA9" + std::string(20, 'b') + "\",\n" + std::string(8, ' ') +
                           "\"n\": null" + std::string(30, ' ') + "}" + std::string(25, ' ');
  const Value v = parse(text, 2, "f.json");
  const Object& o = v.as_object();
  EXPECT_EQ(o.key_location(0), (SourceLoc{2, 2, 41}));
  EXPECT_EQ(o.value(0).location(), (SourceLoc{2, 2, 49}));
  EXPECT_EQ(o.value(0).as_string(), std::string(50, 'a') + "\n\xC3\xA9" + std::string(20, 'b'));
  EXPECT_EQ(o.key_location(1), (SourceLoc{2, 3, 9}));
  EXPECT_EQ(o.value(1).location(), (SourceLoc{2, 3, 14}));
  EXPECT_TRUE(o.value(1).is_null());
}

TEST(JsonParse, LocationsCountBytesAndSkipBom) {
  // "é" is two bytes, so the value after it starts two columns later.
  const Value v = parse("\xEF\xBB\xBF[\"\xC3\xA9\", 1]");
  EXPECT_EQ(v.location().column, 1u);
  EXPECT_EQ(v.as_array()[1].location().column, 8u);
}

TEST(JsonParseErrors, Messages) {
  expect_error("", "unexpected end of input; expected a JSON value", 1, 1);
  expect_error("[1,]", "trailing comma in array", 1, 3);
  expect_error("{\"a\":1,\n }", "trailing comma in object", 1, 7);
  expect_error("{\"a\":1 \"b\":2}", "expected ',' or '}' after object member", 1, 8);
  expect_error("[1 2]", "expected ',' or ']' after array element", 1, 4);
  expect_error("{\"a\" 1}", "expected ':' after object key", 1, 6);
  expect_error("{1:2}", "expected a string key in object, found '1'", 1, 2);
  expect_error("{\"a\":1", "unexpected end of input; expected ',' or '}' after object member", 1,
               7);
  expect_error("[1", "unexpected end of input; expected ',' or ']' after array element", 1, 3);
  expect_error("tru", "invalid literal; expected 'true', 'false' or 'null'", 1, 1);
  expect_error("[nulls]", "invalid literal; expected 'true', 'false' or 'null'", 1, 2);
  expect_error("True", "unexpected 'T'; expected a JSON value", 1, 1);
  expect_error("[01]", "leading zeros are not allowed in numbers", 1, 2);
  expect_error("-", "expected a digit in number", 1, 2);
  expect_error("1.", "expected a digit after '.' in number", 1, 3);
  expect_error("1e", "expected a digit in number exponent", 1, 3);
  expect_error(".5", "unexpected '.'; expected a JSON value", 1, 1);
  expect_error("\"a\tb\"", "unescaped control character U+0009 in string", 1, 3);
  expect_error("\"a\nb\"", "unescaped control character U+000A in string", 1, 3);
  expect_error("\"abc", "unterminated string", 1, 1);
  expect_error(R"("\x")", "invalid escape sequence '\\x' in string", 1, 2);
  // Bytes that are not printable are named by their code, never echoed raw.
  expect_error("\"\\\x01\"", "invalid escape sequence: '\\' followed by byte 0x01 in string", 1, 2);
  expect_error("\x01{}", "unexpected byte 0x01; expected a JSON value", 1, 1);
  expect_error("\xff", "unexpected byte 0xFF; expected a JSON value", 1, 1);
  expect_error(R"("\u12G4")", "invalid \\u escape: expected 4 hex digits", 1, 2);
  expect_error(R"(["\uD83D"])",
               "lone high surrogate \\uD83D in string (expected a following \\uDC00-\\uDFFF "
               "escape)",
               1, 3);
  expect_error(R"("\uD83D\u0041")",
               "lone high surrogate \\uD83D in string (expected a following \\uDC00-\\uDFFF "
               "escape)",
               1, 2);
  expect_error(R"("\uDE00")", "unpaired low surrogate \\uDE00 in string", 1, 2);
  expect_error("\"\xC3\x28\"", "invalid UTF-8 in string", 1, 2);
  expect_error("\"\xED\xA0\x80\"", "invalid UTF-8 in string", 1, 2);  // encoded surrogate
  expect_error("{} x", "unexpected trailing characters after the JSON value", 1, 4);
  expect_error("1\n\n  ]", "unexpected trailing characters after the JSON value", 3, 3);
  expect_error(std::string(600, '['), "nesting deeper than 512 levels", 1, 513);
}

TEST(JsonParseErrors, WhatNamesFileLineColumn) {
  try {
    parse("[1,]", 1, "models/a.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "models/a.json:1:3: error: trailing comma in array");
  }
}

TEST(JsonValue, EqualityIgnoresOrderAndLocation) {
  EXPECT_EQ(parse(R"({"a":1,"b":[1,2]})"), parse("{\"b\" : [1, 2],\n\"a\": 1.0}"));
  EXPECT_NE(parse(R"({"a":1})"), parse(R"({"a":1,"b":2})"));
  EXPECT_NE(parse(R"([1,2])"), parse(R"([2,1])"));
  EXPECT_NE(parse("1"), parse("\"1\""));
  EXPECT_EQ(parse("0"), parse("-0"));
}

TEST(JsonValue, SetReplacesAndEraseRemoves) {
  Object o;
  o.set("a", 1);
  o.set("b", 2);
  o.set("a", 3);
  ASSERT_EQ(o.size(), 2u);
  EXPECT_EQ(o.find("a")->as_number(), 3);
  EXPECT_TRUE(o.erase("a"));
  EXPECT_FALSE(o.erase("a"));
  EXPECT_EQ(o.size(), 1u);
  EXPECT_EQ(o.key(0), "b");
}

TEST(JsonDump, CompactAndIndented) {
  const Value v = parse(R"({"a":[1,2.5,"x\"y"],"b":{},"c":[],"d":null,"e":true})");
  EXPECT_EQ(dump(v), R"({"a":[1,2.5,"x\"y"],"b":{},"c":[],"d":null,"e":true})");
  EXPECT_EQ(dump(parse(R"({"a":[1,{"b":2}]})"), 2),
            "{\n  \"a\": [\n    1,\n    {\n      \"b\": 2\n    }\n  ]\n}");
  EXPECT_EQ(dump(Value(std::numeric_limits<double>::infinity())), "null");
}

TEST(JsonNumberToString, EcmaScriptVectors) {
  EXPECT_EQ(number_to_string(0), "0");
  EXPECT_EQ(number_to_string(-0.0), "0");
  EXPECT_EQ(number_to_string(1), "1");
  EXPECT_EQ(number_to_string(-1.5), "-1.5");
  EXPECT_EQ(number_to_string(100), "100");
  EXPECT_EQ(number_to_string(1e21), "1e+21");
  EXPECT_EQ(number_to_string(1e20), "100000000000000000000");
  EXPECT_EQ(number_to_string(123456789012345680000.0), "123456789012345680000");
  EXPECT_EQ(number_to_string(1e-7), "1e-7");
  EXPECT_EQ(number_to_string(1.5e-7), "1.5e-7");
  EXPECT_EQ(number_to_string(1e-6), "0.000001");
  EXPECT_EQ(number_to_string(0.000123), "0.000123");
  EXPECT_EQ(number_to_string(5e-324), "5e-324");
  EXPECT_EQ(number_to_string(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(number_to_string(1.7976931348623157e308), "1.7976931348623157e+308");
  EXPECT_EQ(number_to_string(4.35), "4.35");
  EXPECT_EQ(number_to_string(333333333.33333329), "333333333.3333333");
  EXPECT_EQ(number_to_string(9007199254740992.0), "9007199254740992");
  EXPECT_EQ(number_to_string(1.2345e22), "1.2345e+22");
  EXPECT_EQ(number_to_string(std::numeric_limits<double>::infinity()), "Infinity");
  EXPECT_EQ(number_to_string(-std::numeric_limits<double>::infinity()), "-Infinity");
  EXPECT_EQ(number_to_string(std::nan("")), "NaN");
}

TEST(JsonCanonicalize, SortsByUtf16AndEscapesMinimally) {
  // U+20AC (one UTF-16 unit 0x20AC), U+FB33 (0xFB33) and U+1F600 (0xD83D 0xDE00):
  // UTF-16 order puts the astral character before U+FB33, unlike code-point order.
  const std::string euro = "\xE2\x82\xAC";
  const std::string fb33 = "\xEF\xAC\xB3";
  const std::string smile = "\xF0\x9F\x98\x80";
  Object o;
  o.set(fb33, 1);
  o.set(smile, 2);
  o.set(euro, 3);
  o.set("b", 4);
  o.set("a\x7F", 5);
  EXPECT_EQ(canonicalize(Value(o)),
            "{\"a\x7F\":5,\"b\":4,\"" + euro + "\":3,\"" + smile + "\":2,\"" + fb33 + "\":1}");
  EXPECT_EQ(canonicalize(parse(R"("\u0001\u001f\b\t\n\f\r\"\\/\u00e9")")),
            "\"\\u0001\\u001f\\b\\t\\n\\f\\r\\\"\\\\/\xC3\xA9\"");
}

TEST(JsonCanonicalize, NumbersAndNesting) {
  const Value v = parse(
      R"({"numbers":[333333333.33333329,1E30,4.50,2e-3,0.000000000000000000000000001],
          "literals":[null,true,false], "z":{"b":1,"a":[{"d":1,"c":2}]}})");
  EXPECT_EQ(canonicalize(v),
            R"({"literals":[null,true,false],"numbers":[333333333.3333333,1e+30,4.5,0.002,)"
            R"(1e-27],"z":{"a":[{"c":2,"d":1}],"b":1}})");
  EXPECT_THROW(canonicalize(Value(std::numeric_limits<double>::infinity())), Error);
}

// ---------------------------------------------------------------------------
// Values in an arena

using mospec::test::CountingResource;

constexpr std::string_view kArenaDoc =
    R"({"a long key that is not a short string": [1, "a string past the small-string buffer", {"nested object key long enough": "another value long enough to allocate"}], "esc\u00e9aped and long enough to allocate": true})";

TEST(JsonArena, ParsedValuesLiveInTheGivenResource) {
  CountingResource counting;
  {
    const Value in_arena = parse(kArenaDoc, 1, "doc.json", &counting);
    // One block per object, array, key and string past the small-string
    // buffer: 2 objects, 1 array, 3 keys and 2 strings.
    EXPECT_EQ(counting.allocations, 8u);
    EXPECT_EQ(in_arena, parse(kArenaDoc));
    EXPECT_EQ(in_arena.as_object().resource(), &counting);
    const Value& nested = in_arena.as_object().value(0).as_array()[2];
    EXPECT_EQ(nested.as_object().resource(), &counting);
    EXPECT_EQ(nested.as_object().key(0), "nested object key long enough");
  }
  EXPECT_EQ(counting.live_bytes, 0u);
}

// The parser's buffers outlive a parse when the caller passes a ParseScratch
// (the next parse reuses them): a parse that fails half-way must not leave
// values in them whose blocks are in the caller's resource, which the caller
// may free next.
TEST(JsonArena, AFailedParseLeavesNothingInTheResource) {
  CountingResource counting;
  ParseScratch scratch;
  EXPECT_THROW(parse(R"({"a long key that is not a short string": {"another long key kept in the )"
                     R"(parser's buffers": ["a string past the small-string buffer", tru]}})",
                     1, "doc.json", &counting, &scratch),
               Error);
  EXPECT_EQ(counting.live_bytes, 0u);
  EXPECT_EQ(parse(kArenaDoc), parse(kArenaDoc, 1, "doc.json", &counting, &scratch));
}

// A ParseScratch carries nothing of one document into the next: whatever came
// before (deeper, wider, duplicate keys, a failure), a document parses as it
// does with buffers of its own.
TEST(JsonArena, AReusedScratchParsesEachDocumentAsAFreshOneWould) {
  const std::vector<std::string> docs = {
      R"({"a": {"b": {"c": [1, 2, {"d": [3, 4, 5]}]}}, "e": [6, 7]})",
      R"({"x": 1, "x": 2, "y": [1], "y": {"z": true}})",
      R"([[[[["deep"]]]], {"k": "v"}, []])",
      R"({"a": [1, {"b": tru}]})",  // fails inside two levels
      R"({"only": "one"})",
      R"([1])",
      kArenaDoc.data(),
  };
  ParseScratch scratch;
  for (int round = 0; round < 2; ++round) {
    for (const std::string& doc : docs) {
      SCOPED_TRACE(doc);
      std::optional<Value> fresh;
      try {
        fresh = parse(doc);
      } catch (const Error&) {
      }
      if (fresh) {
        EXPECT_EQ(parse(doc, 0, "<input>", std::pmr::get_default_resource(), &scratch), *fresh);
      } else {
        EXPECT_THROW(parse(doc, 0, "<input>", std::pmr::get_default_resource(), &scratch), Error);
      }
    }
  }
}

TEST(JsonArena, CopiesGoToTheHeapAndOutliveTheArena) {
  Value copy;
  {
    std::pmr::monotonic_buffer_resource arena;
    const Value in_arena = parse(kArenaDoc, 1, "doc.json", &arena);
    copy = in_arena;
    EXPECT_EQ(copy.as_object().resource(), std::pmr::get_default_resource());
    EXPECT_EQ(copy.as_object().value(0).as_array()[2].as_object().resource(),
              std::pmr::get_default_resource());
  }
  // The arena is gone; the copy's bytes are its own.
  EXPECT_EQ(copy, parse(kArenaDoc));
  EXPECT_EQ(copy.as_object().value(0).as_array()[1].as_string(),
            "a string past the small-string buffer");
}

TEST(JsonArena, KeysAddedToAnArenaObjectLiveInItsResource) {
  CountingResource counting;
  {
    Object o(&counting);
    o.append_new("a key long enough to need its own block", Value(1));
    o.set(std::string("another key long enough to need its own block"), Value(2));
    EXPECT_EQ(o.key(1), "another key long enough to need its own block");
    // The members' block (grown once) and the two keys.
    EXPECT_GE(counting.allocations, 3u);
  }
  EXPECT_EQ(counting.live_bytes, 0u);
}

// What lets the loader drop a parsed or expanded tree with its arena instead
// of destroying it: every block of the tree is in the arena, key indexes of
// wide objects included, and lives_in() says so (or says where it is not).
TEST(JsonArena, AWholeParsedTreeLivesInItsArenaWideObjectsIncluded) {
  std::string wide = "{";
  for (int i = 0; i < 40; ++i) {
    wide += (i ? ", " : "") + std::string("\"member number ") + std::to_string(i) +
            " with a long key\": [\"a value long enough to allocate\"]";
  }
  wide += "}";
  CountingResource counting;
  {
    const Value in_arena = parse(wide, 1, "wide.json", &counting);
    EXPECT_TRUE(lives_in(in_arena, &counting));
    EXPECT_FALSE(lives_in(in_arena, std::pmr::get_default_resource()));
    // A find through the key index still answers.
    ASSERT_NE(in_arena.as_object().find("member number 39 with a long key"), nullptr);
    // A copy is on the heap, key index included.
    const Value copy = in_arena;
    EXPECT_TRUE(lives_in(copy, std::pmr::get_default_resource()));
    EXPECT_EQ(copy, in_arena);
  }
  EXPECT_EQ(counting.live_bytes, 0u);
}

TEST(JsonArena, LivesInFindsAHeapValueInsideAnArenaTree) {
  CountingResource counting;
  {
    Value tree = parse(kArenaDoc, 1, "doc.json", &counting);
    EXPECT_TRUE(lives_in(tree, &counting));
    // A string made on the heap and moved in keeps its resource.
    tree.as_object().value(0).as_array().push_back(
        Value(std::string_view("a heap string long enough to allocate")));
    EXPECT_FALSE(lives_in(tree, &counting));
  }
  EXPECT_EQ(counting.live_bytes, 0u);
}

// Assigning a wide object rebuilds or moves its key index so that lookups
// answer and nothing is left behind in either resource.
TEST(JsonArena, AssignedWideObjectsKeepAWorkingKeyIndex) {
  std::string wide = "{";
  for (int i = 0; i < 20; ++i)
    wide += (i ? ", " : "") + std::string("\"k") + std::to_string(i) + "\": 1";
  wide += "}";
  const Value on_heap = parse(wide);
  CountingResource counting;
  {
    Object target(&counting);
    target = on_heap.as_object();  // copy-assigned
    ASSERT_NE(target.find("k19"), nullptr);
    EXPECT_EQ(target.find("k20"), nullptr);
    Object moved_into(&counting);
    Object source = on_heap.as_object();  // on the heap
    moved_into = std::move(source);       // across resources: moved member by member
    ASSERT_NE(moved_into.find("k19"), nullptr);
    Object same(&counting);
    same = std::move(moved_into);  // same resource: the index moves with the members
    ASSERT_NE(same.find("k0"), nullptr);
    EXPECT_EQ(same.find("k20"), nullptr);
  }
  EXPECT_EQ(counting.live_bytes, 0u);
}

}  // namespace
}  // namespace mospec::json
