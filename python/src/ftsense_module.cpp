// ftsense._ftsense: the compiled part of the Python module `ftsense` (docs/python.md).
//
// A Pipeline is built from a config file (the loader `ftsense run` uses: same checks, same
// messages, paths prefixed by the file name) or from JSON text (a Python dict, dumped by
// ftsense/__init__.py). Every tick runs here, in C++: `run` and `run_log` take whole arrays or a
// whole log, release the GIL and step the pipeline row by row over preallocated buffers; `step`
// is one tick for interactive use. `run_log` is the log runner of `ftsense run` itself
// (apps/ftsense/log_runner.cpp), so its columns and numbers are those of `ftsense run`'s CSV.
//
// Errors become Python exceptions carrying ftsense's message: ConfigError (with .problems, the
// (path, message) pairs), LogError, OutputError and UsageError, all ftsense.Error.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli.hpp"
#include "ftsense/diagnostics.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/io/csv_log.hpp"
#include "ftsense/io/output_file.hpp"
#include "ftsense/json_text.hpp"
#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"
#include "ftsense/text_file.hpp"
#include "log_runner.hpp"
#include "report.hpp"

namespace py = pybind11;

namespace ftsense::python {
namespace {

// The verbs as `ftsense` runs them: the reference plugins, messages naming "ftsense".
const cli::Context& reference_context() {
  static const PluginRegistry registry = reference_plugins::registry();
  static const cli::Context context{registry, "ftsense"};
  return context;
}

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// One port of the pipeline as Python sees it: a pipeline input ("input.<name>", with the log
// columns it reads) or a stage output ("<stage>.<port>").
struct Port {
  std::string name;
  std::size_t dim = 0;
  std::string unit;
  std::string description;
  std::vector<std::string> columns;  // pipeline inputs: the log columns, one per value
};

// ConfigError problems prefixed by where the config came from ("file.json:/stages/2").
[[noreturn]] void rethrow_with_source(const ConfigError& e, const std::string& source) {
  std::vector<Diagnostic> problems = e.problems();
  if (!source.empty()) {
    for (auto& p : problems) p.path = source + ":" + p.path;
  }
  throw ConfigError(std::move(problems));
}

// The pipeline and what Python needs to address its signals by name.
class PyPipeline {
 public:
  PyPipeline(Pipeline pipeline, std::string source) : pipeline_(std::move(pipeline)), source_(std::move(source)) {
    for (const PipelineInput& in : pipeline_.inputs()) {
      inputs_.push_back({in.name, in.values.dim, in.unit, "", in.columns});
    }
    // signal_names(): inputs first, then every stage's outputs in run order and port order (then
    // the previous-tick signals, which name_of finds through signal_names()).
    const auto names = pipeline_.signal_names();
    std::size_t at = pipeline_.inputs().size();
    for (std::size_t s = 0; s < pipeline_.stage_count(); ++s) {
      for (const PortSpec& spec : pipeline_.stage(s).ports().outputs()) {
        outputs_.push_back({names[at].first, spec.dim, names[at].second, spec.description, {}});
        ++at;
      }
    }
  }

  // The loader of `ftsense run`: a config file, and optionally a thresholds file from calibrate.
  static std::unique_ptr<PyPipeline> from_file(const std::string& path, const std::string& thresholds_path) {
    return std::make_unique<PyPipeline>(cli::load_pipeline(reference_context(), path, thresholds_path), path);
  }

  // A config as JSON text (a Python dict dumped); `thresholds_text` as written by calibrate.
  static std::unique_ptr<PyPipeline> from_json(const std::string& text, const std::string& thresholds_text,
                              const std::filesystem::path& base_dir) {
    Json config = parse_json_text(text, "<config>");
    if (!thresholds_text.empty()) {
      cli::apply_thresholds(config, parse_json_text(thresholds_text, "<thresholds>"), "<thresholds>");
    }
    return std::make_unique<PyPipeline>(Pipeline::build(config, reference_plugins::registry(), base_dir), "");
  }

