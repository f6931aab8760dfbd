#pragma once
// The pipeline config document, described once.
//
// Its sections and keys live in one table (pipeline_document_sections()); the reader below
// checks a document against it (unknown keys, missing required keys, types) and the config
// reference (docs/config_reference.md) is generated from it, like plugin parameters from their
// `describe`. The monitor's wires are the rows of kMonitorColumns (monitor_columns.hpp).
//
//   {
//     "sample_period_s": 0.001,                                   tick period T [s]
//     "inputs": { "<name>": { "columns": [...], "unit": "N", "derived_from": [...] }, ... },
//     "stages": [ { "name": "...", "plugin": "...", "params": {...},
//                   "inputs": { "<port>": "<wire>", ... } }, ... ],
//     "monitor": { "channels": [...], "<monitor column key>": "<wire>", ..., "extra": {...} },
//     "previous_tick": { "<name>": { "signal": "<stage>.<port>", "dim": 8, "unit": "N" }, ... },
//     "allow_dependent_virtual_sensor": false
//   }
//
// A wire is "input.<name>", "<stage>.<port>" or "previous_tick.<name>", or a non-empty array of
// them concatenated in order. "previous_tick.<name>" is what its signal held at the end of the
// tick before (its `initial` value before the first): the one way a stage reads what a later
// stage computes, so a loop (recovered values fed back into the virtual sensors) has a delay by
// construction and the run order stays a dependency order. Reading resolves every name the document itself defines (inputs, stages); what only
// the plugins know (ports, dimensions, units, parameters) is the builder's to check.

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ftsense/diagnostics.hpp"
#include "ftsense/monitor_columns.hpp"
#include "ftsense/params.hpp"

namespace ftsense {

// The JSON type a key takes.
// `wires`: an object whose every value is a wire (a stage's inputs, the monitor's extra).
enum class DocumentValue { number, boolean, text, object, array, text_list, wire, wires, range, numbers };
// As users read it: "number", "array of strings", "wire", ...
[[nodiscard]] std::string_view to_string(DocumentValue value) noexcept;
// Whether `value` has the JSON type (a wire: a string or a non-empty array of strings).
[[nodiscard]] bool has_type(const Json& value, DocumentValue type) noexcept;

// One key of a document section, as users read it.
struct DocumentKey {
  std::string key;
  DocumentValue type;
  bool required;
  std::string default_value;  // JSON text of the default of an optional key; empty: none
  std::string rule;           // beyond the type: "> 0", "non-empty", "unique identifier", ...
  std::string meaning;        // what it is; also the hint of "missing required key (...)"
  std::optional<PlausibleRange> plausible = std::nullopt;  // numbers: outside it is a warning
};

struct DocumentSection {
  std::string path;   // "", "inputs/<name>", "stages/<i>", "monitor"
  std::string what;   // "the pipeline config", "an input", ... (in messages)
  std::string intro;  // a sentence for the reference; may be empty
  std::vector<DocumentKey> keys;

