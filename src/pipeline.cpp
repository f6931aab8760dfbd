#include "ftsense/pipeline.hpp"

#include <algorithm>
#include <iterator>
#include <map>
#include <optional>
#include <set>

namespace ftsense {

// ---------------------------------------------------------------------------------------------
// Strict JSON text parsing

namespace {

struct ParseFrame {
  bool is_object = false;
  std::set<std::string> keys;
  std::string key;
  std::size_t next_index = 0;
  [[nodiscard]] std::string token() const {
    return is_object ? json_pointer_token(key) : std::to_string(next_index - 1);
  }
};

std::pair<std::size_t, std::size_t> line_column(std::string_view text, std::size_t byte) {
  std::size_t line = 1;
  std::size_t column = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// Calls `visit(byte)` for every byte of `text` outside string literals, until it returns true;
// returns that byte's index, or npos.
template <class Visit>
std::size_t find_outside_strings(std::string_view text, Visit visit) {
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (visit(i)) {
      return i;
    }
  }
  return std::string_view::npos;
}

bool is_number_char(char c) {
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
}

std::string position(std::string_view text, std::size_t byte, std::string_view source_name) {
  const auto [line, column] = line_column(text, byte);
  return std::string(source_name) + ":" + std::to_string(line) + ":" + std::to_string(column);
}

}  // namespace

Json parse_json_text(std::string_view text, std::string_view source_name) {
  // nlohmann stops at a NUL byte as at the end of the text: whatever follows would be ignored.
  if (const auto nul = text.find('\0'); nul != std::string_view::npos) {
    throw ConfigError(position(text, nul, source_name),
                      "not valid JSON: a NUL byte; is this a text file (or a truncated one)?");
  }
  // Nesting is limited before parsing: JSON values are copied, compared and printed
  // recursively, so a deep enough text ("[[[[...") would overflow the stack.
  std::size_t depth = 0;
  const std::size_t too_deep = find_outside_strings(text, [&](std::size_t i) {
    if (text[i] == '[' || text[i] == '{') return ++depth > kMaxJsonDepth;
    if ((text[i] == ']' || text[i] == '}') && depth > 0) --depth;
    return false;
  });
  if (too_deep != std::string_view::npos) {
    throw ConfigError(position(text, too_deep, source_name),
                      "not valid JSON: nested deeper than " + std::to_string(kMaxJsonDepth) +
                          " arrays or objects; a config needs a handful of levels");
  }
  std::vector<ParseFrame> stack;
  std::vector<Diagnostic> duplicates;
  auto on_element = [&stack] {
    if (!stack.empty() && !stack.back().is_object) ++stack.back().next_index;
  };
  auto callback = [&](int /*depth*/, Json::parse_event_t event, Json& parsed) {
    switch (event) {
      case Json::parse_event_t::object_start:
      case Json::parse_event_t::array_start:
        on_element();
        stack.push_back(ParseFrame{event == Json::parse_event_t::object_start, {}, {}, 0});
        break;
      case Json::parse_event_t::object_end:
      case Json::parse_event_t::array_end:
        if (!stack.empty()) stack.pop_back();
        break;
      case Json::parse_event_t::key: {
        if (stack.empty()) break;
        const std::string key = parsed.get<std::string>();
        ParseFrame& top = stack.back();
        if (!top.keys.insert(key).second) {
          std::string path;
          for (std::size_t i = 0; i + 1 < stack.size(); ++i) {
            path += '/';
            path += stack[i].token();
          }
          duplicates.push_back({path + "/" + json_pointer_token(key),
                                "duplicate key '" + key +
                                    "' (JSON keeps only the last one); remove or rename one"});
        }
        top.key = key;
        break;
      }
      case Json::parse_event_t::value:
        on_element();
        break;
    }
    return true;
  };
  Json document;
  try {
    document = Json::parse(text.begin(), text.end(), callback, /*allow_exceptions=*/true,
                           /*ignore_comments=*/false);
  } catch (const Json::parse_error& e) {
    const auto [line, column] = line_column(text, e.byte == 0 ? 0 : e.byte - 1);
    std::string what = e.what();
    // nlohmann's text: "[json.exception.parse_error.101] parse error at line 1, column 2: ..."
    if (const auto colon = what.find(": "); colon != std::string::npos) what = what.substr(colon + 2);
    throw ConfigError(std::string(source_name) + ":" + std::to_string(line) + ":" +
                          std::to_string(column),
                      "not valid JSON: " + what);
  } catch (const Json::out_of_range& e) {
    // A number beyond the range of a double ("1e400"): nlohmann says "number overflow parsing
    // '1e400'" without a position; the first number token spelled so is the one.
    std::string what = e.what();
    if (const auto colon = what.find("] "); colon != std::string::npos) what = what.substr(colon + 2);
    const auto open = what.find('\'');
    const auto close = what.rfind('\'');
    const std::string token = open < close ? what.substr(open + 1, close - open - 1) : std::string();
    const std::size_t at = find_outside_strings(text, [&](std::size_t i) {
      return !token.empty() && text.substr(i, token.size()) == token && (i == 0 || !is_number_char(text[i - 1])) &&
             (i + token.size() == text.size() || !is_number_char(text[i + token.size()]));
    });
    throw ConfigError(position(text, at == std::string_view::npos ? 0 : at, source_name),
                      "not valid JSON: " + what + " (beyond the range of a double)");
  }
  if (!duplicates.empty()) {
    for (auto& d : duplicates) d.message += " (in " + std::string(source_name) + ")";
    throw ConfigError(std::move(duplicates));
  }
  return document;
}

// ---------------------------------------------------------------------------------------------
// Pipeline

Pipeline::Pipeline() = default;
Pipeline::Pipeline(Pipeline&&) noexcept = default;
Pipeline& Pipeline::operator=(Pipeline&&) noexcept = default;
Pipeline::~Pipeline() = default;

std::span<double> Pipeline::input_values(std::size_t input_index) noexcept {
  const SignalRef ref = inputs_[input_index].values;
  return {values_.data() + ref.offset, ref.dim};
}

std::string_view Pipeline::stage_name(std::size_t run_index) const noexcept {
  return stages_[run_index].name;
}

Stage& Pipeline::stage(std::size_t run_index) noexcept { return *stages_[run_index].stage; }

SignalRef Pipeline::signal(std::string_view reference) const {
  const auto dot = reference.find('.');
  std::vector<std::string> known;
  if (dot != std::string_view::npos) {
    const std::string_view node = reference.substr(0, dot);
    const std::string_view port = reference.substr(dot + 1);
    if (node == "input") {
      for (const auto& in : inputs_) {
        if (in.name == port) return in.values;
      }
    }
    for (const auto& s : stages_) {
      if (s.name != node) continue;
      if (const auto index = s.stage->ports().find_output(port)) return s.output_refs[*index];
    }
  }
  for (const auto& [name, unit] : signal_names()) known.push_back(name);
  throw ConfigError("", "no signal named '" + std::string(reference) + "'; " +
                            suggest(reference, known));
}

std::vector<std::pair<std::string, std::string>> Pipeline::signal_names() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& in : inputs_) out.emplace_back("input." + in.name, in.unit);
  for (const auto& s : stages_) {
    const auto& outputs = s.stage->ports().outputs();
    for (std::size_t o = 0; o < outputs.size(); ++o) out.emplace_back(s.name + "." + outputs[o].name, s.output_units[o]);
  }
  return out;
}

