#include "ftsense/config_schema.hpp"

#include <limits>
#include <optional>
#include <string>

#include "ftsense/pipeline_document.hpp"
#include "example_ports_period.hpp"

namespace ftsense {

namespace {

constexpr std::string_view kIdentifierPattern = "^[A-Za-z_][A-Za-z0-9_]*$";

std::string ref(std::string_view definition) { return "#/definitions/" + std::string(definition); }

Json ref_to(std::string_view definition) { return Json{{"$ref", ref(definition)}}; }

// "<meaning>; <rule>; plausible <range>" as editors show it on hover.
std::string key_description(const DocumentKey& k) {
  std::string out = k.meaning;
  if (!k.rule.empty()) out += "; " + k.rule;
  if (k.plausible) out += "; plausible " + k.plausible->text({});
  return out;
}

Json number_list() { return Json{{"type", "array"}, {"items", {{"type", "number"}}}}; }

// The definition of a section: "monitor", "time"; one entry of a map or list: "input", "stage"
// (for "inputs/<name>", "stages/<i>").
std::string definition_name(const DocumentSection& section) {
  const std::size_t slash = section.path.find('/');
  if (slash == std::string::npos) return section.path;
  std::string name = section.path.substr(0, slash);
  if (name.ends_with('s')) name.pop_back();
  return name;
}

// The section that details key `key` of the document root: "monitor", "inputs/<name>", ...
const DocumentSection* detail_section(std::string_view key) {
  for (const DocumentSection& section : pipeline_document_sections()) {
    const std::string& path = section.path;
    if (path == key || path == std::string(key) + "/<name>" || path == std::string(key) + "/<i>") return &section;
  }
  return nullptr;
}

Json value_schema(const DocumentKey& k, std::string_view section_path) {
  using V = DocumentValue;
  Json out;
  switch (k.type) {
    case V::number: out = {{"type", "number"}}; break;
    case V::boolean: out = {{"type", "boolean"}}; break;
    case V::text: out = {{"type", "string"}}; break;
    case V::object: out = {{"type", "object"}}; break;
    case V::array: out = {{"type", "array"}}; break;
    case V::text_list: out = {{"type", "array"}, {"items", {{"type", "string"}}}}; break;
    case V::wire: out = ref_to("wire"); break;
    case V::wires: out = {{"type", "object"}, {"additionalProperties", ref_to("wire")}}; break;
    case V::range: out = number_list(), out["minItems"] = 2, out["maxItems"] = 2; break;
    case V::numbers: out = {{"anyOf", Json::array({{{"type", "number"}}, number_list()})}}; break;
  }
  // A root key a section details refers to that section's definition.
  if (section_path.empty()) {
    if (const DocumentSection* detail = detail_section(k.key)) {
      const std::string name = definition_name(*detail);
      if (detail->path == k.key) {
        out = ref_to(name);
      } else if (k.type == V::object) {
        out["propertyNames"] = {{"pattern", kIdentifierPattern}};
        out["additionalProperties"] = ref_to(name);
      } else {
        out["items"] = ref_to(name);
      }
    }
  }
  if (section_path == "time" && k.key == "unit") {
    Json units = Json::array();
    for (const auto& [unit, seconds] : kTimeUnits) units.push_back(unit);
    out["enum"] = units;
  }
  // Draft-07 ignores the siblings of a $ref: wrap it to keep the description and default.
  if (out.contains("$ref")) out = {{"allOf", Json::array({out})}};
  out["description"] = key_description(k);
  if (!k.default_value.empty()) out["default"] = Json::parse(k.default_value);
  return out;
}

Json section_schema(const DocumentSection& section) {
  Json out{{"type", "object"}, {"additionalProperties", false}};
  if (!section.intro.empty()) out["description"] = section.intro;
  Json properties = Json::object();
  Json required = Json::array();
  for (const DocumentKey& k : section.keys) {
    properties[k.key] = value_schema(k, section.path);
    if (k.required) required.push_back(k.key);
  }
  out["properties"] = properties;
  if (!required.empty()) out["required"] = required;
  return out;
}

// One number (or list entry) of a parameter: its type and bounds.
Json scalar_schema(const ParamInfo& p, std::string_view type) {
  Json out{{"type", type}};
  if (p.lower) out[p.lower->inclusive ? "minimum" : "exclusiveMinimum"] = p.lower->value;
  if (p.upper) out[p.upper->inclusive ? "maximum" : "exclusiveMaximum"] = p.upper->value;
  return out;
}

Json counted_list(const ParamInfo& p, Json items) {
  Json out{{"type", "array"}, {"items", std::move(items)}};
  if (p.min_count > 0) out["minItems"] = p.min_count;
  if (p.max_count != std::numeric_limits<std::size_t>::max()) out["maxItems"] = p.max_count;
  return out;
}

Json param_schema(const ParamInfo& p) {
  Json out;
  switch (p.kind) {
    case ParamKind::number: out = scalar_schema(p, "number"); break;
    case ParamKind::integer: out = scalar_schema(p, "integer"); break;
    case ParamKind::boolean: out = {{"type", "boolean"}}; break;
    case ParamKind::text: out = {{"type", "string"}}; break;
    case ParamKind::choice: out = {{"enum", p.choices}}; break;
    case ParamKind::number_list: out = counted_list(p, scalar_schema(p, "number")); break;
    case ParamKind::text_list: out = counted_list(p, {{"type", "string"}}); break;
    case ParamKind::point_list: {
      Json point{{"type", "array"}, {"items", scalar_schema(p, "number")}, {"minItems", 2}, {"maxItems", 2}};
      out = counted_list(p, std::move(point));
      break;
    }
  }
  std::string description = p.description;
  if (!p.unit.empty()) description += " [" + p.unit + "]";
  if (p.plausible) description += "; plausible " + p.plausible->text(p.unit);
  // The value itself, or a reference to the config's own definitions (config_definitions.hpp):
  // if/then/else rather than anyOf, so that a wrong value is reported where it is wrong (the
  // list element), not at the parameter. No parameter is itself an object.
  Json either{{"if", {{"type", "object"}}},
              {"then", ref_to("definition_reference")},
              {"else", std::move(out)},
              {"description", description}};
  if (!p.required) either["default"] = p.default_value;
  return either;
}

// The params object of one plugin.
Json plugin_params_schema(const PluginInfo& plugin) {
  Json out{{"type", "object"}, {"additionalProperties", false}, {"description", "parameters of " + plugin.name}};
  Json properties = Json::object();
  Json required = Json::array();
  for (const ParamInfo& p : plugin.params) {
    properties[p.key] = param_schema(p);
    if (p.required) required.push_back(p.key);
  }
  out["properties"] = properties;
  if (!required.empty()) out["required"] = required;
  if (!plugin.example_params.empty()) {
    const Json example = Json::parse(plugin.example_params);
    out["examples"] = example.is_array() ? example : Json::array({example});
  }
  return out;
}

// What a stage running `plugin` must satisfy beyond the stage section: its params, and input
// port names among those its examples declare.
Json plugin_stage_rule(const PluginInfo& plugin) {
  Json then{{"properties", {{"params", ref_to("params." + plugin.name)}}}};
  Diagnostics ignored;
  if (const std::optional<Ports> ports = plugin.example_ports ? plugin.example_ports(kExamplePortsSamplePeriodS, ignored)
                                                               : std::nullopt) {
    then["properties"]["inputs"] = {{"propertyNames", {{"enum", ports->input_names()}}}};
  }
  return {{"if", {{"properties", {{"plugin", {{"const", plugin.name}}}}}, {"required", {"plugin"}}}},
          {"then", std::move(then)}};
}

}  // namespace

Json config_json_schema(const PluginRegistry& plugins) {
  Json definitions = Json::object();
  definitions["wire_end"] = {
      {"type", "string"},
      {"pattern", kWireEndPattern},
      {"description", "\"input.<name>\", \"<stage>.<port>\" or \"previous_tick.<name>\", optionally with a "
                      "selection of its values: \"[i]\" or \"[i:j]\" (0-based, j excluded)"}};
  definitions["wire"] = {
      {"description", "a wire end, or a non-empty array of them concatenated in order"},
      {"anyOf", Json::array({ref_to("wire_end"),
                             {{"type", "array"}, {"minItems", 1}, {"items", ref_to("wire_end")}}})}};
  definitions["definition_reference"] = {
      {"type", "object"},
      {"properties", {{"$ref", {{"type", "string"}, {"pattern", "^#/definitions/[^/]+$"}}}}},
      {"required", Json::array({"$ref"})},
      {"additionalProperties", false},
      {"description", "a value of the config's top-level \"definitions\": {\"$ref\": \"#/definitions/<name>\"}"}};
  Json root;
  for (const DocumentSection& section : pipeline_document_sections()) {
    if (section.path.empty()) {
      root = section_schema(section);
      continue;
    }
    definitions[definition_name(section)] = section_schema(section);
  }
  Json& stage = definitions["stage"];
  Json names = Json::array();
  Json rules = Json::array();
  for (const PluginInfo& plugin : plugins.plugins()) {
    names.push_back(plugin.name);
    definitions["params." + plugin.name] = plugin_params_schema(plugin);
    rules.push_back(plugin_stage_rule(plugin));
  }
  stage["properties"]["plugin"]["enum"] = names;
  stage["properties"]["name"]["pattern"] = kIdentifierPattern;
  stage["allOf"] = rules;

  Json schema{{"$schema", kJsonSchemaDraft},
              {"title", "ftsense pipeline config"},
              {"description",
               "Generated by `ftsense plugins --schema` from the descriptions in the code (as "
               "docs/config_reference.md); `make docs` rewrites it. `ftsense check` has the last word."}};
  for (auto& [key, value] : root.items()) schema[key] = value;
  schema["definitions"] = definitions;
  return schema;
}

}  // namespace ftsense
