#include "description/xml_outline.hpp"

#include <cstdio>
#include <cstring>

#include "support/diagnostics.hpp"
#include "support/utf8.hpp"

namespace mospec::description {

const std::string* XmlElement::attribute(std::string_view attribute_name) const {
  for (const XmlAttribute& a : attributes)
    if (a.name == attribute_name) return &a.value;
  return nullptr;
}

int XmlOutline::first_child(int parent, std::string_view name) const {
  for (int c = elements[static_cast<std::size_t>(parent)].first_child; c >= 0;
       c = elements[static_cast<std::size_t>(c)].next_sibling) {
    if (elements[static_cast<std::size_t>(c)].name == name) return c;
  }
  return -1;
}

namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

// As TinyXML reads names: it takes '<' before anything else (a ':' too) for
// markup to skip up to the next '>', which this scan must not take for an
// element.
bool is_name_start(char c) {
  const auto u = static_cast<unsigned char>(c);
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || u >= 0x80;
}

bool is_name_char(char c) {
  return is_name_start(c) || (c >= '0' && c <= '9') || c == '-' || c == '.' || c == ':';
}

// XML 1.0's Char production: what a character reference may name.
bool is_xml_char(uint32_t c) {
  return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) ||
         (c >= 0xE000 && c <= 0xFFFD) || (c >= 0x10000 && c <= 0x10FFFF);
}

class Scanner {
 public:
  Scanner(std::string_view text, const std::string& source) : t_(text), source_(source) {}

  XmlOutline run() {
    check_characters();
    std::size_t i = 0;
    // A byte order mark is no text outside the root.
    if (t_.substr(0, 3) == "\xEF\xBB\xBF") i = 3;
    while (i < t_.size()) {
      if (t_[i] != '<') {
        i = text(i);
      } else if (starts(i, "<?")) {
        i = processing_instruction(i);
      } else if (starts(i, "<!--")) {
        i = skip_past(i, 4, "-->", "comment");
      } else if (starts(i, "<![CDATA[")) {
        if (stack_.empty()) fail(i, "a CDATA section outside the root element");
        i = skip_past(i, 9, "]]>", "CDATA section");
      } else if (starts(i, "<!DOCTYPE")) {
        i = doctype(i);
      } else if (starts(i, "<!")) {
        fail(i, "unknown markup '<!'; only comments, CDATA sections and a DOCTYPE start so");
      } else if (starts(i, "</")) {
        i = end_tag(i);
      } else {
        i = start_tag(i);
      }
    }
    if (!stack_.empty()) {
      const XmlElement& open = outline_.elements[static_cast<std::size_t>(stack_.back())];
      throw Error("invalid-urdf",
                  "element <" + shown(open.name) + "> is not closed (the document ends first)",
                  source_, open.line, open.column);
    }
    if (outline_.elements.empty()) {
      throw Error("invalid-urdf", "the document has no element (a URDF is one <robot> element)",
                  source_);
    }
    return std::move(outline_);
  }

 private:
  [[noreturn]] void fail(std::size_t pos, const std::string& message) {
    advance_to(pos);
    throw Error("invalid-urdf", message, source_, line_, column(pos));
  }

  // Line counting moves forward only: positions are asked for in order.
  void advance_to(std::size_t pos) {
    for (const char* p = t_.data() + counted_; counted_ < pos;) {
      const void* nl = std::memchr(p, '\n', pos - counted_);
      if (nl == nullptr) {
        counted_ = pos;
        break;
      }
      const auto at = static_cast<std::size_t>(static_cast<const char*>(nl) - t_.data());
      ++line_;
      line_start_ = at + 1;
      counted_ = at + 1;
      p = t_.data() + counted_;
    }
  }
  uint32_t column(std::size_t pos) const { return static_cast<uint32_t>(pos - line_start_ + 1); }

  bool starts(std::size_t i, std::string_view s) const { return t_.substr(i, s.size()) == s; }