void Pipeline::bind_spans() noexcept {
  for (auto& s : stages_) {
    s.input_spans.clear();
    s.output_spans.clear();
    for (const SignalRef& r : s.input_refs) s.input_spans.emplace_back(values_.data() + r.offset, r.dim);
    for (const SignalRef& r : s.output_refs) s.output_spans.emplace_back(values_.data() + r.offset, r.dim);
    s.io.inputs = s.input_spans;
    s.io.outputs = s.output_spans;
  }
}

void Pipeline::reset() noexcept {
  std::fill(values_.begin(), values_.end(), 0.0);
  for (auto& s : stages_) s.stage->reset();
}

void Pipeline::step_stage(std::size_t run_index, double time_s) noexcept {
  double* const v = values_.data();
  StageRun& s = stages_[run_index];
  for (const Copy& c : s.gathers) std::copy_n(v + c.from, c.count, v + c.to);
  s.io.time_s = time_s;
  s.stage->step(s.io);
}

void Pipeline::step(double time_s) noexcept {
  double* const v = values_.data();
  for (auto& s : stages_) {
    for (const Copy& c : s.gathers) std::copy_n(v + c.from, c.count, v + c.to);
    s.io.time_s = time_s;
    s.stage->step(s.io);
  }
  for (const Copy& c : monitor_gathers_) std::copy_n(v + c.from, c.count, v + c.to);
}

// ---------------------------------------------------------------------------------------------
// Building

namespace {

bool is_identifier(std::string_view s) {
  if (s.empty()) return false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
    const bool digit = c >= '0' && c <= '9';
    if (!(letter || (digit && i > 0))) return false;
  }
  return true;
}

// Reports keys of `object` that are not in `known`.
void check_keys(const Json& object, const std::string& path, const std::vector<std::string>& known,
                std::string_view what, Diagnostics& diag) {
  for (const auto& [key, value] : object.items()) {
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      diag.error(json_pointer_append(path, key),
                 "unknown key in " + std::string(what) + "; " + suggest(key, known));
    }
  }
}

void type_error(const Json& value, const std::string& path, std::string_view expected,
                std::string_view what, Diagnostics& diag) {
  diag.error(path, " = " + detail::abbreviated_dump(value) + " has type " + value.type_name() +
                       ", expected " + std::string(expected) + " (" + std::string(what) + ")");
}

// One element of a wire: "input.<name>" or "<stage>.<port>".
struct WireEnd {
  std::string text;
  std::string node;
  std::string port;
  bool from_input = false;
  std::size_t producer = 0;  // stage declaration index when !from_input
};

struct Wire {
  std::string port;  // the consuming port (stage input or monitor field)
  std::string path;  // JSON Pointer of the wire
  std::vector<WireEnd> ends;
};

struct SignalInfo {
  SignalRef ref;
  std::string unit;
  std::set<std::string> depends_on;  // pipeline input names
  // For leave-one-out outputs: the inputs of the measured signal it leaves channel by channel out.
  std::set<std::string> leave_one_out_of;
};

