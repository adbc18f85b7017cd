// What the verifier (check(), ir.cpp) gives each step kind's hooks
// (StepKindInfo::signature, verify): the data types a step takes and gives,
// and the findings it adds, each located at the model entity involved.
#pragma once

#include <algorithm>
#include <array>
#include <initializer_list>
#include <string>
#include <vector>

#include "ir/ir.hpp"
#include "support/diagnostics.hpp"

namespace mospec::ir {

// A list of data types, held inline up to 16 (every step kind's ports so far),
// so that checking a step allocates nothing: the verifier runs after every pass.
class Types {
 public:
  Types() = default;
  Types(std::initializer_list<DataType> types) {
    if (types.size() <= inline_.size()) {
      std::copy(types.begin(), types.end(), inline_.begin());
      size_ = types.size();
    } else {
      for (DataType t : types) push_back(t);
    }
  }
  Types(size_t n, DataType t) {
    if (n <= inline_.size()) {
      std::fill_n(inline_.begin(), n, t);
      size_ = n;
    } else {
      for (size_t k = 0; k < n; ++k) push_back(t);
    }
  }
  void push_back(DataType t) {
    if (size_ < inline_.size()) {
      inline_[size_] = t;
    } else {
      if (overflow_.empty()) overflow_.assign(inline_.begin(), inline_.end());
      overflow_.push_back(t);
    }
    ++size_;
  }
  size_t size() const { return size_; }
  DataType operator[](size_t k) const {
    return size_ <= inline_.size() ? inline_[k] : overflow_[k];
  }

 private:
  std::array<DataType, 16> inline_{};
  std::vector<DataType> overflow_;  // all of them, once there are more than 16
  size_t size_ = 0;
};

// The data types each step kind takes and gives (expected), or why the step
// has none (`problem`). Variadic kinds check their inputs themselves.
struct Signature {
  Signature(Types i, Types o, bool variadic = false, std::string why = {})
      : in(std::move(i)),
        out(std::move(o)),
        variadic_in(variadic),
        variadic_out(variadic),
        problem(std::move(why)) {}
  Types in, out;
  bool variadic_in = false, variadic_out = false;  // any number, of any type (checked elsewhere)
  std::string problem;
};

// Collects the verifier's findings, each located at the model entity involved.
class Findings {
 public:
  Findings(const Program& p, const SourceFiles* files)
      : p_(p), files_(files), n_data_(p.data.size()) {}

  void step(const Step& st, const std::string& what) {
    std::string msg = "IR step '";
    msg.append(st.name)
        .append("' (")
        .append(kind_name(st))
        .append(", from '")
        .append(st.iri)
        .append("'): ")
        .append(what);
    add(st.where, std::move(msg));
  }
  void add(const SourceLoc& where, std::string message) {
    Diagnostic d;
    d.code = "ir-invalid";
    d.message = std::move(message);
    if (files_ && where.known()) {
      d.file = files_->path(where.file);
      d.line = where.line;
      d.column = where.column;
    }
    out_.push_back(std::move(d));
  }
  // (The count is kept: size() divides by sizeof(Data), and this runs for
  // every input and output of every step after every pass.)
  bool valid_datum(int d) const { return d >= 0 && static_cast<size_t>(d) < n_data_; }
  std::string describe(int d) const {
    if (!valid_datum(d)) return "datum " + std::to_string(d) + " (which does not exist)";
    const Data& dd = p_.data[static_cast<size_t>(d)];
    return "'" + dd.name + "' (a " + std::string(to_string(dd.type)) + ")";
  }
  std::vector<Diagnostic> take() { return std::move(out_); }

 private:
  const Program& p_;
  const SourceFiles* files_;
  const size_t n_data_;
  std::vector<Diagnostic> out_;
};

}  // namespace mospec::ir