  [[nodiscard]] const std::vector<Port>& inputs() const noexcept { return inputs_; }
  [[nodiscard]] const std::vector<Port>& outputs() const noexcept { return outputs_; }
  [[nodiscard]] double sample_period_s() const noexcept { return pipeline_.sample_period_s(); }
  [[nodiscard]] const std::string& time_column() const noexcept { return pipeline_.time_column(); }
  [[nodiscard]] const std::string& source() const noexcept { return source_; }
  [[nodiscard]] io::TimeColumn time() const { return cli::time_column_of(pipeline_); }

  [[nodiscard]] std::vector<std::string> warnings() const {
    std::vector<std::string> out;
    for (const Diagnostic& w : pipeline_.warnings()) out.push_back(w.text());
    return out;
  }

  [[nodiscard]] std::vector<std::string> channels() const {
    return pipeline_.has_monitor() ? pipeline_.monitor().channels : std::vector<std::string>{};
  }

  // The columns `ftsense run` writes (time_s, then the monitored channels); none without monitor.
  [[nodiscard]] std::vector<std::string> columns() const {
    return pipeline_.has_monitor() ? cli::monitor_columns(pipeline_.monitor()) : std::vector<std::string>{};
  }

  // Monitor key ("measured", "virtual", ...) -> the signal it reads.
  [[nodiscard]] std::vector<std::pair<std::string, std::string>> monitor() const {
    std::vector<std::pair<std::string, std::string>> out;
    if (!pipeline_.has_monitor()) return out;
    for (const MonitorColumnInfo& column : kMonitorColumns) {
      out.emplace_back(std::string(column.key), name_of(pipeline_.monitor()[column.column]));
    }
    return out;
  }

  // The current values of a signal ("input.<name>", "<stage>.<port>" or "previous_tick.<name>"), a copy.
  py::array_t<double> values(const std::string& name) {
    const Busy busy(*this);
    return current_values(name);
  }

  void reset() {
    const Busy busy(*this);
    pipeline_.reset();
  }

  // One tick: every input's values, then step(t); returns the requested signals' values.
  py::dict step(double time_s, const py::dict& inputs, const std::optional<std::vector<std::string>>& outputs) {
    const Busy busy(*this);
    const std::vector<Array> given = input_arrays(inputs, false);
    for (std::size_t i = 0; i < given.size(); ++i) {
      std::copy_n(given[i].data(), given[i].size(), pipeline_.input_values(i).begin());
    }
    pipeline_.step(time_s);
    py::dict out;
    for (const std::string& name : output_names(outputs)) out[py::str(name)] = current_values(name);
    return out;
  }

  // Every row of the input arrays (rows = ticks) in turn; returns the requested signals as
  // (ticks, dim) arrays. time: one time per row, or none for t = k T.
  py::dict run(const py::dict& inputs, const std::optional<Array>& time,
               const std::optional<std::vector<std::string>>& outputs, bool reset) {
    const Busy busy(*this);
    const std::vector<Array> given = input_arrays(inputs, true);
    const std::size_t ticks = given.empty() ? (time ? static_cast<std::size_t>(time->size()) : 0)
                                            : static_cast<std::size_t>(given.front().shape(0));
    const std::vector<double> times = tick_times(time, ticks);
    const std::vector<std::string> names = output_names(outputs);
    std::vector<SignalRef> refs;
    std::vector<py::array_t<double>> arrays;
    std::vector<double*> into;
    for (const std::string& name : names) {
      refs.push_back(signal(name));
      arrays.emplace_back(std::vector<py::ssize_t>{static_cast<py::ssize_t>(ticks), static_cast<py::ssize_t>(refs.back().dim)});
      into.push_back(arrays.back().mutable_data());
    }
    std::vector<const double*> from;
    for (const Array& a : given) from.push_back(a.data());
    {
      const py::gil_scoped_release unlocked;
      if (reset) pipeline_.reset();
      for (std::size_t k = 0; k < ticks; ++k) {
        for (std::size_t i = 0; i < from.size(); ++i) {
          const auto values = pipeline_.input_values(i);
          std::copy_n(from[i] + k * values.size(), values.size(), values.begin());
        }
        pipeline_.step(times[k]);
        for (std::size_t o = 0; o < refs.size(); ++o) {
          const auto v = pipeline_.values(refs[o]);
          std::copy(v.begin(), v.end(), into[o] + k * v.size());
        }
      }
    }
    py::dict out;
    for (std::size_t o = 0; o < names.size(); ++o) out[py::str(names[o])] = arrays[o];
    return out;
  }