struct StageDecl {
  std::string name;
  std::string path;
  const PluginInfo* plugin = nullptr;
  Json params = Json::object();
  std::vector<Wire> wires;
  bool declared_ok = true;
  bool built = false;
  std::set<std::size_t> upstream;
};

std::string join(const std::set<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "'" : ", '") + s + "'";
  return out;
}

}  // namespace

class PipelineBuilder {
 public:
  PipelineBuilder(const Json& config, const PluginRegistry& plugins, std::filesystem::path config_directory)
      : cfg_(config), plugins_(plugins), config_directory_(std::move(config_directory)) {}

  Pipeline build() {
    if (!cfg_.is_object()) {
      type_error(cfg_, "", "object", "a pipeline config", diag_);
      diag_.throw_if_errors();
    }
    check_keys(cfg_, "",
               {"description", "sample_period_s", "inputs", "stages", "monitor",
                "allow_dependent_virtual_sensor"},
               "the pipeline config", diag_);
    read_header();
    read_inputs();
    read_stages();
    const std::vector<std::size_t> order = run_order();
    for (std::size_t index : order) build_stage(index);
    for (auto& d : decls_) {
      // Stages that could not be constructed still get their parameters checked.
      if (!d.built && d.plugin != nullptr && !constructed_attempted_.count(d.name)) {
        d.plugin->check_params(d.params, d.path + "/params", diag_);
      }
    }
    read_monitor();
    diag_.throw_if_errors();
    pipeline_.values_.assign(next_offset_, 0.0);
    pipeline_.warnings_ = diag_.warnings();
    pipeline_.bind_spans();
    pipeline_.reset();
    return std::move(pipeline_);
  }

 private:
  SignalRef allocate(std::size_t dim) {
    SignalRef r{next_offset_, dim};
    next_offset_ += dim;
    return r;
  }

  void read_header() {
    const auto it = cfg_.find("sample_period_s");
    if (it == cfg_.end()) {
      diag_.error("/sample_period_s", "missing required key (tick period T of the pipeline, s)");
    } else if (!it->is_number()) {
      type_error(*it, "/sample_period_s", "number", "tick period T, s", diag_);
    } else if (!(it->get<double>() > 0.0)) {
      diag_.error("/sample_period_s", " = " + it->dump() + " violates > 0 (tick period T, s)");
    } else {
      pipeline_.sample_period_s_ = it->get<double>();
    }
    if (const auto a = cfg_.find("allow_dependent_virtual_sensor"); a != cfg_.end()) {
      if (!a->is_boolean()) {
        type_error(*a, "/allow_dependent_virtual_sensor", "boolean",
                   "accept virtual sensors computed from the sensors they judge", diag_);
      } else {
        allow_dependent_ = a->get<bool>();
      }
    }
    if (const auto d = cfg_.find("description"); d != cfg_.end() && !d->is_string()) {
      type_error(*d, "/description", "string", "free text", diag_);
    }
  }

  void read_inputs() {
    const auto it = cfg_.find("inputs");
    if (it == cfg_.end()) {
      diag_.error("/inputs", "missing required key (the signals the pipeline reads each tick)");
      return;
    }
    if (!it->is_object() || it->empty()) {
      if (!it->is_object()) type_error(*it, "/inputs", "object", "named input signals", diag_);
      else diag_.error("/inputs", "is empty; declare at least one input signal");
      return;
    }
    for (const auto& [name, spec] : it->items()) {
      const std::string path = json_pointer_append("/inputs", name);
      if (!is_identifier(name)) {
        diag_.error(path, "input name '" + name + "' must be an identifier (letters, digits, _)");
        continue;
      }
      if (!spec.is_object()) {
        type_error(spec, path, "object", "an input signal", diag_);
        continue;
      }
      check_keys(spec, path, {"columns", "unit", "derived_from", "description"}, "an input", diag_);
      PipelineInput input;
      input.name = name;
      bool ok = true;
      const auto columns = spec.find("columns");
      if (columns == spec.end()) {
        diag_.error(path + "/columns", "missing required key (log column names, one per value)");
        ok = false;
      } else if (!columns->is_array() || columns->empty()) {
        if (!columns->is_array()) type_error(*columns, path + "/columns", "array of strings", "log column names", diag_);
        else diag_.error(path + "/columns", "is empty; list at least one log column");
        ok = false;
      } else {
        for (std::size_t i = 0; i < columns->size(); ++i) {
          const Json& c = (*columns)[i];
          if (!c.is_string() || c.get<std::string>().empty()) {
            type_error(c, json_pointer_append(path + "/columns", i), "non-empty string", "a log column name", diag_);
            ok = false;
          } else {
            input.columns.push_back(c.get<std::string>());
          }
        }
      }
      const auto unit = spec.find("unit");
      if (unit == spec.end()) {
        diag_.error(path + "/unit", "missing required key (SI unit of the values, \"1\" if dimensionless)");
        ok = false;
      } else if (!unit->is_string() || unit->get<std::string>().empty()) {
        type_error(*unit, path + "/unit", "non-empty string", "SI unit", diag_);
        ok = false;
      } else {
        input.unit = unit->get<std::string>();
      }
      if (const auto from = spec.find("derived_from"); from != spec.end()) {
        if (!from->is_array()) {
          type_error(*from, path + "/derived_from", "array of input names", "inputs this one is computed from", diag_);
        } else {
          for (std::size_t i = 0; i < from->size(); ++i) {
            const Json& f = (*from)[i];
            if (!f.is_string()) {
              type_error(f, json_pointer_append(path + "/derived_from", i), "string", "an input name", diag_);
            } else {
              input.derived_from.push_back(f.get<std::string>());
            }
          }
        }
      }
      if (const auto d = spec.find("description"); d != spec.end() && !d->is_string()) {
        type_error(*d, path + "/description", "string", "free text", diag_);
      }
      if (!ok) continue;
      input.values = allocate(input.columns.size());
      pipeline_.inputs_.push_back(std::move(input));
    }
    std::vector<std::string> names;
    for (const auto& in : pipeline_.inputs_) names.push_back(in.name);
    for (const auto& in : pipeline_.inputs_) {
      for (std::size_t i = 0; i < in.derived_from.size(); ++i) {
        const std::string& f = in.derived_from[i];
        if (std::find(names.begin(), names.end(), f) == names.end()) {
          diag_.error(json_pointer_append(json_pointer_append("/inputs", in.name) + "/derived_from", i),
                      "unknown input '" + f + "'; " + suggest(f, names));
        }
      }
    }
    for (const auto& in : pipeline_.inputs_) {
      SignalInfo info{in.values, in.unit, {}, {}};
      collect_input_dependencies(in.name, info.depends_on);
      signals_["input." + in.name] = std::move(info);
    }
  }

