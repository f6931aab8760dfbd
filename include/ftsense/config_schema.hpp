#pragma once
// docs/ftsense-config.schema.json: a JSON Schema of the pipeline config for editors, generated
// from the same descriptions as docs/config_reference.md (config_reference.hpp): the document's
// table (pipeline_document.hpp), the wire form, and every plugin's parameters and example ports
// from a plugin registry. A test compares the committed file with this output.
//
// Draft-07: the draft VS Code, the JetBrains IDEs and most validators support fully; the schema
// needs nothing later (per-plugin params by if/then, which draft-07 introduced).
//
// The schema checks structure: keys, types, bounds, choices, list lengths, the wire form and
// each stage's params and input port names by its plugin. What needs the whole document (unique
// stage names, wires naming known stages, dimensions, units, the independence rule) is
// `ftsense check`'s: a config the schema accepts can still fail there, and it should reject no
// config ftsense accepts (a test validates every shipped config against it).

#include <string_view>

#include "ftsense/params.hpp"
#include "ftsense/plugin_registry.hpp"

namespace ftsense {

inline constexpr std::string_view kJsonSchemaDraft = "http://json-schema.org/draft-07/schema#";

[[nodiscard]] Json config_json_schema(const PluginRegistry& plugins);

}  // namespace ftsense