  // The monitored channels of a run over arrays, in `ftsense run`'s columns: (columns, ticks),
  // one row per column (each column contiguous; ftsense/__init__.py makes the dict).
  py::array_t<double> run_table(const py::dict& inputs, const std::optional<Array>& time, bool reset) {
    const Busy busy(*this);
    require_monitor();
    const std::vector<Array> given = input_arrays(inputs, true);
    const std::size_t ticks = given.empty() ? (time ? static_cast<std::size_t>(time->size()) : 0)
                                            : static_cast<std::size_t>(given.front().shape(0));
    const std::vector<double> times = tick_times(time, ticks);
    const std::size_t width = columns().size();
    py::array_t<double> table(std::vector<py::ssize_t>{static_cast<py::ssize_t>(width), static_cast<py::ssize_t>(ticks)});
    double* const out = table.mutable_data();
    std::vector<const double*> from;
    for (const Array& a : given) from.push_back(a.data());
    {
      const py::gil_scoped_release unlocked;
      if (reset) pipeline_.reset();
      std::vector<double> row(width);
      for (std::size_t k = 0; k < ticks; ++k) {
        for (std::size_t i = 0; i < from.size(); ++i) {
          const auto values = pipeline_.input_values(i);
          std::copy_n(from[i] + k * values.size(), values.size(), values.begin());
        }
        pipeline_.step(times[k]);
        monitor_row(times[k], row);
        for (std::size_t c = 0; c < width; ++c) out[c * ticks + k] = row[c];
      }
    }
    return table;
  }

  // `ftsense run`'s log runner over a CSV log: (columns, ticks) as run_table, the clock
  // warnings `ftsense run` prints (empty when none), and the run summary.
  // With `output`, the same rows also go to that CSV file, as `ftsense run --output` writes it.
  py::tuple run_log(const std::string& path, double gap_reset_periods, const std::string& output) {
    const Busy busy(*this);
    require_monitor();
    io::CsvLogReader log(path, cli::time_column_of(pipeline_));
    const cli::ColumnMap map = [&] {
      try {
        return cli::ColumnMap::make(pipeline_, log);
      } catch (const ConfigError& e) {
        rethrow_with_source(e, source_);
      }
    }();
    cli::ClockPolicy clock;
    clock.gap_reset_periods = gap_reset_periods;
    const std::size_t width = columns().size();
    std::vector<double> rows;  // row-major, grown per tick: the run's result, not the tick's work
    std::vector<double> row(width);
    std::optional<io::CsvLogWriter> out_file;
    if (!output.empty()) {
      std::vector<std::string> read{path};
      if (!source_.empty()) read.push_back(source_);
      out_file.emplace(output, columns(), read);
    }
    cli::RunSummary summary;
    {
      const py::gil_scoped_release unlocked;
      summary = cli::run_over_log(pipeline_, log, map, out_file ? &*out_file : nullptr, [&](double t) {
        monitor_row(t, row);
        rows.insert(rows.end(), row.begin(), row.end());
      }, {}, clock);
    }
    if (out_file) out_file->commit();
    const std::size_t ticks = summary.ticks;
    py::array_t<double> table(std::vector<py::ssize_t>{static_cast<py::ssize_t>(width), static_cast<py::ssize_t>(ticks)});
    double* const out = table.mutable_data();
    for (std::size_t k = 0; k < ticks; ++k) {
      for (std::size_t c = 0; c < width; ++c) out[c * ticks + k] = rows[k * width + c];
    }
    py::dict info;
    info["ticks"] = summary.ticks;
    info["gap_resets"] = summary.gap_resets;
    info["irregular_steps"] = summary.irregular_steps;
    py::dict first_fault;
    for (std::size_t c = 0; c < summary.first_fault_time_s.size(); ++c) {
      first_fault[py::str(pipeline_.monitor().channels[c])] = summary.first_fault_time_s[c];
    }
    info["first_fault_time_s"] = first_fault;
    py::dict unjudged;
    for (std::size_t c = 0; c < summary.unjudged_ticks.size(); ++c) {
      unjudged[py::str(pipeline_.monitor().channels[c])] = summary.unjudged_ticks[c];
    }
    info["unjudged_ticks"] = unjudged;
    const std::string warnings = cli::clock_warnings(path, summary, pipeline_.sample_period_s(), clock);
    return py::make_tuple(table, warnings, info);
  }

