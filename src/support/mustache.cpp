#include "support/mustache.hpp"

#include <cctype>

#include "support/diagnostics.hpp"

namespace mospec::mustache {

void Data::put(std::string_view key, Data value) {
  for (Member& m : members_) {
    if (m.key == key) {
      m.value = std::move(value);
      return;
    }
  }
  if (members_.empty()) members_.reserve(8);  // most objects have a few members
  members_.push_back(Member{std::string(key), std::move(value)});
}

const Data* Data::find(std::string_view key) const {
  for (const Member& m : members_)
    if (m.key == key) return &m.value;
  return nullptr;
}

namespace {

[[noreturn]] void fail(const std::string& message, size_t at) {
  throw Error("codegen-template", message + " at byte " + std::to_string(at));
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// One piece of a parsed template. A section's body is the nodes after it up
// to `end` (the index of its closing node, which renders nothing).
struct Node {
  enum class Type : uint8_t { Text, Newline, Variable, Section, Inverted, Close, Comment };
  Type type;
  std::string_view text;  // Text and Newline: the text; tags: the name
  size_t end = 0;         // Section and Inverted: index of the closing node
};

// Text is cut at every line break ("\r\n" or "\n": one Newline node each), as
// kainjow does, so that rendering can apply its blank-line rule per line.
std::vector<Node> parse(std::string_view in) {
  std::vector<Node> nodes;
  std::vector<size_t> open;  // indices of the sections not closed yet
  size_t text_start = 0, i = 0;
  const auto flush_text = [&](size_t upto) {
    if (upto > text_start)
      nodes.push_back({Node::Type::Text, in.substr(text_start, upto - text_start)});
  };
  while (i < in.size()) {
    if (in[i] == '\n' || (in[i] == '\r' && i + 1 < in.size() && in[i + 1] == '\n')) {
      flush_text(i);
      const size_t n = in[i] == '\n' ? 1 : 2;
      nodes.push_back({Node::Type::Newline, in.substr(i, n)});
      i += n;
      text_start = i;
      continue;
    }
    if (in.compare(i, 2, "{{") != 0) {
      ++i;
      continue;
    }
    flush_text(i);
    const bool triple = i + 2 < in.size() && in[i + 2] == '{';
    const size_t contents = i + (triple ? 3 : 2);
    const size_t close = in.find(triple ? "}}}" : "}}", contents);
    if (close == std::string_view::npos) fail("unclosed tag", i);
    std::string_view tag = trim(in.substr(contents, close - contents));
    Node node{Node::Type::Variable, tag};
    if (!triple && !tag.empty()) {
      const char sigil = tag.front();
      switch (sigil) {
        case '#':
          node.type = Node::Type::Section;
          break;
        case '^':
          node.type = Node::Type::Inverted;
          break;
        case '/':
          node.type = Node::Type::Close;
          break;
        case '&':
          break;
        case '!':
          node.type = Node::Type::Comment;
          break;
        case '>':
          fail("partials are not supported", i);
        case '=':
          fail("set-delimiter tags are not supported", i);
        default:
          break;
      }
      if (sigil == '#' || sigil == '^' || sigil == '/' || sigil == '&' || sigil == '!')
        node.text = trim(tag.substr(1));
    }
    if (node.type != Node::Type::Comment && node.text.find('.') != std::string_view::npos)
      fail("dotted names are not supported", i);
    if (node.type == Node::Type::Close) {
      if (open.empty()) fail("section '" + std::string(node.text) + "' closed but never opened", i);
      Node& section = nodes[open.back()];
      if (section.text != node.text)
        fail("section '" + std::string(section.text) + "' closed as '" + std::string(node.text) +
                 "'",
             i);
      section.end = nodes.size();
      open.pop_back();
    }
    if (node.type == Node::Type::Section || node.type == Node::Type::Inverted)
      open.push_back(nodes.size());
    nodes.push_back(node);
    i = close + (triple ? 3 : 2);
    text_start = i;
  }
  flush_text(in.size());
  if (!open.empty()) fail("section '" + std::string(nodes[open.back()].text) + "' never closed", 0);
  return nodes;
}

class Renderer {
 public:
  explicit Renderer(const std::vector<Node>& nodes) : nodes_(nodes) {}

  std::string run(const Data& root) {
    stack_.push_back(&root);
    walk(0, nodes_.size());
    end_line(nullptr);
    return std::move(out_);
  }

 private:
  const Data* lookup(std::string_view name) const {
    for (size_t k = stack_.size(); k-- > 0;)
      if (const Data* d = stack_[k]->find(name)) return d;
    return nullptr;
  }

  static bool falsy(const Data* d) {
    return d == nullptr || d->kind() == Data::Kind::False ||
           (d->kind() == Data::Kind::List && d->items().empty());
  }

  // A line is written when it ends, unless it held the tag of a section that
  // rendered and is empty or blanks only (then it goes with its line break).
  void end_line(const Node* newline) {
    bool blank = true;
    for (char c : line_)
      if (c != ' ' && c != '\t') {
        blank = false;
        break;
      }
    if (!(section_tag_ && blank)) {
      out_ += line_;
      if (newline != nullptr) out_ += newline->text;
    }
    line_.clear();
    section_tag_ = false;
  }

  // Renders the body [begin, end) of a section once, with `pushed` (if any)
  // innermost.
  void body(size_t begin, size_t end, const Data* pushed) {
    section_tag_ = true;  // the opening tag is on the current line
    if (pushed != nullptr) stack_.push_back(pushed);
    walk(begin, end);
    if (pushed != nullptr) stack_.pop_back();
    section_tag_ = true;  // and the closing tag on the line rendering ended on
  }

  void walk(size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const Node& n = nodes_[i];
      switch (n.type) {
        case Node::Type::Text:
          line_ += n.text;
          break;
        case Node::Type::Newline:
          end_line(&n);
          break;
        case Node::Type::Variable:
          if (const Data* d = lookup(n.text); d != nullptr && d->kind() == Data::Kind::String)
            line_ += d->text();
          break;
        case Node::Type::Section: {
          const Data* d = lookup(n.text);
          if (!falsy(d)) {
            if (d->kind() == Data::Kind::List) {
              for (const Data& item : d->items()) body(i + 1, n.end, &item);
            } else {
              body(i + 1, n.end, d);
            }
          }
          i = n.end;
          break;
        }
        case Node::Type::Inverted: {
          const Data* d = lookup(n.text);
          if (falsy(d)) body(i + 1, n.end, d);
          i = n.end;
          break;
        }
        case Node::Type::Close:
        case Node::Type::Comment:
          break;
      }
    }
  }

  const std::vector<Node>& nodes_;
  std::vector<const Data*> stack_;
  std::string out_;
  std::string line_;          // the current line, not written yet
  bool section_tag_ = false;  // it held the tag of a section that rendered
};

}  // namespace

std::string render(std::string_view text, const Data& data) {
  return Renderer(parse(text)).run(data);
}

}  // namespace mospec::mustache