  // TinyXML steps over a UTF-8 sequence by its lead byte: an ill-formed one
  // would swallow the quote or '>' after it and misparse what follows.
  void check_characters() {
    const std::size_t invalid = find_invalid_utf8(t_);
    for (std::size_t i = 0; i < t_.size() && i <= invalid; ++i) {
      if (i == invalid) fail(i, "ill-formed UTF-8 (a URDF is UTF-8 text)");
      const auto u = static_cast<unsigned char>(t_[i]);
      // TinyXML skips U+FEFF, U+FFFE and U+FFFF as if they were spaces, so
      // one inside a tag would end a name there for TinyXML and not here.
      if (u == 0xEF && i > 0 &&
          (t_.substr(i, 3) == "\xEF\xBB\xBF" || t_.substr(i, 3) == "\xEF\xBF\xBE" ||
           t_.substr(i, 3) == "\xEF\xBF\xBF")) {
        fail(i,
             "U+FEFF, U+FFFE or U+FFFF after the start of the document (TinyXML reads "
             "them as spaces)");
      }
      if (u < 0x20 && u != '\t' && u != '\n' && u != '\r') {
        char code[8];
        std::snprintf(code, sizeof code, "0x%02x", u);
        fail(i, std::string("control character ") + code +
                    " (XML allows only tab, line feed and carriage return)");
      }
    }
  }

  // The end is looked for after the whole opener: "<!-->" opens a comment and
  // does not close it (TinyXML reads on to the next "-->").
  std::size_t skip_past(std::size_t i, std::size_t opener, std::string_view end, const char* what) {
    const std::size_t e = t_.find(end, i + opener);
    if (e == std::string_view::npos) fail(i, std::string("unterminated ") + what);
    return e + end.size();
  }

  // TinyXML ends a processing instruction (and the XML declaration) at its
  // first '>', XML at "?>": what lies between would be hidden from this scan
  // and parsed by TinyXML, so the two must coincide.
  std::size_t processing_instruction(std::size_t i) {
    const std::size_t gt = t_.find('>', i + 2);
    if (gt == std::string_view::npos) fail(i, "unterminated processing instruction");
    if (t_[gt - 1] != '?' || gt - 1 < i + 2) {
      fail(gt, "'>' inside a processing instruction (one ends at the first '?>')");
    }
    return gt + 1;
  }

  std::size_t doctype(std::size_t i) {
    if (!outline_.elements.empty()) fail(i, "a DOCTYPE after the root element");
    for (std::size_t j = i + 9; j < t_.size(); ++j) {
      if (t_[j] == '>') return j + 1;
      if (t_[j] == '[') {
        fail(j,
             "a DOCTYPE with an internal subset (entity or element declarations); a URDF "
             "needs none");
      }
    }
    fail(i, "unterminated DOCTYPE");
  }

  std::size_t text(std::size_t i) {
    const void* lt = std::memchr(t_.data() + i, '<', t_.size() - i);
    const std::size_t end =
        lt ? static_cast<std::size_t>(static_cast<const char*>(lt) - t_.data()) : t_.size();
    if (stack_.empty()) {
      for (std::size_t j = i; j < end; ++j)
        if (!is_space(t_[j])) fail(j, "text outside the root element");
    }
    // TinyXML decodes the references of text too, and fails on a malformed
    // "&#...;" without saying where.
    std::string decoded;
    for (std::size_t j = i; j < end; ++j) {
      if (t_[j] == '&') j = reference(j, end, decoded);
    }
    return end;
  }

  std::size_t name_end(std::size_t i) const {
    if (i >= t_.size() || !is_name_start(t_[i])) return i;
    while (i < t_.size() && is_name_char(t_[i])) ++i;
    return i;
  }

  std::size_t skip_space(std::size_t i) const {
    while (i < t_.size() && is_space(t_[i])) ++i;
    return i;
  }