 private:
  // One user of the pipeline at a time: run() releases the GIL, so another Python thread could
  // otherwise step the same buffers.
  class Busy {
   public:
    explicit Busy(PyPipeline& p) : lock_(p.busy_, std::try_to_lock) {
      if (!lock_.owns_lock()) throw std::runtime_error("this ftsense.Pipeline is in use by another thread");
    }

   private:
    std::unique_lock<std::mutex> lock_;
  };

  [[nodiscard]] py::array_t<double> current_values(const std::string& name) const {
    const auto v = pipeline_.values(signal(name));
    return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
  }

  [[nodiscard]] SignalRef signal(const std::string& name) const {
    try {
      return pipeline_.signal(name);
    } catch (const ConfigError& e) {
      throw py::key_error(e.problems().front().message);
    }
  }

  // The name of the signal a SignalRef points at ("input.forces", "vfs.forces"); a monitor
  // wire that concatenates several signals has none of its own.
  [[nodiscard]] std::string name_of(SignalRef ref) const {
    for (const Port& p : inputs_) {
      const SignalRef r = pipeline_.signal("input." + p.name);
      if (r.offset == ref.offset && r.dim == ref.dim) return "input." + p.name;
    }
    for (const Port& p : outputs_) {
      const SignalRef r = pipeline_.signal(p.name);
      if (r.offset == ref.offset && r.dim == ref.dim) return p.name;
    }
    for (const auto& [name, unit] : pipeline_.signal_names()) {
      if (name.rfind("previous_tick.", 0) != 0) continue;
      const SignalRef r = pipeline_.signal(name);
      if (r.offset == ref.offset && r.dim == ref.dim) return name;
    }
    return {};
  }

  [[nodiscard]] std::vector<std::string> output_names(const std::optional<std::vector<std::string>>& outputs) const {
    if (outputs) return *outputs;
    std::vector<std::string> names;
    for (const Port& p : outputs_) names.push_back(p.name);
    return names;
  }

  void require_monitor() const {
    if (!pipeline_.has_monitor()) {
      throw ConfigError((source_.empty() ? std::string() : source_ + ":") + "/monitor",
                        "missing; the monitored channels (ftsense run's columns) need a \"monitor\" section");
    }
  }

