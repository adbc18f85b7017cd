// The Mustache templates of src/codegen/templates, embedded at build time
// (embed_templates.cmake): file name without ".mustache" -> text.
#pragma once

#include <array>
#include <string_view>

namespace mospec::codegen {

struct Template {
  std::string_view file;  // the generated file's name, e.g. "controller.cpp"
  std::string_view text;
};

inline constexpr std::size_t kTemplateCount = 3;
extern const std::array<Template, kTemplateCount> kTemplates;

}  // namespace mospec::codegen
