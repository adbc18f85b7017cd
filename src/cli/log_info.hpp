// A program's log described for figures and the report page (plot::LogInfo):
// written into a run's summary by `mospec run --summary`, and read back from
// the model by `mospec report` for a summary written without it.
#pragma once

#include <nlohmann/json.hpp>

#include "ir/ir.hpp"
#include "plot/log_info.hpp"

namespace mospec::cli {

// Every log column's unit and every evaluated constraint's relation and
// constant thresholds.
plot::LogInfo log_info(const ir::Program& program);

// As the summary's "log" member: {"units": {column: unit}, "constraints":
// {name: {"relation", "reference"|"lower"|"upper", "tolerance", "guard"}}}.
nlohmann::ordered_json log_info_json(const plot::LogInfo& info);

}  // namespace mospec::cli
