// A linear, non-recursive pass over a URDF's XML before urdfdom reads it.
//
// urdfdom parses with TinyXML, which recurses once per element level while it
// parses and again while it frees the tree, finds duplicate attributes by a
// linear search (quadratic in an element's attributes), and reports a syntax
// error without its line. This pass bounds what reaches TinyXML (depth,
// element count, attributes per element), refuses what XML does not allow with
// the line and column of the offending byte, and keeps each element's name,
// attributes and position, so that the importer can locate what it refuses at
// the <link>, <joint>, <inertial> or <origin> concerned.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace mospec::description {

// A URDF needs 5 levels (robot/link/visual/geometry/mesh); 64 leaves room for
// extension elements (<gazebo> plugins) and stays far from TinyXML's stack use.
inline constexpr int kMaxXmlDepth = 64;
// A large robot (hundreds of links with visuals and collisions) has a few
// thousand elements; the bound keeps urdfdom's model, and the memory TinyXML
// takes for it, small.
inline constexpr std::size_t kMaxXmlElements = 100'000;
// A URDF element has at most 7 attributes (<inertia> has 6).
inline constexpr std::size_t kMaxXmlAttributes = 64;

struct XmlAttribute {
  std::string name;
  std::string value;  // entity and character references replaced
};

struct XmlElement {
  std::string name;
  uint32_t line = 0;    // of the start tag's '<', 1-based
  uint32_t column = 0;  // in bytes, 1-based
  int parent = -1;      // index in XmlOutline::elements; -1 for the root
  int first_child = -1;
  int next_sibling = -1;
  std::vector<XmlAttribute> attributes;

  // The attribute's value, or nullptr when the element has none of that name.
  const std::string* attribute(std::string_view attribute_name) const;
};

struct XmlOutline {
  std::vector<XmlElement> elements;  // in document order; elements[0] is the root

  // The first child of `parent` named `name` (the one urdfdom reads), or -1.
  int first_child(int parent, std::string_view name) const;
};

// Text from the document as messages quote it: printable ASCII as is, other
// bytes as \xHH, cut after `max` bytes, so a hostile name can neither flood
// nor garble the terminal.
std::string shown(std::string_view s, std::size_t max = 60);

// Scans `text` (the whole document; `source` names it in errors). Throws
// mospec::Error (code "invalid-urdf") at FILE:LINE:COL of the first offending
// byte or element: a NUL or other control character, a malformed tag,
// attribute, comment, CDATA section or processing instruction, an unquoted or
// duplicate attribute, a '%' in the value of an attribute other than
// `filename` (raw or as &#37;: urdfdom uses some values as printf formats),
// an unknown entity, a mismatched or missing end tag, text
// or a second element outside the root, a DOCTYPE with an internal subset, an
// element nested deeper than kMaxXmlDepth, the element past kMaxXmlElements, or
// one with more than kMaxXmlAttributes attributes. A document with no element
// at all is refused naming only the file.
XmlOutline scan_xml(std::string_view text, const std::string& source);

}  // namespace mospec::description
