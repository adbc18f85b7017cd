#include "ir/emit.hpp"

namespace mospec::ir {

std::string join_inputs(const EmitContext& ctx, const Step& st, size_t from, size_t to,
                        std::string_view separator) {
  std::string text;
  for (size_t k = from; k < to; ++k) {
    if (!text.empty()) text.append(separator);
    text.append(ctx.in(st, k));
  }
  return text;
}

}  // namespace mospec::ir