  // An input depends on itself and, transitively, on what it is derived from.
  void collect_input_dependencies(const std::string& name, std::set<std::string>& out) const {
    if (!out.insert(name).second) return;
    for (const auto& in : pipeline_.inputs_) {
      if (in.name != name) continue;
      for (const auto& f : in.derived_from) collect_input_dependencies(f, out);
    }
  }

  void read_stages() {
    const auto it = cfg_.find("stages");
    if (it == cfg_.end()) {
      diag_.error("/stages", "missing required key (the list of processing stages)");
      return;
    }
    if (!it->is_array()) {
      type_error(*it, "/stages", "array", "the list of processing stages", diag_);
      return;
    }
    // Names first, so that wires may name stages declared later.
    for (std::size_t i = 0; i < it->size(); ++i) {
      const Json& s = (*it)[i];
      StageDecl d;
      d.path = json_pointer_append("/stages", i);
      if (s.is_object()) {
        if (const auto n = s.find("name"); n != s.end() && n->is_string()) d.name = n->get<std::string>();
      }
      decls_.push_back(std::move(d));
    }
    for (auto& d : decls_) stage_names_.push_back(d.name);
    for (std::size_t i = 0; i < it->size(); ++i) read_stage((*it)[i], decls_[i], i);
  }

  void read_stage(const Json& s, StageDecl& d, std::size_t index) {
    if (!s.is_object()) {
      type_error(s, d.path, "object", "a stage", diag_);
      d.declared_ok = false;
      return;
    }
    check_keys(s, d.path, {"name", "plugin", "params", "inputs", "description"}, "a stage", diag_);
    const auto name = s.find("name");
    if (name == s.end()) {
      diag_.error(d.path + "/name", "missing required key (the stage's unique name)");
      d.declared_ok = false;
    } else if (!name->is_string()) {
      type_error(*name, d.path + "/name", "string", "the stage's unique name", diag_);
      d.declared_ok = false;
    } else if (!is_identifier(d.name) || d.name == "input") {
      diag_.error(d.path + "/name", " = " + name->dump() +
                                        " violates identifier (letters, digits, _; not 'input')");
      d.declared_ok = false;
    } else {
      for (std::size_t j = 0; j < index; ++j) {
        if (decls_[j].name == d.name) {
          diag_.error(d.path + "/name", "duplicate stage name '" + d.name + "' (also " +
                                            decls_[j].path + "); stage names must be unique");
          d.declared_ok = false;
        }
      }
    }
    const auto plugin = s.find("plugin");
    if (plugin == s.end()) {
      diag_.error(d.path + "/plugin", "missing required key; " + suggest("", plugins_.names()));
      d.declared_ok = false;
    } else if (!plugin->is_string()) {
      type_error(*plugin, d.path + "/plugin", "string", "a plugin name", diag_);
      d.declared_ok = false;
    } else {
      d.plugin = plugins_.find(plugin->get<std::string>());
      if (d.plugin == nullptr) {
        diag_.error(d.path + "/plugin", "unknown plugin '" + plugin->get<std::string>() + "'; " +
                                            suggest(plugin->get<std::string>(), plugins_.names()));
        d.declared_ok = false;
      }
    }
    if (const auto p = s.find("params"); p != s.end()) d.params = *p;
    if (const auto d2 = s.find("description"); d2 != s.end() && !d2->is_string()) {
      type_error(*d2, d.path + "/description", "string", "free text", diag_);
    }
    const auto inputs = s.find("inputs");
    if (inputs == s.end()) return;
    if (!inputs->is_object()) {
      type_error(*inputs, d.path + "/inputs", "object", "input port -> wire", diag_);
      d.declared_ok = false;
      return;
    }
    for (const auto& [port, value] : inputs->items()) {
      Wire w;
      w.port = port;
      w.path = json_pointer_append(d.path + "/inputs", port);
      if (!read_wire(value, w)) {
        d.declared_ok = false;
        continue;
      }
      for (const auto& e : w.ends) {
        if (!e.from_input) d.upstream.insert(e.producer);
      }
      d.wires.push_back(std::move(w));
    }
  }