  // The inputs given by name, in the pipeline's input order, as contiguous double arrays:
  // (dim,) for one tick, or (ticks, dim) with the same ticks for all. Every input is required.
  std::vector<Array> input_arrays(const py::dict& given, bool rows) const {
    std::vector<std::string> known;
    for (const Port& p : inputs_) known.push_back(p.name);
    for (const auto& item : given) {
      const std::string name = py::str(item.first);
      if (std::find(known.begin(), known.end(), name) == known.end()) {
        throw py::key_error("no pipeline input named '" + name + "'; " + suggest(name, known));
      }
    }
    std::vector<Array> out;
    std::string first;  // the input the others' row count is compared with
    std::string missing;
    for (const Port& p : inputs_) {
      if (!given.contains(py::str(p.name))) {
        missing += (missing.empty() ? "" : ", ") + p.name;
        continue;
      }
      Array a = Array::ensure(given[py::str(p.name)]);
      if (!a) throw py::type_error("input '" + p.name + "': not convertible to an array of numbers");
      const auto dim = static_cast<py::ssize_t>(p.dim);
      if (rows) {
        // One value per tick may come as a 1-D array for a one-dimensional input.
        if (a.ndim() == 1 && dim == 1) a = Array::ensure(a.reshape({a.shape(0), py::ssize_t{1}}));
        if (a.ndim() != 2 || a.shape(1) != dim) {
          throw py::value_error("input '" + p.name + "': expected an array of shape (ticks, " + std::to_string(p.dim) +
                                "), got " + shape_text(a));
        }
        if (!out.empty() && a.shape(0) != out.front().shape(0)) {
          throw py::value_error("input '" + p.name + "': " + std::to_string(a.shape(0)) + " rows, but input '" +
                                first + "' has " + std::to_string(out.front().shape(0)));
        }
      } else if (a.ndim() > 1 || a.size() != dim) {
        throw py::value_error("input '" + p.name + "': expected " + std::to_string(p.dim) + " values, got " +
                              shape_text(a));
      }
      if (out.empty()) first = p.name;
      out.push_back(std::move(a));
    }
    if (!missing.empty()) throw py::key_error("missing pipeline input(s): " + missing);
    return out;
  }

  static std::string shape_text(const Array& a) {
    std::string text = "shape (";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) text += (d ? ", " : "") + std::to_string(a.shape(d));
    return text + (a.ndim() == 1 ? ",)" : ")");
  }

  [[nodiscard]] std::vector<double> tick_times(const std::optional<Array>& time, std::size_t ticks) const {
    std::vector<double> times(ticks);
    if (!time) {
      for (std::size_t k = 0; k < ticks; ++k) times[k] = static_cast<double>(k) * pipeline_.sample_period_s();
      return times;
    }
    if (time->ndim() != 1 || static_cast<std::size_t>(time->size()) != ticks) {
      throw py::value_error("time: expected " + std::to_string(ticks) + " values (one per row), got " +
                            shape_text(*time));
    }
    std::copy_n(time->data(), ticks, times.begin());
    return times;
  }

  // One row of `ftsense run`'s output after a tick, in the order cli::monitor_columns names
  // (monitor_columns.hpp: per channel the kMonitorColumns, then the extra signals).
  void monitor_row(double time_s, std::vector<double>& row) const noexcept {
    const Monitor& m = pipeline_.monitor();
    std::size_t at = 0;
    row[at++] = time_s;
    for (std::size_t c = 0; c < m.channels.size(); ++c) {
      for (const MonitorColumnInfo& column : kMonitorColumns) row[at++] = pipeline_.values(m[column.column])[c];
      for (const Monitor::Extra& e : m.extra) row[at++] = pipeline_.values(e.signal)[c];
    }
  }

