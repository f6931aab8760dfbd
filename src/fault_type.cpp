#include "ftsense/fault_type.hpp"

namespace ftsense {

std::string fault_type_table_markdown() {
  std::string out = "| code | name | model (x true value, y reading) |\n|---|---|---|\n";
  for (const FaultTypeInfo& row : kFaultTypes) {
    out += "| " + std::to_string(static_cast<int>(row.type)) + " | `" + std::string(row.name) + "` | " +
           std::string(row.model) + " |\n";
  }
  return out;
}

}  // namespace ftsense