  // Parses a wire value: "node.port" or an array of them.
  bool read_wire(const Json& value, Wire& w) {
    std::vector<std::pair<std::string, std::string>> texts;  // text, path
    if (value.is_string()) {
      texts.emplace_back(value.get<std::string>(), w.path);
    } else if (value.is_array() && !value.empty()) {
      for (std::size_t i = 0; i < value.size(); ++i) {
        if (!value[i].is_string()) {
          type_error(value[i], json_pointer_append(w.path, i), "string", "\"input.<name>\" or \"<stage>.<port>\"", diag_);
          return false;
        }
        texts.emplace_back(value[i].get<std::string>(), json_pointer_append(w.path, i));
      }
    } else {
      type_error(value, w.path, "string or non-empty array of strings",
                 "\"input.<name>\" or \"<stage>.<port>\"", diag_);
      return false;
    }
    bool ok = true;
    for (const auto& [text, path] : texts) {
      WireEnd e;
      e.text = text;
      const auto dot = text.find('.');
      if (dot == std::string::npos) {
        diag_.error(path, " = \"" + text + "\" violates the wire form \"input.<name>\" or \"<stage>.<port>\"");
        ok = false;
        continue;
      }
      e.node = text.substr(0, dot);
      e.port = text.substr(dot + 1);
      if (e.node == "input") {
        e.from_input = true;
        if (!signals_.count(text)) {
          std::vector<std::string> names;
          for (const auto& in : pipeline_.inputs_) names.push_back(in.name);
          diag_.error(path, "no input named '" + e.port + "'; " + suggest(e.port, names));
          ok = false;
          continue;
        }
      } else {
        const auto found = std::find(stage_names_.begin(), stage_names_.end(), e.node);
        if (found == stage_names_.end()) {
          diag_.error(path, "no stage named '" + e.node + "' (wire \"" + text + "\"); " +
                                suggest(e.node, stage_names_));
          ok = false;
          continue;
        }
        e.producer = static_cast<std::size_t>(found - stage_names_.begin());
      }
      w.ends.push_back(std::move(e));
    }
    return ok;
  }

  // Stages in dependency order (declaration order among independent ones); stages on a cycle
  // are reported and left out.
  std::vector<std::size_t> run_order() {
    const std::size_t n = decls_.size();
    std::vector<std::size_t> order;
    std::vector<bool> placed(n, false);
    bool progress = true;
    while (progress) {
      progress = false;
      for (std::size_t i = 0; i < n; ++i) {
        if (placed[i]) continue;
        bool ready = true;
        for (std::size_t u : decls_[i].upstream) ready = ready && placed[u];
        if (ready) {
          placed[i] = true;
          order.push_back(i);
          progress = true;
          break;  // restart: keeps declaration order among ready stages
        }
      }
    }
    if (order.size() < n) {
      // Walk upstream from an unplaced stage until a stage repeats: that is a cycle.
      std::size_t start = 0;
      while (placed[start]) ++start;
      std::vector<std::size_t> walk{start};
      while (true) {
        std::size_t next = walk.back();
        for (std::size_t u : decls_[walk.back()].upstream) {
          if (!placed[u]) {
            next = u;
            break;
          }
        }
        const auto seen = std::find(walk.begin(), walk.end(), next);
        if (seen != walk.end()) {
          // walk runs consumer -> producer; print producer -> consumer, closing the loop.
          std::string forward;
          std::vector<std::size_t> cycle(seen, walk.end());
          std::reverse(cycle.begin(), cycle.end());
          // Start the loop at the stage declared first, so the message is stable.
          std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
          for (std::size_t c : cycle) forward += decls_[c].name + " -> ";
          forward += decls_[cycle.front()].name;
          diag_.error("/stages", "the stages form a cycle (" + forward +
                                     "); a stage cannot depend on its own output, so cut the loop");
          break;
        }
        walk.push_back(next);
      }
    }
    return order;
  }