  Pipeline pipeline_;
  std::string source_;  // the config file, or empty for a config given as JSON text
  std::vector<Port> inputs_;
  std::vector<Port> outputs_;
  std::mutex busy_;
};

// Every row of a CSV log read by ftsense's reader (the one `ftsense run` uses): (column names,
// (columns, rows) array); the first column is the time in seconds.
py::tuple read_log(const std::string& path, const io::TimeColumn& time) {
  io::CsvLogReader log(path, time);
  const std::size_t width = log.columns().size();
  std::vector<double> rows;
  std::vector<double> row;
  {
    const py::gil_scoped_release unlocked;
    while (log.next(row)) rows.insert(rows.end(), row.begin(), row.end());
  }
  const std::size_t count = rows.size() / width;
  py::array_t<double> table(std::vector<py::ssize_t>{static_cast<py::ssize_t>(width), static_cast<py::ssize_t>(count)});
  double* const out = table.mutable_data();
  for (std::size_t k = 0; k < count; ++k) {
    for (std::size_t c = 0; c < width; ++c) out[c * count + k] = rows[k * width + c];
  }
  return py::make_tuple(log.columns(), table);
}

// Runs `body` with std::cout and std::cerr written into strings (the verbs print their results
// and refusals there); one capture at a time, as the streams are the process's.
template <class Body>
std::pair<std::string, std::string> captured(Body&& body) {
  static std::mutex streams;
  const std::lock_guard lock(streams);
  std::ostringstream out;
  std::ostringstream err;
  std::streambuf* const old_out = std::cout.rdbuf(out.rdbuf());
  std::streambuf* const old_err = std::cerr.rdbuf(err.rdbuf());
  try {
    body();
  } catch (...) {
    std::cout.rdbuf(old_out);
    std::cerr.rdbuf(old_err);
    throw;
  }
  std::cout.rdbuf(old_out);
  std::cerr.rdbuf(old_err);
  return {out.str(), err.str()};
}

// `ftsense calibrate` (its verb function, the same code): returns (exit status, stdout, stderr).
py::tuple calibrate(const std::vector<std::string>& args) {
  int status = 0;
  std::pair<std::string, std::string> text;
  {
    const py::gil_scoped_release unlocked;
    text = captured([&] { status = cli::calibrate_command(args, reference_context()); });
  }
  return py::make_tuple(status, text.first, text.second);
}

// `ftsense report`'s metrics (cli::make_report): (metrics.json text, the terminal table).
py::tuple make_report(const std::string& run, const std::string& truth, const std::string& out_dir, double warmup_s,
                 bool figures, const std::string& title) {
  cli::ReportOptions options;
  options.metrics.warmup_s = warmup_s;
  options.figures = figures;
  options.title = title;
  cli::Report r;
  {
    const py::gil_scoped_release unlocked;
    r = cli::make_report(run, truth, out_dir, options);
  }
  return py::make_tuple(r.json.dump(), r.table);
}

// A Python exception class ftsense.<name> deriving from `bases`, kept for the life of the
// process (the translator raises it; a static py::object would be released after Python is gone).
py::handle exception_class(py::module_& m, const char* name, const py::tuple& bases, const char* doc) {
  const std::string qualified = std::string("ftsense.") + name;
  py::object type = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr));
  if (!type) throw py::error_already_set();
  m.attr(name) = type;
  return type.release();
}

}  // namespace
}  // namespace ftsense::python

