#include "plot/log_info.hpp"

#include "plot/figure.hpp"

namespace mospec::plot {

std::string unit_symbol(std::string_view qudt) {
  static const std::map<std::string_view, std::string_view> kSymbols = {
      {"M", "m"},
      {"MilliM", "mm"},
      {"RAD", "rad"},
      {"DEG", "°"},
      {"N", "N"},
      {"N-M", "N·m"},
      {"M-PER-SEC", "m/s"},
      {"RAD-PER-SEC", "rad/s"},
      {"SEC", "s"},
      {"KiloGM", "kg"},
      {"M-PER-SEC2", "m/s²"},
      {"RAD-PER-SEC2", "rad/s²"},
      {"UNITLESS", "1"},
      {"NUM", "1"},
      {"N-PER-M", "N/m"},
      {"N-SEC-PER-M", "N·s/m"},
      {"N-M-PER-RAD", "N·m/rad"},
      {"N-M2-PER-SEC2", "N·m²/s²"},
      {"KiloGM-M2", "kg·m²"},
  };
  const auto it = kSymbols.find(qudt);
  return it == kSymbols.end() ? std::string(qudt) : std::string(it->second);
}

std::string column_unit(const LogInfo& info, const std::string& column) {
  if (const auto it = info.units.find(column); it != info.units.end())
    return unit_symbol(it->second);
  return unit_of(column);
}

}  // namespace mospec::plot