  std::size_t start_tag(std::size_t i) {
    const std::size_t name_begin = i + 1, name_stop = name_end(name_begin);
    if (name_stop == name_begin) fail(i, "'<' starts no element name");
    if (stack_.empty() && !outline_.elements.empty()) {
      fail(i, "a second root element <" + shown(t_.substr(name_begin, name_stop - name_begin)) +
                  "> (a URDF is one <robot> element)");
    }
    if (outline_.elements.size() == kMaxXmlElements) {
      fail(i, "more than " + std::to_string(kMaxXmlElements) +
                  " elements; mospec reads URDFs of at most that many");
    }
    if (stack_.size() == static_cast<std::size_t>(kMaxXmlDepth)) {
      fail(i, "element <" + shown(t_.substr(name_begin, name_stop - name_begin)) + "> is nested " +
                  std::to_string(kMaxXmlDepth + 1) +
                  " levels deep; mospec reads URDFs nested at most " +
                  std::to_string(kMaxXmlDepth) + " deep (a robot needs about 5)");
    }
    advance_to(i);
    const int index = static_cast<int>(outline_.elements.size());
    XmlElement element;
    element.name.assign(t_.substr(name_begin, name_stop - name_begin));
    element.line = line_;
    element.column = column(i);
    element.parent = stack_.empty() ? -1 : stack_.back();
    std::size_t j = name_stop;
    for (;;) {
      const std::size_t k = skip_space(j);
      if (k >= t_.size()) fail(i, "unterminated start tag <" + shown(element.name) + ">");
      if (t_[k] == '>' || starts(k, "/>")) {
        link(index, element.parent);
        outline_.elements.push_back(std::move(element));
        last_child_.push_back(-1);
        if (t_[k] == '>') {
          stack_.push_back(index);
          return k + 1;
        }
        return k + 2;
      }
      if (k == j) fail(k, "expected whitespace, '>' or '/>' in the start tag");
      j = attribute(k, element);
    }
  }

  // Keeps the tree's child lists: the last child of each open element is the
  // one the next child follows.
  void link(int index, int parent) {
    if (parent < 0) return;
    XmlElement& p = outline_.elements[static_cast<std::size_t>(parent)];
    if (p.first_child < 0) {
      p.first_child = index;
    } else {
      outline_.elements[static_cast<std::size_t>(last_child_[static_cast<std::size_t>(parent)])]
          .next_sibling = index;
    }
    last_child_[static_cast<std::size_t>(parent)] = index;
  }

  std::size_t attribute(std::size_t i, XmlElement& element) {
    const std::size_t stop = name_end(i);
    if (stop == i) fail(i, "expected an attribute name");
    std::string name(t_.substr(i, stop - i));
    if (element.attributes.size() == kMaxXmlAttributes) {
      fail(i, "element <" + shown(element.name) + "> has more than " +
                  std::to_string(kMaxXmlAttributes) + " attributes");
    }
    if (element.attribute(name) != nullptr) {
      fail(i, "attribute '" + shown(name) + "' is repeated in <" + shown(element.name) + ">");
    }
    std::size_t j = skip_space(stop);
    if (j >= t_.size() || t_[j] != '=')
      fail(j, "expected '=' after attribute '" + shown(name) + "'");
    j = skip_space(j + 1);
    if (j >= t_.size() || (t_[j] != '"' && t_[j] != '\'')) {
      fail(j, "the value of attribute '" + shown(name) + "' is not quoted");
    }
    const std::size_t close = t_.find(t_[j], j + 1);
    if (close == std::string_view::npos)
      fail(j, "unterminated value of attribute '" + shown(name) + "'");
    std::string value;
    value.reserve(close - j - 1);
    // urdfdom hands some values it cannot read to printf as the format of its
    // message ("Inertial: mass [%n] is not a float"); no URDF value needs a
    // '%' but a file name.
    const bool may_hold_percent = name == "filename";
    for (std::size_t k = j + 1; k < close; ++k) {
      if (t_[k] == '<') fail(k, "'<' in the value of attribute '" + shown(name) + "'");
      if (t_[k] != '&') {
        if (t_[k] == '%' && !may_hold_percent) percent(k, name);
        value += t_[k];
        continue;
      }
      const std::size_t ref = k;
      k = reference(k, close, value);
      if (!may_hold_percent && !value.empty() && value.back() == '%') percent(ref, name);
    }
    element.attributes.push_back({std::move(name), std::move(value)});
    return close + 1;
  }