  void build_stage(std::size_t index) {
    StageDecl& d = decls_[index];
    if (!d.declared_ok || d.plugin == nullptr) return;
    // Resolve what each wire carries; a wire from a stage that failed stays unresolved.
    struct Resolved {
      std::vector<const SignalInfo*> ends;
      bool complete = true;
      std::size_t dim = 0;
    };
    std::vector<Resolved> resolved(d.wires.size());
    std::vector<std::pair<std::string, std::size_t>> wired_dims;
    bool all_resolved = true;
    for (std::size_t w = 0; w < d.wires.size(); ++w) {
      for (std::size_t e = 0; e < d.wires[w].ends.size(); ++e) {
        const SignalInfo* s = resolve(d.wires[w].ends[e], d.wires[w].ends.size() > 1
                                                              ? json_pointer_append(d.wires[w].path, e)
                                                              : d.wires[w].path);
        if (s == nullptr) {
          resolved[w].complete = false;
          continue;
        }
        resolved[w].ends.push_back(s);
        resolved[w].dim += s->ref.dim;
      }
      if (resolved[w].complete) wired_dims.emplace_back(d.wires[w].port, resolved[w].dim);
      all_resolved = all_resolved && resolved[w].complete;
    }
    if (!all_resolved) return;  // the cause is reported; parameters are still checked later
    constructed_attempted_.insert(d.name);
    StageContext context(pipeline_.sample_period_s_ > 0 ? pipeline_.sample_period_s_ : 1e-3, d.name,
                         wired_dims, config_directory_);
    std::unique_ptr<Stage> stage = d.plugin->create(d.params, d.path, context, diag_);
    if (!stage) return;
    const Ports& ports = stage->ports();
    bool ok = true;
    for (const auto& w : d.wires) {
      if (!ports.find_input(w.port)) {
        diag_.error(w.path, "plugin " + d.plugin->name + " has no input '" + w.port + "'; " +
                                suggest(w.port, ports.input_names()));
        ok = false;
      }
    }
    Pipeline::StageRun run;
    run.name = d.name;
    std::set<std::string> stage_depends_on;
    std::optional<std::string> generic_unit;
    std::string generic_unit_source;
    // Per input port: the dependencies of what is wired, for the independence rule.
    std::vector<std::set<std::string>> port_depends_on(ports.inputs().size());
    // Per input port: the sensors its values leave out channel by channel (leave-one-out outputs),
    // and whether every value wired to it is such an output.
    std::vector<std::set<std::string>> port_leaves_out(ports.inputs().size());
    std::vector<bool> port_all_leave_one_out(ports.inputs().size(), true);
    for (std::size_t p = 0; p < ports.inputs().size(); ++p) {
      const PortSpec& spec = ports.inputs()[p];
      std::size_t w = 0;
      while (w < d.wires.size() && d.wires[w].port != spec.name) ++w;
      if (w == d.wires.size()) {
        diag_.error(d.path + "/inputs/" + json_pointer_token(spec.name),
                    "missing input of plugin " + d.plugin->name + ": " + spec.description + " (" +
                        std::to_string(spec.dim) + " values" +
                        (spec.unit.empty() ? std::string() : ", " + spec.unit) +
                        "); wire it to \"input.<name>\" or \"<stage>.<port>\"");
        ok = false;
        continue;
      }
      const Wire& wire = d.wires[w];
      if (resolved[w].dim != spec.dim) {
        std::string detail;
        for (std::size_t e = 0; e < wire.ends.size(); ++e) {
          detail += (e ? " + " : "") + wire.ends[e].text + " (" + std::to_string(resolved[w].ends[e]->ref.dim) + ")";
        }
        diag_.error(wire.path, "carries " + std::to_string(resolved[w].dim) + " values [" + detail +
                                   "] but input '" + spec.name + "' of " + d.plugin->name +
                                   " takes " + std::to_string(spec.dim));
        ok = false;
      }
      for (std::size_t e = 0; e < wire.ends.size(); ++e) {
        const SignalInfo& s = *resolved[w].ends[e];
        port_depends_on[p].insert(s.depends_on.begin(), s.depends_on.end());
        port_leaves_out[p].insert(s.leave_one_out_of.begin(), s.leave_one_out_of.end());
        port_all_leave_one_out[p] = port_all_leave_one_out[p] && !s.leave_one_out_of.empty();
        if (spec.unit.empty()) {
          if (!generic_unit) {
            generic_unit = s.unit;
            generic_unit_source = wire.ends[e].text;
          } else if (*generic_unit != s.unit) {
            diag_.error(wire.path, "unit mismatch: " + wire.ends[e].text + " is in '" + s.unit +
                                       "' but " + generic_unit_source + " is in '" + *generic_unit +
                                       "'; the unit-generic inputs of " + d.plugin->name +
                                       " must share one unit");
            ok = false;
          }
        } else if (s.unit != spec.unit) {
          diag_.error(wire.path, "unit mismatch: " + wire.ends[e].text + " is in '" + s.unit +
                                     "' but input '" + spec.name + "' of " + d.plugin->name +
                                     " takes '" + spec.unit + "'");
          ok = false;
        }
      }
      stage_depends_on.insert(port_depends_on[p].begin(), port_depends_on[p].end());
    }
    check_independence(d, ports, port_depends_on, port_leaves_out, port_all_leave_one_out);
    if (!ok) return;
    // Buffers: an input wired to exactly one signal reads it in place; a concatenation is
    // gathered into a block of its own before each step.
    for (std::size_t p = 0; p < ports.inputs().size(); ++p) {
      std::size_t w = 0;
      while (d.wires[w].port != ports.inputs()[p].name) ++w;
      run.input_refs.push_back(place(resolved[w].ends, run.gathers));
    }
    std::set<std::string> measured_depends_on;
    for (std::size_t p = 0; p < ports.inputs().size(); ++p) {
      if (ports.inputs()[p].role == PortRole::measured) {
        measured_depends_on.insert(port_depends_on[p].begin(), port_depends_on[p].end());
      }
    }
    for (const PortSpec& out : ports.outputs()) {
      SignalInfo info;
      if (out.leave_one_out) info.leave_one_out_of = measured_depends_on;
      info.ref = allocate(out.dim);
      const std::string common_unit = generic_unit.value_or(std::string(kDimensionless));
      if (out.unit.empty()) {
        info.unit = common_unit;
      } else if (out.unit == kAnyUnitSquared) {
        info.unit = common_unit == kDimensionless ? common_unit : common_unit + "^2";
      } else {
        info.unit = out.unit;
      }
      info.depends_on = stage_depends_on;
      run.output_refs.push_back(info.ref);
      run.output_units.push_back(info.unit);
      signals_[d.name + "." + out.name] = std::move(info);
    }
    run.stage = std::move(stage);
    pipeline_.stages_.push_back(std::move(run));
    d.built = true;
  }

