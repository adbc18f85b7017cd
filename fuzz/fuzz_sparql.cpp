// libFuzzer target for the SPARQL parser, algebra builder and evaluator.
//
// Any input either parses or is rejected with a QueryError whose code is
// "sparql-syntax" or "unsupported-sparql" and whose message starts with the
// position it names; any other exception or code escapes and is reported.
// Short queries that parse are also evaluated (ASK, so a solution ends the
// search) over a tiny dataset with a pre-bound $this, exercising the join,
// path and expression code, under small Limits: a query that exceeds them ends
// with a "sparql-limit" error, which is an accepted outcome.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "rdf/nquads.hpp"
#include "sparql/query.hpp"

namespace {

const mospec::rdf::Dataset& tiny() {
  static const mospec::rdf::Dataset data = [] {
    mospec::rdf::Dataset d;
    mospec::rdf::read_nquads(
        "<http://e/a> <http://e/p> <http://e/b> .\n"
        "<http://e/b> <http://e/p> <http://e/a> .\n"
        "<http://e/b> <http://e/v> \"1\"^^<http://www.w3.org/2001/XMLSchema#integer> .\n"
        "_:l <http://www.w3.org/1999/02/22-rdf-syntax-ns#first> \"x\"@en .\n"
        "_:l <http://www.w3.org/1999/02/22-rdf-syntax-ns#rest> "
        "<http://www.w3.org/1999/02/22-rdf-syntax-ns#nil> .\n",
        d);
    return d;
  }();
  return data;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const mospec::sparql::PrefixMap prefixes{{"e", "http://e/"}};
  try {
    mospec::sparql::Query q = mospec::sparql::parse_query(text, prefixes);
    // Bounded work: long queries can describe huge joins on purpose.
    if (size > 96) return 0;
    static mospec::sparql::Evaluator eval = [] {
      mospec::sparql::Evaluator e(tiny());
      e.set_limits(mospec::sparql::Limits{1, 10'000'000, 100'000});
      return e;
    }();
    const mospec::sparql::Binding bound[] = {{"this", tiny().terms().find_iri("http://e/a")}};
    eval.ask(q, bound);
  } catch (const mospec::sparql::QueryError& e) {
    if (e.code() != "sparql-syntax" && e.code() != "unsupported-sparql") std::abort();
    if (e.line() != 0 && e.diagnostic().message.rfind("line ", 0) != 0) std::abort();
  } catch (const mospec::Error& e) {
    if (e.code() != "sparql-limit") std::abort();
  }
  return 0;
}
