// Pipeline::build: from a read document (pipeline_document.hpp) to a runnable pipeline.
//
// The builder owns what only the plugins know: it constructs each stage in dependency order,
// checks every wire against the stage's ports (names, dimensions, units), applies the
// independence rule (independence_rule.hpp) and lays every signal out in one buffer.

#include <algorithm>
#include <deque>
#include <map>
#include <optional>
#include <set>

#include "ftsense/config_definitions.hpp"
#include "ftsense/independence_rule.hpp"
#include "ftsense/pipeline.hpp"
#include "ftsense/pipeline_document.hpp"

namespace ftsense {

namespace {

struct SignalInfo {
  SignalRef ref;
  std::string unit;
  SignalDependence dependence;
};

}  // namespace

class PipelineBuilder {
 public:
  PipelineBuilder(const Json& config, const PluginRegistry& plugins, std::filesystem::path config_directory)
      : cfg_(config), plugins_(plugins), config_directory_(std::move(config_directory)) {}

  Pipeline build() {
    doc_ = read_pipeline_document(cfg_, diag_);
    if (!cfg_.is_object()) diag_.throw_if_errors();
    pipeline_.sample_period_s_ = doc_.sample_period_s.value_or(0.0);
    pipeline_.time_column_ = doc_.time.column;
    pipeline_.time_unit_ = doc_.time.unit;
    pipeline_.time_seconds_per_unit_ = doc_.time.seconds_per_unit;
    place_inputs();
    place_previous_ticks();
    find_plugins();
    built_.assign(doc_.stages.size(), false);
    const std::vector<std::size_t> order = run_order();
    for (std::size_t index : order) build_stage(index);
    for (std::size_t i = 0; i < doc_.stages.size(); ++i) {
      // Stages that could not be constructed still get their parameters checked.
      if (!built_[i] && plugin_of_[i] != nullptr && !construction_attempted_.count(i)) {
        plugin_of_[i]->check_params(doc_.stages[i].params, doc_.stages[i].path + "/params", diag_);
      }
    }
    connect_previous_ticks();
    if (doc_.monitor) build_monitor(*doc_.monitor);
    diag_.throw_if_errors();
    pipeline_.values_.assign(next_offset_, 0.0);
    pipeline_.implausible_.assign(pipeline_.inputs_.size(), 0);
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

  void place_inputs() {
    std::vector<InputDerivation> derivations;
    for (const InputDecl& in : doc_.inputs) derivations.push_back({in.name, in.derived_from});
    for (const InputDecl& in : doc_.inputs) {
      PipelineInput input;
      input.name = in.name;
      input.columns = in.columns;
      input.unit = in.unit;
      input.derived_from = in.derived_from;
      input.values = allocate(in.columns.size());
      input.scale = in.scale;
      input.offset = in.offset;
      for (std::size_t i = 0; i < in.columns.size() && i < in.scale.size() && i < in.offset.size(); ++i) {
        if (in.scale[i] != 1.0 || in.offset[i] != 0.0) {
          pipeline_.conversions_.push_back({input.values.offset + i, in.scale[i], in.offset[i]});
        }
      }
      if (in.plausible_range) {
        input.plausible_min = (*in.plausible_range)[0];
        input.plausible_max = (*in.plausible_range)[1];
        pipeline_.gates_.push_back({pipeline_.inputs_.size(), input.values, input.plausible_min, input.plausible_max});
      }
      signals_["input." + in.name] = SignalInfo{input.values, in.unit, {input_dependencies(in.name, derivations), {}}};
      pipeline_.inputs_.push_back(std::move(input));
    }
  }

  // Each previous-tick signal gets a block of its declared size, which its stages read, and one
  // that stages its signal from the end of a tick to the start of the next (pipeline.hpp).
  void place_previous_ticks() {
    for (const PreviousTickDecl& d : doc_.previous_tick) {
      const SignalRef block = allocate(d.dim);
      const SignalRef staged = allocate(d.dim);
      signals_["previous_tick." + d.name] = SignalInfo{block, d.unit, {upstream_inputs(d.signal), {}}};
      pipeline_.previous_ticks_.push_back({d.name, d.unit, block, staged, d.initial});
    }
  }

  // The pipeline inputs a wire end depends on, through every stage upstream of it and every
  // previous-tick signal on the way: read from the document, before any plugin is built, since
  // a stage reading a previous-tick signal is built before the stage that computes it. It counts
  // everything a stage reads in each of its outputs (no leave-one-out exemption: a fed-back value
  // of channel i may carry channel j through the loop), so it errs towards reporting a breach.
  std::set<std::string> upstream_inputs(const WireEnd& end) const {
    std::vector<InputDerivation> derivations;
    for (const InputDecl& in : doc_.inputs) derivations.push_back({in.name, in.derived_from});
    std::set<std::string> inputs;
    std::set<std::size_t> seen_stages;
    std::set<std::string> seen_previous;
    std::vector<const WireEnd*> todo{&end};
    while (!todo.empty()) {
      const WireEnd* e = todo.back();
      todo.pop_back();
      if (e->from_input) {
        const std::set<std::string> d = input_dependencies(e->port, derivations);
        inputs.insert(d.begin(), d.end());
      } else if (e->from_previous_tick) {
        if (!seen_previous.insert(e->port).second) continue;
        for (const PreviousTickDecl& p : doc_.previous_tick) {
          if (p.name == e->port) todo.push_back(&p.signal);
        }
      } else if (seen_stages.insert(e->producer).second) {
        for (const WireDecl& w : doc_.stages[e->producer].wires) {
          for (const WireEnd& u : w.ends) todo.push_back(&u);
        }
      }
    }
    return inputs;
  }

  // Once every stage is built: each previous-tick signal's source, checked against what it
  // declared, and the copy that fills its block at the end of a tick.
  void connect_previous_ticks() {
    for (std::size_t i = 0; i < doc_.previous_tick.size(); ++i) {
      const PreviousTickDecl& d = doc_.previous_tick[i];
      const SignalInfo* source = resolve(d.signal);
      if (source == nullptr) continue;  // reported, or its stage was not built (its cause is reported)
      if (source->ref.dim != d.dim) {
        diag_.error(d.path + "/dim", " = " + std::to_string(d.dim) + " but \"" + d.signal.text + "\" carries " +
                                         std::to_string(source->ref.dim) + " values; declare \"dim\": " +
                                         std::to_string(source->ref.dim));
        continue;
      }
      if (source->unit != d.unit) {
        diag_.error(d.path + "/unit", " = \"" + d.unit + "\" but \"" + d.signal.text + "\" is in '" + source->unit +
                                          "'; declare \"unit\": \"" + source->unit + "\"");
        continue;
      }
      const Pipeline::PreviousTick& p = pipeline_.previous_ticks_[i];
      pipeline_.previous_tick_stores_.push_back({source->ref.offset, p.staged.offset, d.dim});
      pipeline_.previous_tick_loads_.push_back({p.staged.offset, p.values.offset, d.dim});
    }
  }

  void find_plugins() {
    plugin_of_.assign(doc_.stages.size(), nullptr);
    for (std::size_t i = 0; i < doc_.stages.size(); ++i) {
      StageDecl& d = doc_.stages[i];
      if (d.plugin.empty()) continue;  // missing or not a string: reported with the document
      plugin_of_[i] = plugins_.find(d.plugin);
      if (plugin_of_[i] == nullptr) {
        diag_.error(d.path + "/plugin", "unknown plugin '" + d.plugin + "'; " + suggest(d.plugin, plugins_.names()));
        d.ok = false;
      }
    }
  }

  // Stages in dependency order (declaration order among independent ones); stages on a cycle
  // are reported and left out.
  std::vector<std::size_t> run_order() {
    const auto& decls = doc_.stages;
    const std::size_t n = decls.size();
    std::vector<std::size_t> order;
    std::vector<bool> placed(n, false);
    bool progress = true;
    while (progress) {
      progress = false;
      for (std::size_t i = 0; i < n; ++i) {
        if (placed[i]) continue;
        bool ready = true;
        for (std::size_t u : decls[i].upstream) ready = ready && placed[u];
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
        for (std::size_t u : decls[walk.back()].upstream) {
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
          for (std::size_t c : cycle) forward += decls[c].name + " -> ";
          forward += decls[cycle.front()].name;
          diag_.error("/stages", "the stages form a cycle (" + forward +
                                     "); a stage cannot read its own output on the same tick: cut the loop, or read one of its "
                                     "signals one tick late (\"previous_tick\")");
          break;
        }
        walk.push_back(next);
      }
    }
    return order;
  }

  // What one end of a wire carries: null while its producer is unbuilt (its problems are
  // reported) or when the producer has no such output (reported here).
  const SignalInfo* resolve(const WireEnd& e) {
    if (e.from_input || e.from_previous_tick) {
      // Absent when the declaration is broken (reported with the document).
      const auto it = signals_.find(e.signal);
      return it == signals_.end() ? nullptr : select(e, it->second);
    }
    if (!built_[e.producer]) return nullptr;
    const auto it = signals_.find(e.signal);
    if (it != signals_.end()) return select(e, it->second);
    const StageDecl& producer = doc_.stages[e.producer];
    std::vector<std::string> outputs;
    const std::string prefix = producer.name + ".";
    for (const auto& [name, info] : signals_) {
      if (name.rfind(prefix, 0) == 0) outputs.push_back(name.substr(prefix.size()));
    }
    diag_.error(e.path, "stage '" + producer.name + "' (" + producer.plugin + ") has no output '" + e.port + "'; " +
                            suggest(e.port, outputs));
    return nullptr;
  }

  // The end's selection of `whole` ("[i:j]"), or `whole` itself; null (reported) when the
  // selection reaches beyond the signal's values.
  const SignalInfo* select(const WireEnd& e, const SignalInfo& whole) {
    if (!e.select) return &whole;
    const auto [first, last] = *e.select;
    if (last > whole.ref.dim) {
      diag_.error(e.path, "\"" + e.text + "\" selects values " + std::to_string(first) + " to " +
                              std::to_string(last - 1) + " of " + e.signal + ", which has " +
                              std::to_string(whole.ref.dim) + " (0-based: the last is [" +
                              std::to_string(whole.ref.dim - 1) + "])");
      return nullptr;
    }
    // Same unit and dependence as the whole signal; stored where its address stays put.
    return &selections_.emplace_back(SignalInfo{{whole.ref.offset + first, last - first}, whole.unit, whole.dependence});
  }

  // Every end of a wire resolved, or nullopt when one is not.
  std::optional<std::vector<const SignalInfo*>> resolve(const WireDecl& w) {
    std::vector<const SignalInfo*> ends;
    bool complete = true;
    for (const WireEnd& e : w.ends) {
      const SignalInfo* s = resolve(e);
      complete = complete && s != nullptr;
      if (s != nullptr) ends.push_back(s);
    }
    if (!complete) return std::nullopt;
    return ends;
  }

  static std::size_t total_dim(const std::vector<const SignalInfo*>& ends) {
    std::size_t dim = 0;
    for (const SignalInfo* s : ends) dim += s->ref.dim;
    return dim;
  }

  // Where a consumer reads a wire: in place when it is one signal, else a block of its own that
  // `gathers` fill before each step.
  SignalRef place(const std::vector<const SignalInfo*>& ends, std::vector<Pipeline::Copy>& gathers) {
    if (ends.size() == 1) return ends.front()->ref;
    const SignalRef block = allocate(total_dim(ends));
    std::size_t to = block.offset;
    for (const SignalInfo* s : ends) {
      gathers.push_back({s->ref.offset, to, s->ref.dim});
      to += s->ref.dim;
    }
    return block;
  }

  void build_stage(std::size_t index) {
    StageDecl& d = doc_.stages[index];
    const PluginInfo* plugin = plugin_of_[index];
    if (!d.ok || plugin == nullptr) return;
    // Resolve what each wire carries; a wire from a stage that failed stays unresolved.
    std::vector<std::vector<const SignalInfo*>> resolved(d.wires.size());
    std::vector<std::pair<std::string, std::size_t>> wired_dims;
    bool all_resolved = true;
    for (std::size_t w = 0; w < d.wires.size(); ++w) {
      auto ends = resolve(d.wires[w]);
      if (!ends) {
        all_resolved = false;
        continue;
      }
      resolved[w] = std::move(*ends);
      wired_dims.emplace_back(d.wires[w].port, total_dim(resolved[w]));
    }
    if (!all_resolved) return;  // the cause is reported; parameters are still checked later
    construction_attempted_.insert(index);
    StageContext context(pipeline_.sample_period_s_ > 0 ? pipeline_.sample_period_s_ : 1e-3, d.name, wired_dims,
                         config_directory_);
    std::unique_ptr<Stage> stage = plugin->create(d.params, d.path, context, diag_);
    if (!stage) return;
    const Ports& ports = stage->ports();
    bool ok = true;
    for (const auto& w : d.wires) {
      if (!ports.find_input(w.port)) {
        diag_.error(w.path, "plugin " + plugin->name + " has no input '" + w.port + "'; " +
                                suggest(w.port, ports.input_names()));
        ok = false;
      }
    }
    std::set<std::string> stage_inputs;  // every pipeline input the stage reads
    std::optional<std::string> generic_unit;
    std::string generic_unit_source;
    std::vector<WireDependence> port_dependence(ports.inputs().size());
    std::vector<std::size_t> port_wire(ports.inputs().size(), d.wires.size());
    for (std::size_t p = 0; p < ports.inputs().size(); ++p) {
      const PortSpec& spec = ports.inputs()[p];
      std::size_t w = 0;
      while (w < d.wires.size() && d.wires[w].port != spec.name) ++w;
      port_wire[p] = w;
      if (w == d.wires.size()) {
        diag_.error(d.path + "/inputs/" + json_pointer_token(spec.name),
                    "missing input of plugin " + plugin->name + ": " + spec.description + " (" +
                        std::to_string(spec.dim) + " values" + (spec.unit.empty() ? std::string() : ", " + spec.unit) +
                        (spec.frame.empty() ? std::string() : ", " + spec.frame + " frame") +
                        "); wire it to \"input.<name>\", \"<stage>.<port>\" or \"previous_tick.<name>\"");
        ok = false;
        continue;
      }
      const WireDecl& wire = d.wires[w];
      if (total_dim(resolved[w]) != spec.dim) {
        std::string detail;
        for (std::size_t e = 0; e < wire.ends.size(); ++e) {
          detail += (e ? " + " : "") + wire.ends[e].text + " (" + std::to_string(resolved[w][e]->ref.dim) + ")";
        }
        diag_.error(wire.path, "carries " + std::to_string(total_dim(resolved[w])) + " values [" + detail +
                                   "] but input '" + spec.name + "' of " + plugin->name + " takes " +
                                   std::to_string(spec.dim));
        ok = false;
      }
      for (std::size_t e = 0; e < wire.ends.size(); ++e) {
        const SignalInfo& s = *resolved[w][e];
        port_dependence[p].add(s.dependence);
        if (spec.unit.empty()) {
          if (!generic_unit) {
            generic_unit = s.unit;
            generic_unit_source = wire.ends[e].text;
          } else if (*generic_unit != s.unit) {
            diag_.error(wire.path, "unit mismatch: " + wire.ends[e].text + " is in '" + s.unit + "' but " +
                                       generic_unit_source + " is in '" + *generic_unit + "'; the unit-generic inputs of " +
                                       plugin->name + " must share one unit");
            ok = false;
          }
        } else if (s.unit != spec.unit) {
          diag_.error(wire.path, "unit mismatch: " + wire.ends[e].text + " is in '" + s.unit + "' but input '" +
                                     spec.name + "' of " + plugin->name + " takes '" + spec.unit + "'");
          ok = false;
        }
      }
      stage_inputs.insert(port_dependence[p].inputs().begin(), port_dependence[p].inputs().end());
    }
    check_independence(d, ports, port_dependence);
    if (!ok) return;
    Pipeline::StageRun run;
    run.name = d.name;
    for (std::size_t p = 0; p < ports.inputs().size(); ++p) {
      run.input_refs.push_back(place(resolved[port_wire[p]], run.gathers));
    }
    std::set<std::string> measured_inputs;
    for (std::size_t p = 0; p < ports.inputs().size(); ++p) {
      if (ports.inputs()[p].role == PortRole::measured) {
        measured_inputs.insert(port_dependence[p].inputs().begin(), port_dependence[p].inputs().end());
      }
    }
    for (const PortSpec& out : ports.outputs()) {
      SignalInfo info;
      info.ref = allocate(out.dim);
      const std::string common_unit = generic_unit.value_or(std::string(kDimensionless));
      if (out.unit.empty()) {
        info.unit = common_unit;
      } else if (out.unit == kAnyUnitSquared) {
        info.unit = common_unit == kDimensionless ? common_unit : common_unit + "^2";
      } else {
        info.unit = out.unit;
      }
      info.dependence.inputs = stage_inputs;
      if (out.leave_one_out) info.dependence.leaves_out = measured_inputs;
      run.output_refs.push_back(info.ref);
      run.output_units.push_back(info.unit);
      signals_[d.name + "." + out.name] = std::move(info);
    }
    run.stage = std::move(stage);
    pipeline_.stages_.push_back(std::move(run));
    built_[index] = true;
  }

  void check_independence(const StageDecl& d, const Ports& ports, const std::vector<WireDependence>& dependence) {
    for (std::size_t v = 0; v < ports.inputs().size(); ++v) {
      if (ports.inputs()[v].role != PortRole::virtual_estimate) continue;
      for (std::size_t m = 0; m < ports.inputs().size(); ++m) {
        if (ports.inputs()[m].role != PortRole::measured) continue;
        report_breach(d.path + "/inputs/" + json_pointer_token(ports.inputs()[v].name),
                      "'" + ports.inputs()[v].name + "' of stage '" + d.name + "'",
                      "'" + ports.inputs()[m].name + "'", dependence[v].shared_with(dependence[m].inputs()));
      }
    }
  }

  void report_breach(const std::string& path, const std::string& virtual_what, const std::string& measured_what,
                     const std::set<std::string>& shared) {
    if (shared.empty()) return;
    const std::string message = independence_breach(virtual_what, measured_what, shared);
    if (doc_.allow_dependent_virtual_sensor) {
      diag_.warning(path, message + "; accepted because \"allow_dependent_virtual_sensor\" is true");
    } else {
      diag_.error(path, message + ", or set \"allow_dependent_virtual_sensor\": true to accept it");
    }
  }

  // The ends of a monitor wire when they resolve and number one value per channel (else null,
  // reported).
  std::optional<std::vector<const SignalInfo*>> resolve_monitor_wire(const WireDecl& w, std::size_t channels) {
    auto ends = resolve(w);
    if (!ends) return std::nullopt;
    const std::size_t dim = total_dim(*ends);
    if (dim != channels && channels != 0) {
      diag_.error(w.path, "carries " + std::to_string(dim) + " values but the monitor has " + std::to_string(channels) +
                              " channels");
      return std::nullopt;
    }
    return ends;
  }

  void build_monitor(const MonitorDecl& decl) {
    Monitor& m = pipeline_.monitor_;
    m.channels = decl.channels;
    bool ok = decl.ok;
    std::array<WireDependence, kMonitorColumnCount> dependence;
    std::array<std::string, kMonitorColumnCount> units;
    for (std::size_t c = 0; c < kMonitorColumnCount; ++c) {
      if (!decl.columns[c]) continue;  // reported
      const auto ends = resolve_monitor_wire(*decl.columns[c], m.channels.size());
      if (!ends) {
        ok = false;
        continue;
      }
      for (const SignalInfo* s : *ends) {
        dependence[c].add(s->dependence);
        units[c] = s->unit;
      }
      m.columns[c] = place(*ends, pipeline_.monitor_gathers_);
    }
    for (const WireDecl& w : decl.extra) {
      const auto ends = resolve_monitor_wire(w, m.channels.size());
      if (!ends) {
        ok = false;
        continue;
      }
      m.extra.push_back({w.port, ends->front()->unit, place(*ends, pipeline_.monitor_gathers_)});
    }
    if (!ok) return;
    const auto measured = static_cast<std::size_t>(MonitorColumn::measured);
    const auto virtual_value = static_cast<std::size_t>(MonitorColumn::virtual_value);
    const auto cannot_judge = static_cast<std::size_t>(MonitorColumn::cannot_judge);
    if (!decl.columns[cannot_judge]) {  // not wired: the pipeline derives it from the virtual value
      m.columns[cannot_judge] = allocate(m.channels.size());
      pipeline_.derived_cannot_judge_ = {true, m.columns[virtual_value], m.columns[cannot_judge]};
    }
    if (units[measured] != units[virtual_value]) {
      diag_.error("/monitor/virtual", "unit mismatch: measured is in '" + units[measured] + "' but virtual is in '" +
                                          units[virtual_value] + "'");
      return;
    }
    m.unit = units[measured];
    report_breach("/monitor/virtual", "'monitor/virtual'", "'monitor/measured'",
                  dependence[virtual_value].shared_with(dependence[measured].inputs()));
    pipeline_.has_monitor_ = true;
  }

  const Json& cfg_;
  const PluginRegistry& plugins_;
  std::filesystem::path config_directory_;
  Diagnostics diag_;
  PipelineDocument doc_;
  Pipeline pipeline_;
  std::size_t next_offset_ = 0;
  std::map<std::string, SignalInfo> signals_;
  std::deque<SignalInfo> selections_;  // the selected parts of signals ("imu.acc[2]"); stable addresses
  std::vector<const PluginInfo*> plugin_of_;  // per declared stage; null: unknown or missing
  std::vector<bool> built_;                   // per declared stage
  std::set<std::size_t> construction_attempted_;
};

Pipeline Pipeline::build(const Json& config, const PluginRegistry& plugins,
                         const std::filesystem::path& config_directory) {
  Diagnostics references;
  const Json resolved = resolve_definitions(config, references);
  references.throw_if_errors();
  return PipelineBuilder(resolved, plugins, config_directory).build();
}

}  // namespace ftsense