  SignalRef place(const std::vector<const SignalInfo*>& ends, std::vector<Pipeline::Copy>& gathers) {
    if (ends.size() == 1) return ends.front()->ref;
    std::size_t dim = 0;
    for (const SignalInfo* s : ends) dim += s->ref.dim;
    const SignalRef block = allocate(dim);
    std::size_t to = block.offset;
    for (const SignalInfo* s : ends) {
      gathers.push_back({s->ref.offset, to, s->ref.dim});
      to += s->ref.dim;
    }
    return block;
  }

  const SignalInfo* resolve(const WireEnd& e, const std::string& path) {
    if (e.from_input) return &signals_.at(e.text);
    const StageDecl& producer = decls_[e.producer];
    if (!producer.built) return nullptr;  // its own problems are reported
    const auto it = signals_.find(e.text);
    if (it != signals_.end()) return &it->second;
    std::vector<std::string> outputs;
    const std::string prefix = producer.name + ".";
    for (const auto& [name, info] : signals_) {
      if (name.rfind(prefix, 0) == 0) outputs.push_back(name.substr(prefix.size()));
    }
    diag_.error(path, "stage '" + producer.name + "' (" + producer.plugin->name + ") has no output '" +
                          e.port + "'; " + suggest(e.port, outputs));
    return nullptr;
  }

  void check_independence(const StageDecl& d, const Ports& ports,
                          const std::vector<std::set<std::string>>& depends_on,
                          const std::vector<std::set<std::string>>& leaves_out,
                          const std::vector<bool>& all_leave_one_out) {
    for (std::size_t v = 0; v < ports.inputs().size(); ++v) {
      if (ports.inputs()[v].role != PortRole::virtual_estimate) continue;
      for (std::size_t m = 0; m < ports.inputs().size(); ++m) {
        if (ports.inputs()[m].role != PortRole::measured) continue;
        report_dependence(d.path + "/inputs/" + json_pointer_token(ports.inputs()[v].name),
                          "'" + ports.inputs()[v].name + "' of stage '" + d.name + "'",
                          "'" + ports.inputs()[m].name + "'",
                          independent_part(depends_on[v], leaves_out[v], all_leave_one_out[v], depends_on[m]),
                          depends_on[m]);
      }
    }
  }

  // What a virtual signal depends on, less the sensors it leaves out channel by channel when it
  // is a leave-one-out estimate of exactly the measured signal (the same rule as the monitor's).
  static std::set<std::string> independent_part(std::set<std::string> virtual_deps,
                                                const std::set<std::string>& leaves_out,
                                                bool all_leave_one_out,
                                                const std::set<std::string>& measured_deps) {
    if (all_leave_one_out && measured_deps == leaves_out) {
      for (const auto& name : leaves_out) virtual_deps.erase(name);
    }
    return virtual_deps;
  }

  void report_dependence(const std::string& path, const std::string& virtual_what,
                         const std::string& measured_what, const std::set<std::string>& virtual_deps,
                         const std::set<std::string>& measured_deps) {
    std::set<std::string> shared;
    std::set_intersection(virtual_deps.begin(), virtual_deps.end(), measured_deps.begin(),
                          measured_deps.end(), std::inserter(shared, shared.begin()));
    if (shared.empty()) return;
    const std::string message =
        "independence rule: the virtual sensor " + virtual_what + " is computed from " +
        (shared.size() > 1 ? "inputs " : "input ") + join(shared) + ", which is what " + measured_what +
        " measures; a fault of that sensor would leak into its own reference (method.md "
        "section 0). Feed the virtual sensor from other signals (planned ZMP, kinematics)";
    if (allow_dependent_) {
      diag_.warning(path, message + "; accepted because \"allow_dependent_virtual_sensor\" is true");
    } else {
      diag_.error(path, message + ", or set \"allow_dependent_virtual_sensor\": true to accept it");
    }
  }

  // Resolves every end of a monitor wire; null when an end is unresolved or the values do not
  // number one per channel (both reported).
  std::optional<std::vector<const SignalInfo*>> resolve_monitor_wire(const Wire& w, std::size_t channels) {
    std::vector<const SignalInfo*> ends;
    std::size_t dim = 0;
    bool complete = true;
    for (std::size_t e = 0; e < w.ends.size(); ++e) {
      const SignalInfo* s = resolve(w.ends[e], w.ends.size() > 1 ? json_pointer_append(w.path, e) : w.path);
      if (s == nullptr) {
        complete = false;
        continue;
      }
      ends.push_back(s);
      dim += s->ref.dim;
    }
    if (!complete) return std::nullopt;
    if (dim != channels && channels != 0) {
      diag_.error(w.path, "carries " + std::to_string(dim) + " values but the monitor has " +
                              std::to_string(channels) + " channels");
      return std::nullopt;
    }
    return ends;
  }

