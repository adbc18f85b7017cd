// Escaping for each context a value can land in on the report page. Every
// byte the page carries from a summary, a log, a model or a path goes through
// exactly one of these, chosen by where it lands; nothing is escaped "just in
// case" twice, so a reviewer can check each call site against its context.
#pragma once

#include <string>
#include <string_view>

namespace mospec::report {

// HTML text or a double-quoted attribute value: & < > " ' as character
// references. Bytes that are not printable ASCII or valid UTF-8 are written
// as U+FFFD, so a control byte or a broken sequence cannot reach the parser.
std::string html_escape(std::string_view text);

// A relative or file: URL path: every byte except the unreserved characters
// (RFC 3986) and '/' percent-encoded, so a path cannot become a
// `javascript:` URL, end the attribute or add a query. Still needs
// html_escape() for the attribute (a no-op on its output, kept for clarity).
std::string url_path_escape(std::string_view path);

// JSON text made safe to inline in a <script> block: '<', '>' and '&' (which
// JSON has only inside strings) become \u003c, \u003e and \u0026, so no byte
// sequence of the data can end the block (`</script`), open a comment that
// swallows the end tag (`<!--` with `<script`), or be read as HTML. Input is
// expected ASCII (JSON dumped with its non-ASCII escaped); other bytes pass.
std::string script_safe_json(std::string_view json);

}  // namespace mospec::report