PYBIND11_MODULE(_ftsense, m) {
  using namespace ftsense;
  using namespace ftsense::python;
  m.doc() = "ftsense: fault-tolerant sensing pipelines (the compiled part; use the package ftsense)";

  static const py::handle error = exception_class(m, "Error", py::make_tuple(py::handle(PyExc_Exception)),
                                            "An ftsense error; str() is ftsense's message.");
  static const py::handle config_error = exception_class(
      m, "ConfigError", py::make_tuple(error, py::handle(PyExc_ValueError)),
      "A config problem: .problems lists (path, message) pairs, path a JSON Pointer (prefixed by the file).");
  static const py::handle log_error = exception_class(m, "LogError", py::make_tuple(error),
                                                "A log that cannot be read or run: \"file:line: what; what to do\".");
  static const py::handle output_error = exception_class(m, "OutputError", py::make_tuple(error, py::handle(PyExc_OSError)),
                                                   "An output file refused or not written.");
  static const py::handle usage_error = exception_class(m, "UsageError", py::make_tuple(error, py::handle(PyExc_ValueError)),
                                                  "An argument ftsense refuses (a missing file, a bad option value).");
  py::register_exception_translator([](std::exception_ptr p) {
    const auto raise = [](py::handle type, const std::string& message) { return type(message); };
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ConfigError& e) {
      py::object instance = raise(config_error, e.what());
      py::list problems;
      for (const Diagnostic& d : e.problems()) problems.append(py::make_tuple(d.path, d.message));
      instance.attr("problems") = problems;
      PyErr_SetObject(config_error.ptr(), instance.ptr());
    } catch (const io::LogError& e) {
      PyErr_SetObject(log_error.ptr(), raise(log_error, e.what()).ptr());
    } catch (const io::OutputError& e) {
      PyErr_SetObject(output_error.ptr(), raise(output_error, e.what()).ptr());
    } catch (const TextFileError& e) {
      PyErr_SetObject(usage_error.ptr(), raise(usage_error, e.what()).ptr());
    } catch (const cli::UsageError& e) {
      PyErr_SetObject(usage_error.ptr(), raise(usage_error, e.message).ptr());
    }
  });

  py::class_<Port>(m, "Port", "A pipeline input (input.<name>) or stage output (<stage>.<port>).")
      .def_readonly("name", &Port::name)
      .def_readonly("dim", &Port::dim)
      .def_readonly("unit", &Port::unit)
      .def_readonly("description", &Port::description)
      .def_readonly("columns", &Port::columns, "a pipeline input's log columns, one per value")
      .def("__repr__", [](const Port& p) {
        return "Port(" + p.name + ", dim=" + std::to_string(p.dim) + ", unit='" + p.unit + "')";
      });

  py::class_<PyPipeline>(m, "Pipeline")
      .def_static("from_file", &PyPipeline::from_file, py::arg("path"), py::arg("thresholds_path") = "")
      .def_static("from_json", &PyPipeline::from_json, py::arg("text"), py::arg("thresholds_text") = "",
                  py::arg("base_dir") = std::filesystem::path())
      .def_property_readonly("inputs", &PyPipeline::inputs)
      .def_property_readonly("outputs", &PyPipeline::outputs)
      .def_property_readonly("sample_period_s", &PyPipeline::sample_period_s)
      .def_property_readonly("time_column", &PyPipeline::time_column)
      .def_property_readonly("source", &PyPipeline::source)
      .def_property_readonly("warnings", &PyPipeline::warnings)
      .def_property_readonly("channels", &PyPipeline::channels)
      .def_property_readonly("columns", &PyPipeline::columns)
      .def_property_readonly("monitor", &PyPipeline::monitor)
      .def("values", &PyPipeline::values, py::arg("name"))
      .def("reset", &PyPipeline::reset)
      .def("step", &PyPipeline::step, py::arg("time_s"), py::arg("inputs"), py::arg("outputs") = py::none())
      .def("run", &PyPipeline::run, py::arg("inputs"), py::arg("time") = py::none(),
           py::arg("outputs") = py::none(), py::arg("reset") = true)
      .def("run_table", &PyPipeline::run_table, py::arg("inputs"), py::arg("time") = py::none(),
           py::arg("reset") = true)
      .def("run_log", &PyPipeline::run_log, py::arg("path"), py::arg("gap_reset_periods") = 10.0,
           py::arg("output") = "")
      .def("read_log", [](const PyPipeline& p, const std::string& path) { return read_log(path, p.time()); },
           py::arg("path"));

  // The fault type table (fault_type.hpp): the codes in a run's <channel>/fault_type column.
  py::list fault_types;
  for (const FaultTypeInfo& row : kFaultTypes) {
    fault_types.append(py::make_tuple(static_cast<int>(row.type), std::string(row.name), std::string(row.model)));
  }
  m.attr("fault_types") = fault_types;

  m.def("read_log", [](const std::string& path) { return read_log(path, io::TimeColumn{}); }, py::arg("path"));
  m.def("calibrate", &calibrate, py::arg("args"));
  m.def("report", &make_report, py::arg("run"), py::arg("truth"), py::arg("out_dir"), py::arg("warmup_s"),
        py::arg("figures"), py::arg("title"));
}