  [[nodiscard]] const DocumentKey& at(std::string_view key) const;  // a described key
  [[nodiscard]] std::vector<std::string> key_names() const;
};

enum class DocumentSectionId : std::size_t { pipeline, input, stage, monitor, time, previous_tick };
// Every section of the document, in DocumentSectionId order.
[[nodiscard]] const std::vector<DocumentSection>& pipeline_document_sections();
[[nodiscard]] const DocumentSection& document_section(DocumentSectionId id);

// One element of a wire: "input.<name>", "<stage>.<port>" or "previous_tick.<name>", optionally
// followed by a selection
// of its values, "[i]" or "[i:j]" (0-based, j excluded, as in Python): "imu.acc[2]".
struct WireEnd {
  std::string text;          // as written
  std::string signal;        // the text without the selection: "<node>.<port>"
  std::optional<std::array<std::size_t, 2>> select;  // [first, last) of the signal's values
  std::string node;          // "input" or a stage name
  std::string port;          // input name or output port name
  std::string path;          // its JSON Pointer
  bool from_input = false;
  bool from_previous_tick = false;  // "previous_tick.<name>" (the builder finds it by `signal`)
  std::size_t producer = 0;  // index into PipelineDocument::stages when from neither
};

// The form of one wire element as an ECMAScript regular expression (for the config schema):
// an identifier, a dot, an identifier, optionally "[i]" or "[i:j]" (indices of at most 6 digits).
// The reader also demands i < j and names it knows; a test holds the two to the same form.
inline constexpr std::string_view kWireEndPattern =
    R"(^[A-Za-z_][A-Za-z0-9_]*\.[A-Za-z_][A-Za-z0-9_]*(\[[0-9]{1,6}(:[0-9]{1,6})?\])?$)";

struct WireDecl {
  std::string port;  // the consuming port (stage input, monitor column key or extra name)
  std::string path;  // JSON Pointer of the wire
  std::vector<WireEnd> ends;
};

struct InputDecl {
  std::string name;
  std::vector<std::string> columns;       // log column names, one per value
  std::string unit;
  std::vector<std::string> derived_from;  // other inputs this one is computed from
  std::optional<std::array<double, 2>> plausible_range;  // [min, max]; values outside read as missing
  // value = scale * logged + offset, one coefficient per column (raw counts to the unit).
  std::vector<double> scale;
  std::vector<double> offset;
};

// The units the time column may be written in (`time.unit`), and their length in seconds.
inline constexpr std::array<std::pair<std::string_view, double>, 4> kTimeUnits{
    {{"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}, {"ns", 1e-9}}};

// The log's time column: its name and unit; the reader converts it to seconds.
struct TimeColumnDecl {
  std::string column = "time_s";
  std::string unit = "s";
  double seconds_per_unit = 1.0;
};

struct StageDecl {
  std::string name;
  std::string path;            // "/stages/<i>"
  std::string plugin;          // empty when missing or not a string (reported)
  Json params = Json::object();
  std::vector<WireDecl> wires;
  bool ok = true;              // false: reported, not to be built
  std::vector<std::size_t> upstream;  // stages its wires read, sorted, unique
};

struct MonitorDecl {
  std::vector<std::string> channels;
  std::array<std::optional<WireDecl>, kMonitorColumnCount> columns;  // empty: missing or bad (reported)
  std::vector<WireDecl> extra;
  bool ok = true;  // false: some part is reported; the monitor is not built
};

// A signal read one tick late: "previous_tick.<name>" holds what `signal` held at the end of the
// tick before. Its size and unit are declared, since the stages that read it are built before
// the one that computes it; the builder checks them against the signal.
struct PreviousTickDecl {
  std::string name;
  std::string path;  // "/previous_tick/<name>"
  WireEnd signal;    // "<stage>.<port>" or "input.<name>", optionally with a selection
  std::size_t dim = 0;
  std::string unit;
  double initial = 0.0;  // its value before the first tick, and after reset()
};

struct PipelineDocument {
  std::optional<double> sample_period_s;  // empty: missing or invalid (reported)
  TimeColumnDecl time;
  bool allow_dependent_virtual_sensor = false;
  std::vector<InputDecl> inputs;  // the well-declared ones (a broken one is reported, not here)
  std::vector<StageDecl> stages;
  std::optional<MonitorDecl> monitor;
  std::vector<PreviousTickDecl> previous_tick;  // the well-declared ones
};

// Reads `config` against the document's table: every problem goes to `diag` with its JSON
// Pointer; what is readable is returned, so the builder can report further problems at once.
[[nodiscard]] PipelineDocument read_pipeline_document(const Json& config, Diagnostics& diag);

// True for names made of letters, digits and '_' that do not start with a digit.
[[nodiscard]] bool is_identifier(std::string_view s) noexcept;

}  // namespace ftsense