  [[noreturn]] void percent(std::size_t i, const std::string& name) {
    fail(i, "'%' in the value of attribute '" + shown(name) +
                "' (urdfdom passes some values to printf as its format; only a filename may hold "
                "a '%')");
  }

  // Replaces the reference at i (a '&') and returns the position of its ';'.
  std::size_t reference(std::size_t i, std::size_t limit, std::string& out) {
    const std::size_t semi = t_.find(';', i);
    if (semi == std::string_view::npos || semi >= limit || semi - i > 12) {
      fail(i, "'&' starts no entity or character reference (write &amp; for '&')");
    }
    const std::string_view ref = t_.substr(i + 1, semi - i - 1);
    static constexpr std::pair<std::string_view, char> kEntities[] = {
        {"lt", '<'}, {"gt", '>'}, {"amp", '&'}, {"quot", '"'}, {"apos", '\''}};
    for (const auto& [entity, c] : kEntities) {
      if (ref == entity) {
        out += c;
        return semi;
      }
    }
    if (ref.size() >= 2 && ref[0] == '#') {
      const bool hex = ref[1] == 'x';
      const std::string_view digits = ref.substr(hex ? 2 : 1);
      uint32_t code = 0;
      bool ok = !digits.empty();
      for (char c : digits) {
        int d = -1;
        if (c >= '0' && c <= '9')
          d = c - '0';
        else if (hex && c >= 'a' && c <= 'f')
          d = c - 'a' + 10;
        else if (hex && c >= 'A' && c <= 'F')
          d = c - 'A' + 10;
        if (d < 0 || code > 0x10FFFF) {
          ok = false;
          break;
        }
        code = code * (hex ? 16 : 10) + static_cast<uint32_t>(d);
      }
      if (ok && is_xml_char(code)) {
        append_utf8(out, code);
        return semi;
      }
      fail(i, "character reference '&" + shown(ref) + ";' names no character XML allows");
    }
    fail(i, "unknown entity '&" + shown(ref) +
                ";' (XML predefines only &lt; &gt; &amp; &quot; "
                "&apos;)");
  }

  std::size_t end_tag(std::size_t i) {
    const std::size_t name_begin = i + 2, name_stop = name_end(name_begin);
    const std::string_view name = t_.substr(name_begin, name_stop - name_begin);
    const std::size_t k = skip_space(name_stop);
    if (name.empty() || k >= t_.size() || t_[k] != '>') fail(i, "malformed end tag");
    if (stack_.empty()) fail(i, "end tag </" + shown(name) + "> closes no element");
    const XmlElement& open = outline_.elements[static_cast<std::size_t>(stack_.back())];
    if (name != open.name) {
      fail(i, "end tag </" + shown(name) + "> does not close <" + shown(open.name) + "> (line " +
                  std::to_string(open.line) + ", column " + std::to_string(open.column) + ")");
    }
    stack_.pop_back();
    return k + 1;
  }

  std::string_view t_;
  const std::string& source_;
  XmlOutline outline_;
  std::vector<int> stack_;       // the open elements, innermost last
  std::vector<int> last_child_;  // per element: its last child so far
  std::size_t counted_ = 0;      // newlines are counted up to here
  uint32_t line_ = 1;
  std::size_t line_start_ = 0;
};

}  // namespace

std::string shown(std::string_view s, std::size_t max) {
  std::string out;
  for (std::size_t i = 0; i < s.size() && i < max; ++i) {
    const auto u = static_cast<unsigned char>(s[i]);
    if (u >= 0x20 && u < 0x7F) {
      out += s[i];
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 0xF];
    }
  }
  if (s.size() > max) out += "...";
  return out;
}

XmlOutline scan_xml(std::string_view text, const std::string& source) {
  return Scanner(text, source).run();
}

}  // namespace mospec::description
