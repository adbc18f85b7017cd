// URDF import of untrusted text: the XML limits, malformed documents, and every
// number checked where it is stated and after each computation, each refusal
// located at FILE:LINE:COL of the element concerned (issue #32).
#include "description/urdf_import.hpp"

#include <gtest/gtest.h>
#include <pthread.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "description/chain_jsonld.hpp"
#include "description/robot_model.hpp"
#include "description/xml_outline.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"

namespace mospec::description {
namespace {

std::string error_of(const std::string& urdf, const std::string& root = "",
                     const std::string& tip = "") {
  try {
    chain_from_urdf(urdf, root, tip, "r.urdf");
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// "r.urdf:LINE:COL" of the n-th (from 0) occurrence of `needle` in `text`.
std::string at(const std::string& text, const std::string& needle, int n = 0) {
  std::size_t pos = text.find(needle);
  for (; n > 0; --n) pos = text.find(needle, pos + 1);
  const std::size_t line_start = text.rfind('\n', pos) + 1;  // npos + 1 == 0
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n');
  return "r.urdf:" + std::to_string(line) + ":" + std::to_string(pos - line_start + 1);
}

// <robot> on line 1.
std::string robot(const std::string& body) {
  return "<robot name=\"r\">\n" + body + "</robot>\n";
}

const std::string kInertia =
    "<inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/>";

std::string inertial(const std::string& mass, const std::string& inertia = kInertia,
                     const std::string& xyz = "0 0 0") {
  return "<inertial><origin xyz=\"" + xyz + "\"/><mass value=\"" + mass + "\"/>" + inertia +
         "</inertial>";
}

std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const std::string& xyz = "0 0 0.1",
                  const std::string& extra = "") {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/><origin xyz=\"" + xyz + "\"/>" + extra + "</joint>\n";
}

const std::string kAxisLimit =
    "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"1\"/>";

// base -(j1 revolute)-> l1 -(f fixed)-> l2: l2 folds into l1.
std::string folded_arm(const std::string& l1_mass, const std::string& l2_mass,
                       const std::string& f_xyz = "0 0 0.1") {
  return robot("<link name=\"base\"/>\n<link name=\"l1\">" + inertial(l1_mass) + "</link>\n" +
               "<link name=\"l2\">" + inertial(l2_mass) + "</link>\n" +
               joint("j1", "revolute", "base", "l1", "0 0 0.1", kAxisLimit) +
               joint("f", "fixed", "l1", "l2", f_xyz));
}

TEST(UrdfXml, DeepNestingIsRefusedAtTheElementPastTheLimit) {
  std::string deep = "<robot name=\"r\">";
  for (int i = 0; i < kMaxXmlDepth; ++i) deep += "<a>";
  EXPECT_EQ(error_of(deep),
            "r.urdf:1:" + std::to_string(17 + 3 * (kMaxXmlDepth - 1)) +
                ": error: element <a> is nested 65 levels deep; mospec reads URDFs nested at "
                "most 64 deep (a robot needs about 5)");
}

// Recursive parsing had no limit: a million levels overflowed TinyXML's stack.
TEST(UrdfXml, AMillionLevelsDoNotCrash) {
  std::string deep = "<robot name=\"r\">\n";
  for (int i = 0; i < 1'000'000; ++i) deep += "<a>";
  for (int i = 0; i < 1'000'000; ++i) deep += "</a>";
  deep += "</robot>";
  EXPECT_NE(error_of(deep).find("r.urdf:2:190: error: element <a> is nested 65 levels deep"),
            std::string::npos);
}

// TinyXML ends "<?" at the first '>': nesting after it, inside what XML reads
// as one processing instruction, reached TinyXML unseen by the depth limit.
TEST(UrdfXml, ProcessingInstructionsEndWhereTinyXmlEndsThem) {
  std::string hidden = "<robot name=\"r\">\n<?pi >";
  for (int i = 0; i < 1'000'000; ++i) hidden += "<a>";
  for (int i = 0; i < 1'000'000; ++i) hidden += "</a>";
  hidden += "?></robot>";
  EXPECT_EQ(error_of(hidden),
            "r.urdf:2:6: error: '>' inside a processing instruction (one ends at the first '?>')");
  EXPECT_EQ(error_of("<?xml version=\"1.0\"?>\n<robot name=\"r\"><link name=\"a\"/></robot>"),
            "(no error)");
}

TEST(UrdfXml, ElementAndAttributeCountsAreBounded) {
  std::string many = "<robot name=\"r\">\n";
  for (std::size_t i = 1; i < kMaxXmlElements; ++i) many += "<a/>";
  many += "\n<b/></robot>";
  EXPECT_EQ(error_of(many),
            "r.urdf:3:1: error: more than 100000 elements; mospec reads URDFs of at most that "
            "many");
  std::string wide = "<robot name=\"r\">\n<a";
  for (std::size_t i = 0; i <= kMaxXmlAttributes; ++i) wide += " a" + std::to_string(i) + "=''";
  wide += "/></robot>";
  EXPECT_EQ(error_of(wide), "r.urdf:2:" + std::to_string(4 + 6 * 10 + 7 * 54) +
                                ": error: element <a> has more than 64 attributes");
}

TEST(UrdfXml, MalformedXmlIsLocated) {
  EXPECT_EQ(error_of("<robot name='x'"), "r.urdf:1:1: error: unterminated start tag <robot>");
  EXPECT_EQ(error_of(robot("<link name=\"a\">\n</joint>")),
            "r.urdf:3:1: error: end tag </joint> does not close <link> (line 2, column 1)");
  EXPECT_EQ(error_of("<robot name=\"r\">\n<link name=\"a\">"),
            "r.urdf:2:1: error: element <link> is not closed (the document ends first)");
  EXPECT_EQ(error_of(robot("<link name=a/>")),
            "r.urdf:2:12: error: the value of attribute 'name' is not quoted");
  EXPECT_EQ(error_of(robot("<link name=\"a&b;\"/>")),
            "r.urdf:2:14: error: unknown entity '&b;' (XML predefines only &lt; &gt; &amp; "
            "&quot; &apos;)");
  // TinyXML said "Error reading Element value." of a reference in text.
  EXPECT_EQ(error_of(robot("<link name=\"a\">x &#xA-p;</link>")),
            "r.urdf:2:18: error: character reference '&#xA-p;' names no character XML allows");
  EXPECT_EQ(error_of(robot("<link name=\"a\" name=\"b\"/>")),
            "r.urdf:2:16: error: attribute 'name' is repeated in <link>");
  EXPECT_EQ(error_of(robot("<!-- open")), "r.urdf:2:1: error: unterminated comment");
  EXPECT_EQ(error_of(robot("<!--><link name=\"a\"/>")), "r.urdf:2:1: error: unterminated comment");
  EXPECT_EQ(error_of("<!DOCTYPE r [<!ENTITY e \"x\">]>\n<robot name=\"r\"/>"),
            "r.urdf:1:13: error: a DOCTYPE with an internal subset (entity or element "
            "declarations); a URDF needs none");
  EXPECT_EQ(error_of(robot("") + "<robot name=\"s\"/>"),
            "r.urdf:3:1: error: a second root element <robot> (a URDF is one <robot> element)");
  EXPECT_EQ(error_of(""),
            "mospec: error: the document has no element (a URDF is one <robot> element) (in "
            "r.urdf)");
  EXPECT_EQ(error_of("<link name=\"a\"/>"),
            "r.urdf:1:1: error: the root element is <link>; a URDF's is <robot>");
}

// TinyXML steps over a UTF-8 sequence by its lead byte, so an ill-formed one
// can swallow the quote after it: urdfdom then said only "Error reading
// Attributes.", at no line (fuzz/corpus/urdf/utf8-swallows-quote.urdf).
TEST(UrdfXml, IllFormedUtf8IsRefused) {
  const std::string text = robot("<link name=\"a\xE6l\"/>");
  EXPECT_EQ(error_of(text), at(text, "\xE6") + ": error: ill-formed UTF-8 (a URDF is UTF-8 text)");
  // TinyXML skips a byte order mark anywhere as a space: as an attribute's
  // name it read '="..."' and said "Error reading Attributes.", at no line.
  const std::string bom = "\xEF\xBB\xBF" + robot("<link name=\"a\" \xEF\xBB\xBF=\"1\"/>");
  EXPECT_EQ(error_of(bom), at(bom, "\xEF\xBB\xBF", 1) +
                               ": error: U+FEFF, U+FFFE or U+FFFF after the start of the document "
                               "(TinyXML reads them as spaces)");
}

// urdfdom logs a value it cannot read with the value in printf's format: a
// mass of "%s%s%s%s%n" read and wrote through whatever the stack held.
TEST(UrdfXml, PercentSignsAreRefusedOutsideFileNames) {
  const std::string format = robot("<link name=\"a\">" + inertial("%s%s%s%s%n") + "</link>");
  EXPECT_EQ(error_of(format),
            at(format, "%s") +
                ": error: '%' in the value of attribute 'value' (urdfdom passes some values to "
                "printf as its format; only a filename may hold a '%')");
  const std::string reference = robot("<link name=\"a\">" + inertial("&#37;n") + "</link>");
  EXPECT_EQ(error_of(reference).rfind(
                at(reference, "&#37;") + ": error: '%' in the value of attribute 'value'", 0),
            0u);
  EXPECT_EQ(error_of(robot("<link name=\"a\"><visual><geometry><mesh "
                           "filename=\"package://r/a%20b.stl\"/></geometry></visual></link>\n")),
            "(no error)");
}

// urdfdom reads a C string: what followed a NUL was never seen, so a file
// could say one thing to mospec's checks and another to urdfdom.
TEST(UrdfXml, ControlCharactersAreRefused) {
  std::string with_nul = robot("<link name=\"a\"/>") + "x";
  with_nul[with_nul.size() - 1] = '\0';
  EXPECT_EQ(error_of(with_nul),
            "r.urdf:3:1: error: control character 0x00 (XML allows only tab, line feed and "
            "carriage return)");
}

TEST(UrdfTree, LinksAreATree) {
  const std::string links = "<link name=\"a\"/>\n<link name=\"b\"/>\n<link name=\"c\"/>\n";
  EXPECT_EQ(error_of(robot(links + "<link name=\"b\"/>\n")),
            "r.urdf:5:1: error: link 'b' is defined twice (first at line 3, column 1)");
  EXPECT_EQ(
      error_of(robot(links + joint("j1", "fixed", "a", "c") + joint("j2", "fixed", "b", "c"))),
      "r.urdf:6:1: error: link 'c' is the child of joints 'j1' (line 5, column 1) and "
      "'j2'; a URDF is a tree, each link has one parent joint");
  // A cycle away from the root parses in urdfdom; walking up from 'c' never ended.
  const std::string cycle =
      robot(links + joint("j1", "fixed", "b", "c") + joint("j2", "fixed", "c", "b"));
  EXPECT_EQ(error_of(cycle, "a", "c"),
            "r.urdf:5:1: error: joint 'j1' closes a cycle through link 'c'; a URDF is a tree");
}

TEST(UrdfTree, RefusalsAboutLinksPointAtTheirElements) {
  const std::string arm = folded_arm("1", "1");
  EXPECT_EQ(error_of(arm, "", "hand"),
            "r.urdf:1:1: error: robot 'r' has no link 'hand' (links: base, l1, l2)");
  EXPECT_EQ(error_of(arm, "l2", "l1"),
            "r.urdf:3:1: error: link 'l2' is not an ancestor of link 'l1' (the path from 'l1' "
            "ends at the root link 'base')");
  EXPECT_EQ(error_of(robot("<link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\n" +
                           joint("j1", "fixed", "a", "b") + joint("j2", "fixed", "a", "c"))),
            "r.urdf:1:1: error: robot 'r' has 2 leaf links (b, c); name the chain's tip link");
}

// A name with a line break (&#10;) was written raw into a JSON string, and a
// ':' made "link-x:y" an absolute IRI.
TEST(UrdfTree, NamesOnTheChainMustBeIriSafe) {
  const std::string newline =
      robot("<link name=\"a\"/>\n<link name=\"b&#10;c\"/>\n" + joint("j", "fixed", "a", "b&#10;c"));
  EXPECT_EQ(error_of(newline),
            "r.urdf:3:1: error: link 'b\\x0ac': the names of the chain's links and joints become "
            "IRIs of the written model and may hold only letters, digits and - . _ ~ (rename it)");
  const std::string colon =
      robot("<link name=\"a\"/>\n<link name=\"b\"/>\n" + joint("x:y", "fixed", "a", "b"));
  EXPECT_EQ(error_of(colon),
            "r.urdf:4:1: error: joint 'x:y': the names of the chain's links and joints become IRIs "
            "of the written model and may hold only letters, digits and - . _ ~ (rename it)");
}

TEST(UrdfTree, LongListsOfNamesAreCut) {
  std::string body = "<link name=\"l100\"/>";
  for (int i = 101; i < 130; ++i) {
    const std::string name = std::string("l").append(std::to_string(i));
    body.append("<link name=\"").append(name).append("\"/>");
    body += joint(std::string("j").append(name), "fixed", "l100", name);
  }
  const std::string message = error_of(robot(body));
  EXPECT_NE(message.find("has 29 leaf links (l101, l102, "), std::string::npos) << message;
  EXPECT_NE(message.find("l119, l120, ... (9 more)); name"), std::string::npos) << message;
}

// urdfdom's own refusals, located at the element its message names.
TEST(UrdfDom, RefusalsAreLocated) {
  const std::string bad_mass = robot("<link name=\"a\">\n" + inertial("heavy") + "</link>\n");
  EXPECT_EQ(error_of(bad_mass),
            at(bad_mass, "<mass") +
                ": error: urdfdom cannot read the URDF: Inertial: mass [heavy] is not a float; "
                "Could not parse inertial element for Link [a]");
  const std::string no_child = robot("<link name=\"a\"/>\n" + joint("j", "fixed", "a", "nope"));
  EXPECT_EQ(error_of(no_child),
            at(no_child, "<child") +
                ": error: urdfdom cannot read the URDF: Failed to build tree: child link [nope] "
                "of joint [j] not found");
  // Names holding ']', and urdfdom's "for joint  [j]" with two spaces.
  EXPECT_EQ(error_of(robot("<link name=\"a\"/>\n<link name=\"b\"/>\n" +
                           joint("j]x", "revolute", "a", "b"))),
            "r.urdf:4:1: error: urdfdom cannot read the URDF: Joint [j]x] is of type REVOLUTE but "
            "it does not specify limits; joint xml is not initialized correctly");
  const std::string mimic = robot("<link name=\"a\"/>\n<link name=\"b\"/>\n" +
                                  joint("j", "fixed", "a", "b", "0 0 0", "<mimic/>"));
  EXPECT_EQ(error_of(mimic), at(mimic, "<mimic") +
                                 ": error: urdfdom cannot read the URDF: joint mimic: no mimic "
                                 "joint specified; Could not parse mimic element for joint  [j]; "
                                 "joint xml is not initialized correctly");
  EXPECT_EQ(
      error_of(robot("<link name=\"a\"/>\n<link name=\"b\"/>\n" + joint("j", "hinge", "a", "b"))),
      "r.urdf:4:1: error: urdfdom cannot read the URDF: Joint [j] has no known type "
      "[hinge]; joint xml is not initialized correctly");
  EXPECT_EQ(error_of(robot("<link name=\"a\"/>\n<link>\n</link>")),
            "r.urdf:3:1: error: urdfdom cannot read the URDF: No name given for the link.; Failed "
            "to find root link: Two root links found: [] and [a]");
  EXPECT_EQ(error_of(robot("<link name=\"a\"/>\n<link name=\"b\"/>\n" +
                           joint("j", "revolute", "a", "b", "0 0 0",
                                 "<axis xyz=\"0 0 1\"/>\n<limit lower=\"x\"/>"))),
            "r.urdf:5:1: error: urdfdom cannot read the URDF: lower value (x) is not a valid "
            "float; Could not parse limit element for joint [j]; joint xml is not initialized "
            "correctly");
}

// Stated numbers: checked where they are stated.
TEST(UrdfNumbers, StatedMassesAndInertiasArePhysical) {
  const std::string zero = folded_arm("0", "1");
  EXPECT_EQ(error_of(zero), at(zero, "<mass") +
                                ": error: link 'l1': the mass is 0 kg; it must be finite and > 0 "
                                "(a massless link has no <inertial>)");
  const std::string negative = folded_arm("1", "-2");
  EXPECT_EQ(error_of(negative), at(negative, "<mass", 1) +
                                    ": error: link 'l2': the mass is -2 kg; it must be finite "
                                    "and > 0 (a massless link has no <inertial>)");
  const std::string not_psd = robot(
      "<link name=\"a\"/>\n<link name=\"b\">" +
      inertial("1", "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"-1\"/>") +
      "</link>\n" + joint("j", "revolute", "a", "b", "0 0 0", kAxisLimit));
  EXPECT_EQ(error_of(not_psd), at(not_psd, "<inertia ") +
                                   ": error: link 'b': the rotational inertia is not positive "
                                   "semi-definite (principal moments -1 1 1 kg m^2)");
  const std::string triangle = robot(
      "<link name=\"a\"/>\n<link name=\"b\">" +
      inertial("1", "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"3\"/>") +
      "</link>\n" + joint("j", "revolute", "a", "b", "0 0 0", kAxisLimit));
  EXPECT_EQ(error_of(triangle),
            at(triangle, "<inertia ") +
                ": error: link 'b': the rotational inertia's principal moments 1 1 3 kg m^2 "
                "break the triangle inequality (the largest exceeds the sum of the other two, "
                "which no body can)");
}

TEST(UrdfNumbers, JointAxesAndLimitsAreChecked) {
  const std::string links = "<link name=\"a\"/>\n<link name=\"b\"/>\n";
  const std::string zero_axis = robot(links + joint("j", "revolute", "a", "b", "0 0 0",
                                                    "<axis xyz=\"0 0 0\"/><limit effort=\"1\" "
                                                    "velocity=\"1\"/>"));
  EXPECT_EQ(error_of(zero_axis),
            at(zero_axis, "<axis") + ": error: joint 'j': axis (0 0 0) is zero");
  const std::string crossed = robot(links + joint("j", "revolute", "a", "b", "0 0 0",
                                                  "<axis xyz=\"0 0 1\"/><limit lower=\"1\" "
                                                  "upper=\"0\" effort=\"1\" velocity=\"1\"/>"));
  EXPECT_EQ(error_of(crossed),
            at(crossed, "<limit") + ": error: joint 'j': <limit> lower 1 exceeds upper 0");
  const std::string negative = robot(links + joint("j", "revolute", "a", "b", "0 0 0",
                                                   "<axis xyz=\"0 0 1\"/><limit effort=\"-1\" "
                                                   "velocity=\"1\"/>"));
  EXPECT_EQ(error_of(negative), at(negative, "<limit") +
                                    ": error: joint 'j': <limit> velocity 1 and effort -1 must "
                                    "be >= 0");
  // Components near the largest double: the norm overflowed and a valid axis was refused.
  const Chain chain = chain_from_urdf(
      robot(links + joint("j", "revolute", "a", "b", "0 0 0",
                          "<axis xyz=\"1e308 1e308 0\"/><limit effort=\"1\" velocity=\"1\"/>")),
      "", "");
  EXPECT_NEAR(chain.segment(0).axis_J.x(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(chain.segment(0).axis_J.y(), std::sqrt(0.5), 1e-15);
}

// What the importer refuses carries its own code.
TEST(UrdfNumbers, RefusalsAreInvalidUrdf) {
  try {
    chain_from_urdf(folded_arm("1e308", "1e308"), "", "", "r.urdf");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid-urdf") << e.what();
  }
}

// Computed numbers: folding merged two finite masses into an infinite one and
// import-urdf wrote "mass": inf with exit status 0.
TEST(UrdfNumbers, FoldedMassesAreCheckedAgain) {
  EXPECT_EQ(error_of(folded_arm("1e308", "1e308")),
            "r.urdf:6:1: error: fixed joint 'f' folds link 'l2' into link 'l1': link 'l1' with "
            "link 'l2' folded in: mass must be finite and >= 0, got inf kg");
  // Finite masses whose parallel-axis term overflows.
  EXPECT_EQ(error_of(folded_arm("1e300", "1e300", "0 0 1e10")),
            "r.urdf:6:1: error: fixed joint 'f' folds link 'l2' into link 'l1': link 'l1' with "
            "link 'l2' folded in: inertia has non-finite entries");
  // Finite origins whose composition overflows.
  EXPECT_EQ(error_of(robot("<link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\n" +
                           joint("f1", "fixed", "a", "b", "1e308 0 0") +
                           joint("f2", "fixed", "b", "c", "1e308 0 0"))),
            "r.urdf:4:1: error: joint 'f2': fixed joint to link 'c' (composed with the fixed "
            "joints before it): origin is not a rigid transform (position inf 0 0)");
  EXPECT_EQ(error_of(robot("<link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\n" +
                           joint("f1", "fixed", "a", "b", "1e308 0 0") +
                           joint("j", "revolute", "b", "c", "1e308 0 0", kAxisLimit))),
            "r.urdf:4:1: error: joint 'j' (composed with the fixed joints before it): origin is "
            "not a rigid transform (position inf 0 0)");
}

// What an import writes has no inf or nan: the largest finite masses that fold
// still make a document of finite numbers.
TEST(UrdfNumbers, ImportsWriteOnlyFiniteNumbers) {
  const std::string text = chain_to_jsonld(chain_from_urdf(folded_arm("8e307", "8e307"), "", ""));
  EXPECT_EQ(text.find("inf"), std::string::npos);
  EXPECT_EQ(text.find("nan"), std::string::npos);
  EXPECT_NE(text.find("\"mass\": 1.6e+308"), std::string::npos);
}

// urdfdom's links own their children: freeing a chain of 19,000 links recursed
// once per link, 1 to 2 MiB of stack (it crashed in 1 MiB). The import must
// not need more stack for a longer chain: run it on a thread with 512 KiB.
TEST(UrdfTree, ALongChainIsFreedWithoutRecursion) {
  std::string body = "<link name=\"l0\"/>\n";
  const int n = 19'000;  // 5 elements each, within kMaxXmlElements
  for (int i = 1; i <= n; ++i) {
    const std::string name = std::string("l").append(std::to_string(i));
    body.append("<link name=\"").append(name).append("\"/>");
    body += joint(std::string("j").append(name), "fixed",
                  std::string("l").append(std::to_string(i - 1)), name);
  }
  struct Job {
    std::string urdf;
    std::string tip;
  } job{robot(body), {}};
  pthread_attr_t attributes;
  ASSERT_EQ(pthread_attr_init(&attributes), 0);
  ASSERT_EQ(pthread_attr_setstacksize(&attributes, 512 * 1024), 0);
  pthread_t thread;
  ASSERT_EQ(pthread_create(
                &thread, &attributes,
                [](void* arg) -> void* {
                  auto* j = static_cast<Job*>(arg);
                  j->tip = chain_from_urdf(j->urdf, "", "").tip();
                  return nullptr;
                },
                &job),
            0);
  ASSERT_EQ(pthread_join(thread, nullptr), 0);
  pthread_attr_destroy(&attributes);
  EXPECT_EQ(job.tip, std::string("l").append(std::to_string(n)));
}

// import-urdf keeps the URDF's joint limits as model quantities (issue #33
// item 7): position limits where the joint has them (not on a continuous
// joint), velocity and effort limits, each in its joint type's unit, read back
// by chain_from_rdf as the URDF states them.
TEST(UrdfImport, JointLimitsAreKeptAsModelQuantities) {
  const std::string urdf =
      robot("<link name=\"base\"/>\n<link name=\"l1\">" + inertial("1") +
            "</link>\n<link name=\"l2\">" + inertial("1") + "</link>\n<link name=\"l3\">" +
            inertial("1") + "</link>\n<link name=\"tool0\"/>\n" +
            joint("j1", "revolute", "base", "l1", "0 0 0.1",
                  "<axis xyz=\"0 0 1\"/><limit lower=\"-2.5\" upper=\"2\" effort=\"39\" "
                  "velocity=\"1.3\"/>") +
            joint("j2", "continuous", "l1", "l2", "0 0 0.1",
                  "<axis xyz=\"0 1 0\"/><limit effort=\"9\" velocity=\"2.5\"/>") +
            joint("j3", "prismatic", "l2", "l3", "0 0 0.1",
                  "<axis xyz=\"1 0 0\"/><limit lower=\"0\" upper=\"0.2\" effort=\"100\" "
                  "velocity=\"0.1\"/>") +
            joint("flange", "fixed", "l3", "tool0"));
  const UrdfChain imported = import_urdf(urdf, "", "", "r.urdf");
  EXPECT_EQ(imported.robot, "r");
  // tool0 hangs on the last moving link by a fixed joint: import-urdf says so.
  EXPECT_EQ(imported.tip_joints, std::vector<std::string>{"flange"});
  ChainJsonldOptions options;
  options.base = "https://ex.org/r/";
  options.metamodels = "https://comp-rob2b.github.io/metamodels/";
  const std::string text = chain_to_jsonld(imported.chain, options);
  // The published kc-ext:JointLimit, typed by the kind of quantity it limits,
  // its bounds quantities with kind and unit (velocity and effort symmetric).
  for (const char* stated :
       {"\"https://secorolab.github.io/metamodels/kinematic-chain/"
        "structural-entities-extension.json\"",
        "\"https://comp-rob2b.github.io/metamodels/kinematic-chain/state.json\"",
        "\"@id\": \"position-limit-j1\"", "[ \"JointLimit\", \"kc-stat:JointPosition\" ]",
        "\"lower\": { \"@type\": \"Quantity\", \"quantity-kind\": \"Angle\", \"unit\": "
        "\"RAD\", \"value\": -2.5 }",
        "\"upper\": { \"@type\": \"Quantity\", \"quantity-kind\": \"Angle\", \"unit\": "
        "\"RAD\", \"value\": 2 }",
        "\"@id\": \"effort-limit-j1\"", "[ \"JointLimit\", \"kc-stat:JointForce\" ]",
        "\"upper\": { \"@type\": \"Quantity\", \"quantity-kind\": \"Torque\", \"unit\": "
        "\"N-M\", \"value\": 39 }",
        "\"@id\": \"velocity-limit-j2\"", "[ \"JointLimit\", \"kc-stat:JointVelocity\" ]",
        "\"lower\": { \"@type\": \"Quantity\", \"quantity-kind\": \"AngularVelocity\", "
        "\"unit\": \"RAD-PER-SEC\", \"value\": -2.5 }",
        "\"@id\": \"effort-limit-j3\"",
        "\"lower\": { \"@type\": \"Quantity\", \"quantity-kind\": \"Force\", \"unit\": "
        "\"N\", \"value\": -100 }",
        "\"upper\": { \"@type\": \"Quantity\", \"quantity-kind\": \"LinearVelocity\", "
        "\"unit\": \"M-PER-SEC\", \"value\": 0.1 }",
        "\"upper\": { \"@type\": \"Quantity\", \"quantity-kind\": \"Length\", \"unit\": "
        "\"M\", \"value\": 0.2 }",
        "mospec/joints.json"}) {
    EXPECT_NE(text.find(stated), std::string::npos) << stated << " in\n" << text;
  }
  // A continuous joint has no position limits to state; mospec's retired
  // limit classes are gone.
  EXPECT_EQ(text.find("position-limit-j2"), std::string::npos);
  for (const char* retired : {"JointPositionLimits", "JointVelocityLimit", "JointEffortLimit"})
    EXPECT_EQ(text.find(retired), std::string::npos) << retired;

  const std::string file = ::testing::TempDir() + "limits.jsonld";
  write_output(file, text);
  const Chain back = load_chain(file, "https://ex.org/r/chain",
                                {{"https://comp-rob2b.github.io/metamodels/",
                                  std::string(MOSPEC_SOURCE_DIR) + "/metamodels"}});
  ASSERT_EQ(back.size(), 3);
  const runtime::JointLimits& j1 = back.segment(0).limits;
  EXPECT_EQ(j1.lower, -2.5);
  EXPECT_EQ(j1.upper, 2.0);
  EXPECT_EQ(j1.velocity, 1.3);
  EXPECT_EQ(j1.effort, 39.0);
  const runtime::JointLimits& j2 = back.segment(1).limits;
  EXPECT_TRUE(std::isinf(j2.lower) && std::isinf(j2.upper));
  EXPECT_EQ(j2.velocity, 2.5);
  EXPECT_EQ(j2.effort, 9.0);
  const runtime::JointLimits& j3 = back.segment(2).limits;
  EXPECT_EQ(j3.lower, 0.0);
  EXPECT_EQ(j3.upper, 0.2);
  EXPECT_EQ(j3.effort, 100.0);
}

}  // namespace
}  // namespace mospec::description
