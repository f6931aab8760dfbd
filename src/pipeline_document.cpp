#include "ftsense/pipeline_document.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <utility>

namespace ftsense {

// ---------------------------------------------------------------------------------------------
// The table

std::string_view to_string(DocumentValue value) noexcept {
  switch (value) {
    case DocumentValue::number: return "number";
    case DocumentValue::boolean: return "boolean";
    case DocumentValue::text: return "string";
    case DocumentValue::object: return "object";
    case DocumentValue::array: return "array";
    case DocumentValue::text_list: return "array of strings";
    case DocumentValue::wire: return "wire";
    case DocumentValue::wires: return "object of wires";
    case DocumentValue::range: return "[min, max]";
    case DocumentValue::numbers: return "number or array of numbers";
  }
  return "?";
}

bool has_type(const Json& value, DocumentValue type) noexcept {
  switch (type) {
    case DocumentValue::number: return value.is_number();
    case DocumentValue::boolean: return value.is_boolean();
    case DocumentValue::text: return value.is_string();
    case DocumentValue::object:
    case DocumentValue::wires: return value.is_object();
    case DocumentValue::array: return value.is_array();
    case DocumentValue::text_list:
      return value.is_array() && std::all_of(value.begin(), value.end(), [](const Json& v) { return v.is_string(); });
    case DocumentValue::range:
      return value.is_array() && value.size() == 2 && value[0].is_number() && value[1].is_number();
    case DocumentValue::numbers:
      return value.is_number() ||
             (value.is_array() && std::all_of(value.begin(), value.end(), [](const Json& v) { return v.is_number(); }));
    case DocumentValue::wire:
      return value.is_string() ||
             (value.is_array() && !value.empty() &&
              std::all_of(value.begin(), value.end(), [](const Json& v) { return v.is_string(); }));
  }
  return false;
}

const DocumentKey& DocumentSection::at(std::string_view key) const {
  for (const DocumentKey& k : keys) {
    if (k.key == key) return k;
  }
  FTSENSE_DEMAND(false, "key not described in section '" + path + "': " + std::string(key));
}

std::vector<std::string> DocumentSection::key_names() const {
  std::vector<std::string> names;
  for (const DocumentKey& k : keys) names.push_back(k.key);
  return names;
}

namespace {

std::vector<DocumentSection> make_sections() {
  using V = DocumentValue;
  const DocumentKey description{"description", V::text, false, "", "", "free text"};
  std::vector<DocumentSection> sections;
  sections.push_back(
      {"", "the pipeline config", "",
       {{"sample_period_s", V::number, true, "", "> 0", "tick period T of the pipeline, s",
         PlausibleRange{1e-5, 1.0, "control loops tick at 1 Hz to 100 kHz"}},
        {"inputs", V::object, true, "", "non-empty", "the signals the pipeline reads each tick, by name"},
        {"stages", V::array, true, "", "", "the processing stages, run in dependency order"},
        {"monitor", V::object, false, "", "", "the monitored channels written by `ftsense run`"},
        {"time", V::object, false, "{\"column\": \"time_s\", \"unit\": \"s\"}", "",
         "the log's time column (see `time` below)"},
        {"allow_dependent_virtual_sensor", V::boolean, false, "false", "",
         "accept a virtual sensor computed from the sensor it judges (a warning instead of an error)"},
        {"previous_tick", V::object, false, "", "",
         "signals read one tick late, by name, as `previous_tick.<name>`: how a stage reads what a later stage "
         "computes (recovered values fed back into the virtual sensors, say); see `previous_tick` below"},
        description,
        {"definitions", V::object, false, "", "",
         "values written once and used in several places as {\"$ref\": \"#/definitions/<name>\"} (a sole "
         "outline both feet share, say); see include/ftsense/config_definitions.hpp"},
        {"$schema", V::text, false, "", "",
         "the JSON Schema an editor checks the file with (docs/ftsense-config.schema.json); ftsense ignores it"}}});
  sections.push_back(
      {"inputs/<name>", "an input",
       "`<name>` is an identifier (letters, digits, `_`). Stages refer to it as `input.<name>`.",
       {{"columns", V::text_list, true, "", "non-empty", "log column names, one per value"},
        {"unit", V::text, true, "", "non-empty", "SI unit of the values, \"1\" if dimensionless"},
        {"derived_from", V::text_list, false, "", "input names",
         "inputs this one is computed from (for the independence rule, e.g. a logged ZMP computed from "
         "the force sensors)"},
        {"plausible_range", V::range, false, "", "min < max, in `unit`",
         "what the quantity can physically be (a foot force between -0.5 m g and 3 m g, say): a value outside "
         "is read as missing (NaN), so a burst, a stuck-at-full-scale IMU or an absurd position makes the "
         "stages that use it not ready instead of feeding them"},
        {"scale", V::numbers, false, "1", "finite, not 0; one number, or one per column",
         "value = scale * logged + offset: raw counts, millivolts or another unit to `unit` (the range "
         "applies after)"},
        {"offset", V::numbers, false, "0", "finite; one number, or one per column",
         "value = scale * logged + offset, in `unit`"},
        description}});
  sections.push_back(
      {"stages/<i>", "a stage", "",
       {{"name", V::text, true, "", "unique identifier, not `input` or `previous_tick`", "the stage's unique name"},
        {"plugin", V::text, true, "", "", "the plugin that runs the stage; `ftsense plugins` lists them"},
        {"params", V::object, false, "{}", "", "the plugin's parameters"},
        {"inputs", V::wires, false, "", "one wire per input port of the plugin",
         "input port to wire: `\"input.<name>\"`, `\"<stage>.<port>\"` or `\"previous_tick.<name>\"` (a later "
         "stage's signal, one tick late), any with a selection of its values "
         "(`\"imu.acc[2]\"`, `\"input.pos[0:2]\"`: 0-based, end excluded), or an array of them (concatenated)"},
        description}});
  DocumentSection monitor{"monitor", "the monitor",
                          "Every monitored channel `<channel>` gets one output column per wire below; "
                          "`<unit>` is the unit of the measured signal.",
                          {{"channels", V::text_list, true, "", "non-empty, unique",
                            "names of the monitored channels, used as column prefixes"}}};
  for (const MonitorColumnInfo& column : kMonitorColumns) {
    monitor.keys.push_back({std::string(column.key), V::wire, column.required, "", "one value per channel",
                            std::string(column.meaning) + ", written as `" +
                                monitor_column_name("<channel>", column, "<unit>") + "`"});
  }
  monitor.keys.push_back({"extra", V::wires, false, "", "",
                          "name to wire of further per-channel signals, written as `" +
                              extra_column_name("<channel>", "<name>", "<unit>") +
                              "` (no suffix when dimensionless)"});
  sections.push_back(std::move(monitor));
  sections.push_back(
      {"time", "the time column",
       "The log's first column is its time; `ftsense run` and `calibrate` read it in seconds. "
       "PlotJuggler writes `__time` in seconds; loggers often write nanoseconds.",
       {{"column", V::text, false, "\"time_s\"", "non-empty", "name of the log's first column"},
        {"unit", V::text, false, "\"s\"", "one of: s, ms, us, ns", "unit of the time stamps"}}});
  sections.push_back(
      {"previous_tick/<name>", "a previous-tick signal",
       "`<name>` is an identifier. Wires read it as `previous_tick.<name>`: what `signal` held at the end of the "
       "tick before (`initial` before the first tick). A stage cannot read a later stage's output on the same "
       "tick (that would be a cycle); it can read it one tick late, so a feedback loop has a delay by "
       "construction. Its size and unit are declared because the stages that read it are built before the "
       "one that computes it; the build checks them against `signal`.",
       {{"signal", V::text, true, "", "\"<stage>.<port>\" or \"input.<name>\", optionally with a selection",
         "the signal to read one tick late"},
        {"dim", V::number, true, "", "whole number >= 1", "how many values it carries"},
        {"unit", V::text, true, "", "non-empty", "its unit, as the signal's (\"1\" if dimensionless)"},
        {"initial", V::number, false, "0", "finite", "its value before the first tick and after a reset"},
        description}});
  return sections;
}

}  // namespace

const std::vector<DocumentSection>& pipeline_document_sections() {
  static const std::vector<DocumentSection> sections = make_sections();
  return sections;
}

const DocumentSection& document_section(DocumentSectionId id) {
  return pipeline_document_sections()[static_cast<std::size_t>(id)];
}

bool is_identifier(std::string_view s) noexcept {
  if (s.empty()) return false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
    const bool digit = c >= '0' && c <= '9';
    if (!(letter || (digit && i > 0))) return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// The reader

namespace {

void type_error(const Json& value, const std::string& path, std::string_view expected, std::string_view what,
                Diagnostics& diag) {
  diag.error(path, " = " + detail::abbreviated_dump(value) + " has type " + value.type_name() + ", expected " +
                       std::string(expected) + " (" + std::string(what) + ")");
}

class DocumentReader {
 public:
  DocumentReader(const Json& config, Diagnostics& diag) : cfg_(config), diag_(diag) {}

  PipelineDocument read() {
    if (!cfg_.is_object()) {
      type_error(cfg_, "", "object", "a pipeline config", diag_);
      return std::move(doc_);
    }
    const DocumentSection& section = document_section(DocumentSectionId::pipeline);
    check_keys(cfg_, "", section);
    if (const Json* t = field(cfg_, "", section, "sample_period_s")) {
      if (!(t->get<double>() > 0.0)) {
        diag_.error("/sample_period_s", " = " + t->dump() + " violates > 0 (tick period T, s)");
      } else {
        doc_.sample_period_s = t->get<double>();
        const DocumentKey& k = section.at("sample_period_s");
        if (k.plausible) check_plausible(*k.plausible, "s", *doc_.sample_period_s, *t, "/sample_period_s", diag_);
      }
    }
    if (const Json* time = field(cfg_, "", section, "time")) read_time(*time);
    if (const Json* a = field(cfg_, "", section, "allow_dependent_virtual_sensor")) {
      doc_.allow_dependent_virtual_sensor = a->get<bool>();
    }
    (void)field(cfg_, "", section, "description");
    (void)field(cfg_, "", section, "$schema");
    if (const Json* inputs = field(cfg_, "", section, "inputs")) read_inputs(*inputs);
    const Json* previous = field(cfg_, "", section, "previous_tick");
    if (previous != nullptr) {
      // Names first, so that stage wires may read them; their signals once stages are named.
      for (const auto& [name, spec] : previous->items()) declared_previous_.push_back(name);
    }
    if (const Json* stages = field(cfg_, "", section, "stages")) read_stages(*stages);
    if (previous != nullptr) read_previous_tick(*previous);
    if (const Json* monitor = field(cfg_, "", section, "monitor")) read_monitor(*monitor);
    return std::move(doc_);
  }

 private:
  // Reports keys of `object` that `section` does not describe.
  void check_keys(const Json& object, const std::string& path, const DocumentSection& section) {
    const std::vector<std::string> known = section.key_names();
    for (const auto& [key, value] : object.items()) {
      if (std::find(known.begin(), known.end(), key) == known.end()) {
        diag_.error(json_pointer_append(path, key), "unknown key in " + section.what + "; " + suggest(key, known));
      }
    }
  }

  // The value of described key `key` in `object` when it is present with its type; reports a
  // missing required key and a wrong type.
  const Json* field(const Json& object, const std::string& path, const DocumentSection& section,
                    std::string_view key) {
    const DocumentKey& k = section.at(key);
    const std::string key_path = json_pointer_append(path, k.key);
    const auto it = object.find(k.key);
    if (it == object.end()) {
      if (k.required) diag_.error(key_path, "missing required key (" + k.meaning + ")");
      return nullptr;
    }
    if (k.type == DocumentValue::text_list && it->is_array()) {
      // Name the element that is not a string.
      for (std::size_t i = 0; i < it->size(); ++i) {
        if (!(*it)[i].is_string()) {
          type_error((*it)[i], json_pointer_append(key_path, i), "string", k.meaning, diag_);
          return nullptr;
        }
      }
    }
    if (!has_type(*it, k.type)) {
      type_error(*it, key_path, to_string(k.type), k.meaning, diag_);
      return nullptr;
    }
    return &*it;
  }

  void read_inputs(const Json& inputs) {
    if (inputs.empty()) {
      diag_.error("/inputs", "is empty; declare at least one input signal");
      return;
    }
    const DocumentSection& section = document_section(DocumentSectionId::input);
    for (const auto& [name, spec] : inputs.items()) {
      const std::string path = json_pointer_append("/inputs", name);
      if (!is_identifier(name)) {
        diag_.error(path, "input name '" + name + "' must be an identifier (letters, digits, _)");
        continue;
      }
      declared_inputs_.push_back(name);  // wires may name it even when its declaration is broken
      if (!spec.is_object()) {
        type_error(spec, path, "object", "an input signal", diag_);
        continue;
      }
      check_keys(spec, path, section);
      InputDecl input;
      input.name = name;
      bool ok = true;
      if (const Json* columns = field(spec, path, section, "columns")) {
        if (columns->empty()) {
          diag_.error(path + "/columns", "is empty; list at least one log column");
          ok = false;
        }
        for (std::size_t i = 0; i < columns->size(); ++i) {
          const std::string& c = (*columns)[i].get_ref<const std::string&>();
          if (c.empty()) {
            diag_.error(json_pointer_append(path + "/columns", i), "is empty; name the log column");
            ok = false;
          }
          input.columns.push_back(c);
        }
      } else {
        ok = false;
      }
      ok = read_unit(spec, path, section, "the SI unit of the values", input.unit) && ok;
      if (const Json* from = field(spec, path, section, "derived_from")) {
        for (const Json& f : *from) input.derived_from.push_back(f.get<std::string>());
      }
      if (const Json* range = field(spec, path, section, "plausible_range")) {
        const double lo = (*range)[0].get<double>();
        const double hi = (*range)[1].get<double>();
        if (!(lo < hi)) {
          diag_.error(path + "/plausible_range", " = " + range->dump() + " violates min < max");
          ok = false;
        } else {
          input.plausible_range = std::array<double, 2>{lo, hi};
        }
      }
      ok = read_coefficients(spec, path, section, "scale", 1.0, input.columns.size(), input.scale) && ok;
      ok = read_coefficients(spec, path, section, "offset", 0.0, input.columns.size(), input.offset) && ok;
      (void)field(spec, path, section, "description");
      if (ok) doc_.inputs.push_back(std::move(input));
    }
    std::vector<std::string> names;
    for (const auto& in : doc_.inputs) names.push_back(in.name);
    for (const auto& in : doc_.inputs) {
      for (std::size_t i = 0; i < in.derived_from.size(); ++i) {
        const std::string& f = in.derived_from[i];
        if (std::find(names.begin(), names.end(), f) == names.end()) {
          diag_.error(json_pointer_append(json_pointer_append("/inputs", in.name) + "/derived_from", i),
                      "unknown input '" + f + "'; " + suggest(f, names));
        }
      }
    }
  }

  // The required, non-empty "unit" of an input or a previous-tick signal; false when reported.
  bool read_unit(const Json& spec, const std::string& path, const DocumentSection& section, std::string_view what,
                 std::string& unit) {
    const Json* value = field(spec, path, section, "unit");
    if (value == nullptr) return false;
    unit = value->get<std::string>();
    if (unit.empty()) {
      diag_.error(path + "/unit", "is empty; give " + std::string(what) + ", \"1\" if dimensionless");
      return false;
    }
    return true;
  }

  void read_previous_tick(const Json& previous) {
    const DocumentSection& section = document_section(DocumentSectionId::previous_tick);
    for (const auto& [name, spec] : previous.items()) {
      const std::string path = json_pointer_append("/previous_tick", name);
      if (!is_identifier(name)) {
        diag_.error(path, "previous-tick signal name '" + name + "' must be an identifier (letters, digits, _)");
        continue;
      }
      if (!spec.is_object()) {
        type_error(spec, path, "object", "a previous-tick signal", diag_);
        continue;
      }
      check_keys(spec, path, section);
      PreviousTickDecl d;
      d.name = name;
      d.path = path;
      bool ok = true;
      if (const Json* signal = field(spec, path, section, "signal")) {
        WireDecl w;
        w.port = name;
        w.path = path + "/signal";
        if (!read_wire(*signal, w)) {
          ok = false;
        } else if (w.ends.front().from_previous_tick) {
          diag_.error(w.path, " = " + signal->dump() + " reads a previous-tick signal; name the signal it delays "
                                                      "itself (a delay of two ticks is not offered)");
          ok = false;
        } else {
          d.signal = std::move(w.ends.front());
        }
      } else {
        ok = false;
      }
      if (const Json* dim = field(spec, path, section, "dim")) {
        const double n = dim->get<double>();
        if (!(n >= 1.0 && n <= 1e6 && n == std::floor(n))) {
          diag_.error(path + "/dim", " = " + dim->dump() + " violates whole number >= 1 (how many values it carries)");
          ok = false;
        } else {
          d.dim = static_cast<std::size_t>(n);
        }
      } else {
        ok = false;
      }
      ok = read_unit(spec, path, section, "the signal's unit", d.unit) && ok;
      if (const Json* initial = field(spec, path, section, "initial")) {
        d.initial = initial->get<double>();
        if (!std::isfinite(d.initial)) {
          diag_.error(path + "/initial", " = " + initial->dump() + " is not finite");
          ok = false;
        }
      }
      (void)field(spec, path, section, "description");
      if (ok) doc_.previous_tick.push_back(std::move(d));
    }
  }

  void read_time(const Json& time) {
    const DocumentSection& section = document_section(DocumentSectionId::time);
    check_keys(time, "/time", section);
    if (const Json* column = field(time, "/time", section, "column")) {
      if (column->get<std::string>().empty()) {
        diag_.error("/time/column", "is empty; name the log's time column (its first column)");
      } else {
        doc_.time.column = column->get<std::string>();
      }
    }
    if (const Json* unit = field(time, "/time", section, "unit")) {
      const std::string u = unit->get<std::string>();
      const auto it = std::find_if(kTimeUnits.begin(), kTimeUnits.end(), [&u](const auto& k) { return k.first == u; });
      if (it == kTimeUnits.end()) {
        diag_.error("/time/unit", " = \"" + u + "\" is not one of s, ms, us, ns");
      } else {
        doc_.time.unit = u;
        doc_.time.seconds_per_unit = it->second;
      }
    }
  }

  // scale or offset of an input: absent (the default for every column), one number for every
  // column, or one per column. Returns false when it reported a problem.
  bool read_coefficients(const Json& spec, const std::string& path, const DocumentSection& section,
                         std::string_view key, double fallback, std::size_t columns, std::vector<double>& out) {
    out.assign(columns, fallback);
    const Json* value = field(spec, path, section, key);
    if (value == nullptr) return !spec.contains(std::string(key));
    const std::string key_path = json_pointer_append(path, key);
    if (value->is_array() && value->size() != columns) {
      diag_.error(key_path, "has " + std::to_string(value->size()) + " numbers for " + std::to_string(columns) +
                                " columns; give one number, or one per column");
      return false;
    }
    bool ok = true;
    for (std::size_t i = 0; i < columns; ++i) {
      const Json& v = value->is_array() ? (*value)[i] : *value;
      const double x = v.get<double>();
      const bool zero_scale = key == "scale" && x == 0.0;
      if (!std::isfinite(x) || zero_scale) {
        diag_.error(value->is_array() ? json_pointer_append(key_path, i) : key_path,
                    " = " + v.dump() + (zero_scale ? " would erase the signal; scale must not be 0" : " is not finite"));
        ok = false;
      } else {
        out[i] = x;
      }
    }
    return ok;
  }

  void read_stages(const Json& stages) {
    // Names first, so that wires may name stages declared later.
    for (std::size_t i = 0; i < stages.size(); ++i) {
      StageDecl d;
      d.path = json_pointer_append("/stages", i);
      const Json& s = stages[i];
      if (s.is_object()) {
        if (const auto n = s.find("name"); n != s.end() && n->is_string()) d.name = n->get<std::string>();
      }
      stage_names_.push_back(d.name);
      doc_.stages.push_back(std::move(d));
    }
    for (std::size_t i = 0; i < stages.size(); ++i) read_stage(stages[i], i);
  }

  void read_stage(const Json& s, std::size_t index) {
    StageDecl& d = doc_.stages[index];
    if (!s.is_object()) {
      type_error(s, d.path, "object", "a stage", diag_);
      d.ok = false;
      return;
    }
    const DocumentSection& section = document_section(DocumentSectionId::stage);
    check_keys(s, d.path, section);
    if (const Json* name = field(s, d.path, section, "name")) {
      if (!is_identifier(d.name) || d.name == "input" || d.name == "previous_tick") {
        diag_.error(d.path + "/name",
                    " = " + name->dump() + " violates identifier (letters, digits, _; not 'input' or 'previous_tick')");
        d.ok = false;
      }
      for (std::size_t j = 0; j < index; ++j) {
        if (doc_.stages[j].name == d.name) {
          diag_.error(d.path + "/name", "duplicate stage name '" + d.name + "' (also " + doc_.stages[j].path +
                                            "); stage names must be unique");
          d.ok = false;
        }
      }
    } else {
      d.ok = false;
    }
    if (const Json* plugin = field(s, d.path, section, "plugin")) {
      d.plugin = plugin->get<std::string>();
    } else {
      d.ok = false;
    }
    // A params value of the wrong type is the plugin's to report (it names the plugin).
    if (const auto p = s.find("params"); p != s.end()) d.params = *p;
    (void)field(s, d.path, section, "description");
    const Json* inputs = field(s, d.path, section, "inputs");
    if (inputs == nullptr) {
      if (s.contains("inputs")) d.ok = false;
      return;
    }
    for (const auto& [port, value] : inputs->items()) {
      WireDecl w;
      w.port = port;
      w.path = json_pointer_append(d.path + "/inputs", port);
      if (!read_wire(value, w)) {
        d.ok = false;
        continue;
      }
      for (const auto& e : w.ends) {
        // A previous-tick signal is no dependency within the tick: it was written on the one before.
        if (!e.from_input && !e.from_previous_tick) d.upstream.push_back(e.producer);
      }
      d.wires.push_back(std::move(w));
    }
    std::sort(d.upstream.begin(), d.upstream.end());
    d.upstream.erase(std::unique(d.upstream.begin(), d.upstream.end()), d.upstream.end());
  }

  // "[i]" or "[i:j]" with 0 <= i < j as [i, i + 1) or [i, j); nullopt when it is neither.
  static std::optional<std::array<std::size_t, 2>> parse_selection(std::string_view s) {
    if (s.size() < 3 || s.front() != '[' || s.back() != ']') return std::nullopt;
    s = s.substr(1, s.size() - 2);
    const auto number = [](std::string_view digits) -> std::optional<std::size_t> {
      std::size_t v = 0;
      if (digits.empty() || digits.size() > 6) return std::nullopt;
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
      if (ec != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
      return v;
    };
    const auto colon = s.find(':');
    const auto first = number(s.substr(0, colon));
    if (!first) return std::nullopt;
    if (colon == std::string_view::npos) return std::array<std::size_t, 2>{*first, *first + 1};
    const auto last = number(s.substr(colon + 1));
    if (!last || !(*first < *last)) return std::nullopt;
    return std::array<std::size_t, 2>{*first, *last};
  }

  // Parses a wire value, "node.port" or an array of them, and resolves its names.
  bool read_wire(const Json& value, WireDecl& w) {
    std::vector<std::pair<std::string, std::string>> texts;  // text, path
    if (value.is_string()) {
      texts.emplace_back(value.get<std::string>(), w.path);
    } else if (value.is_array() && !value.empty()) {
      for (std::size_t i = 0; i < value.size(); ++i) {
        if (!value[i].is_string()) {
          type_error(value[i], json_pointer_append(w.path, i), "string", "\"input.<name>\", \"<stage>.<port>\" or \"previous_tick.<name>\"",
                     diag_);
          return false;
        }
        texts.emplace_back(value[i].get<std::string>(), json_pointer_append(w.path, i));
      }
    } else {
      type_error(value, w.path, "string or non-empty array of strings", "\"input.<name>\", \"<stage>.<port>\" or \"previous_tick.<name>\"",
                 diag_);
      return false;
    }
    bool ok = true;
    for (auto& [text, path] : texts) {
      WireEnd e;
      e.text = text;
      e.path = path;
      e.signal = text;
      if (const auto bracket = text.find('['); bracket != std::string::npos) {
        e.signal = text.substr(0, bracket);
        e.select = parse_selection(std::string_view(text).substr(bracket));
        if (!e.select) {
          diag_.error(path, " = \"" + text + "\" has a selection that is not \"[i]\" or \"[i:j]\" with 0 <= i < j "
                            "(0-based, j excluded): \"" + e.signal + "[2]\" is the third value");
          ok = false;
          continue;
        }
      }
      const auto dot = e.signal.find('.');
      if (dot == std::string::npos) {
        diag_.error(path, " = \"" + text + "\" violates the wire form \"input.<name>\", \"<stage>.<port>\" or "
                          "\"previous_tick.<name>\"");
        ok = false;
        continue;
      }
      e.node = e.signal.substr(0, dot);
      e.port = e.signal.substr(dot + 1);
      if (e.node == "input") {
        e.from_input = true;
        if (std::find(declared_inputs_.begin(), declared_inputs_.end(), e.port) == declared_inputs_.end()) {
          diag_.error(path, "no input named '" + e.port + "'; " + suggest(e.port, declared_inputs_));
          ok = false;
          continue;
        }
      } else if (e.node == "previous_tick") {
        e.from_previous_tick = true;
        const auto found = std::find(declared_previous_.begin(), declared_previous_.end(), e.port);
        if (found == declared_previous_.end()) {
          diag_.error(path, "no previous-tick signal named '" + e.port + "'; " +
                                (declared_previous_.empty() ? std::string("declare it under \"previous_tick\"")
                                                            : suggest(e.port, declared_previous_)));
          ok = false;
          continue;
        }
      } else {
        const auto found = std::find(stage_names_.begin(), stage_names_.end(), e.node);
        if (found == stage_names_.end()) {
          diag_.error(path, "no stage named '" + e.node + "' (wire \"" + text + "\"); " + suggest(e.node, stage_names_));
          ok = false;
          continue;
        }
        e.producer = static_cast<std::size_t>(found - stage_names_.begin());
      }
      w.ends.push_back(std::move(e));
    }
    return ok;
  }

  void read_monitor(const Json& monitor) {
    const std::string path = "/monitor";
    const DocumentSection& section = document_section(DocumentSectionId::monitor);
    check_keys(monitor, path, section);
    MonitorDecl& m = doc_.monitor.emplace();
    if (const Json* channels = field(monitor, path, section, "channels")) {
      if (channels->empty()) {
        diag_.error(path + "/channels", "is empty; name at least one channel");
        m.ok = false;
      }
      for (std::size_t i = 0; i < channels->size(); ++i) {
        const std::string& c = (*channels)[i].get_ref<const std::string&>();
        const std::string item = json_pointer_append(path + "/channels", i);
        if (c.empty()) {
          diag_.error(item, "is empty; name the channel (it prefixes its output columns)");
          m.ok = false;
        } else if (const std::string problem = column_name_problem(c); !problem.empty()) {
          diag_.error(item, " = " + (*channels)[i].dump() + " " + problem +
                                "; the channel prefixes its output columns, so use letters, digits, _, / or -");
          m.ok = false;
        } else if (std::find(m.channels.begin(), m.channels.end(), c) != m.channels.end()) {
          diag_.error(item, "duplicate channel name " + (*channels)[i].dump());
          m.ok = false;
        } else {
          m.channels.push_back(c);
        }
      }
    } else {
      m.ok = false;
    }
    for (const MonitorColumnInfo& column : kMonitorColumns) {
      WireDecl w;
      w.port = std::string(column.key);
      w.path = path + "/" + w.port;
      const auto value = monitor.find(w.port);
      if (value == monitor.end()) {
        if (!column.required) continue;  // derived by the pipeline
        diag_.error(w.path, "missing required key (the signal written as " +
                                monitor_column_name("<channel>", column, "<unit>") + ")");
        m.ok = false;
        continue;
      }
      if (!read_wire(*value, w)) {
        m.ok = false;
        continue;
      }
      m.columns[static_cast<std::size_t>(column.column)] = std::move(w);
    }
    if (const Json* extra = field(monitor, path, section, "extra")) {
      for (const auto& [name, value] : extra->items()) {
        WireDecl w;
        w.port = name;
        w.path = json_pointer_append(path + "/extra", name);
        if (!is_identifier(name)) {
          diag_.error(w.path, "extra signal name '" + name + "' must be an identifier (letters, digits, _)");
          m.ok = false;
          continue;
        }
        if (!read_wire(value, w)) {
          m.ok = false;
          continue;
        }
        m.extra.push_back(std::move(w));
      }
    } else if (monitor.contains("extra")) {
      m.ok = false;
    }
  }

  const Json& cfg_;
  Diagnostics& diag_;
  PipelineDocument doc_;
  std::vector<std::string> declared_inputs_;
  std::vector<std::string> stage_names_;
  std::vector<std::string> declared_previous_;  // previous_tick names, as declared (broken ones too)
};

}  // namespace

PipelineDocument read_pipeline_document(const Json& config, Diagnostics& diag) {
  return DocumentReader(config, diag).read();
}

}  // namespace ftsense