  void read_monitor() {
    const auto it = cfg_.find("monitor");
    if (it == cfg_.end()) return;
    const std::string path = "/monitor";
    if (!it->is_object()) {
      type_error(*it, path, "object", "the monitored channels and their signals", diag_);
      return;
    }
    static const std::vector<std::string> fields{"measured",  "virtual", "fault_estimate",
                                                 "recovered", "fault",   "fault_type"};
    std::vector<std::string> known{"channels", "extra"};
    known.insert(known.end(), fields.begin(), fields.end());
    check_keys(*it, path, known, "the monitor", diag_);
    Monitor& m = pipeline_.monitor_;
    bool ok = true;
    const auto channels = it->find("channels");
    if (channels == it->end()) {
      diag_.error(path + "/channels", "missing required key (names of the monitored channels)");
      ok = false;
    } else if (!channels->is_array() || channels->empty()) {
      type_error(*channels, path + "/channels", "non-empty array of strings", "channel names", diag_);
      ok = false;
    } else {
      for (std::size_t i = 0; i < channels->size(); ++i) {
        const Json& c = (*channels)[i];
        if (!c.is_string() || c.get<std::string>().empty()) {
          type_error(c, json_pointer_append(path + "/channels", i), "non-empty string", "a channel name", diag_);
          ok = false;
        } else if (std::find(m.channels.begin(), m.channels.end(), c.get<std::string>()) != m.channels.end()) {
          diag_.error(json_pointer_append(path + "/channels", i), "duplicate channel name " + c.dump());
          ok = false;
        } else {
          m.channels.push_back(c.get<std::string>());
        }
      }
    }
    SignalRef* targets[] = {&m.measured, &m.virtual_value, &m.fault_estimate,
                            &m.recovered, &m.fault,        &m.fault_type};
    std::set<std::string> deps[2];
    std::string units[2];
    std::set<std::string> virtual_leave_one_out;
    bool virtual_all_leave_one_out = true;
    for (std::size_t f = 0; f < fields.size(); ++f) {
      Wire w;
      w.port = fields[f];
      w.path = path + "/" + fields[f];
      const auto value = it->find(fields[f]);
      if (value == it->end()) {
        diag_.error(w.path, "missing required key (the signal written as <channel>/" + fields[f] + ")");
        ok = false;
        continue;
      }
      if (!read_wire(*value, w)) {
        ok = false;
        continue;
      }
      const auto ends = resolve_monitor_wire(w, m.channels.size());
      if (!ends) {
        ok = false;
        continue;
      }
      for (const SignalInfo* s : *ends) {
        if (f < 2) {
          deps[f].insert(s->depends_on.begin(), s->depends_on.end());
          units[f] = s->unit;
        }
        if (f == 1) {
          virtual_leave_one_out.insert(s->leave_one_out_of.begin(), s->leave_one_out_of.end());
          virtual_all_leave_one_out = virtual_all_leave_one_out && !s->leave_one_out_of.empty();
        }
      }
      *targets[f] = place(*ends, pipeline_.monitor_gathers_);
    }
    if (const auto extra = it->find("extra"); extra != it->end()) {
      if (!extra->is_object()) {
        type_error(*extra, path + "/extra", "object", "name -> wire of further per-channel signals", diag_);
        ok = false;
      } else {
        for (const auto& [name, value] : extra->items()) {
          Wire w;
          w.port = name;
          w.path = json_pointer_append(path + "/extra", name);
          if (!is_identifier(name)) {
            diag_.error(w.path, "extra signal name '" + name + "' must be an identifier (letters, digits, _)");
            ok = false;
            continue;
          }
          if (!read_wire(value, w)) {
            ok = false;
            continue;
          }
          const auto ends = resolve_monitor_wire(w, m.channels.size());
          if (!ends) {
            ok = false;
            continue;
          }
          m.extra.push_back({name, ends->front()->unit, place(*ends, pipeline_.monitor_gathers_)});
        }
      }
    }
    if (!ok) return;
    if (units[0] != units[1]) {
      diag_.error(path + "/virtual", "unit mismatch: measured is in '" + units[0] +
                                         "' but virtual is in '" + units[1] + "'");
      return;
    }
    m.unit = units[0];
    // A leave-one-out virtual sensor of exactly the measured signal is independent channel by
    // channel: the inputs it leaves out do not count as shared.
    report_dependence(path + "/virtual", "'monitor/virtual'", "'monitor/measured'",
                      independent_part(deps[1], virtual_leave_one_out, virtual_all_leave_one_out, deps[0]),
                      deps[0]);
    pipeline_.has_monitor_ = true;
  }

  const Json& cfg_;
  const PluginRegistry& plugins_;
  std::filesystem::path config_directory_;
  Diagnostics diag_;
  Pipeline pipeline_;
  std::size_t next_offset_ = 0;
  bool allow_dependent_ = false;
  std::map<std::string, SignalInfo> signals_;
  std::vector<StageDecl> decls_;
  std::vector<std::string> stage_names_;
  std::set<std::string> constructed_attempted_;
};

Pipeline Pipeline::build(const Json& config, const PluginRegistry& plugins,
                         const std::filesystem::path& config_directory) {
  return PipelineBuilder(config, plugins, config_directory).build();
}

}  // namespace ftsense
