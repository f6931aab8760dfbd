#pragma once
// The monitor's per-channel columns, described once (design.md "the user-facing contract").
//
// For every monitored channel c, `ftsense run` writes after `time_s`, in the order of
// kMonitorColumns:
//   c/measured_<u>        y      the sensor's reading                        [u]
//   c/virtual_<u>         y_v    the virtual sensor's estimate of it         [u]
//   c/fault_estimate_<u>  f^     the estimated fault, y = x + f              [u]
//   c/recovered_<u>       x^     the recovered signal handed on              [u]
//   c/fault               0/1    1 while the channel is flagged faulty       [1]
//   c/fault_type          code   FaultType code (fault_type.hpp)             [1]
//   c/cannot_judge        0/1    1 while the channel cannot be judged: its    [1]
//                                virtual sensor is not ready, or a fault no
//                                channel can be singled out for (optional
//                                wire; without one, 1 where virtual is not
//                                finite)
// then the monitor's optional `extra` signals as c/<name>_<unit> (no suffix when dimensionless).
// <u> is the unit of the measured signal. The config's `monitor` object has one wire per row
// (its key), the pipeline stores one SignalRef per row, `run` writes its header and rows from
// this table, `report` reads a run's output by it, and the config reference is generated from it.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace ftsense {

enum class MonitorColumn : std::size_t {
  measured, virtual_value, fault_estimate, recovered, fault, fault_type, cannot_judge };

struct MonitorColumnInfo {
  MonitorColumn column;
  std::string_view key;      // the monitor config key, and the column name after "<channel>/"
  bool in_signal_unit;       // the column name ends in "_<unit of the measured signal>"
  std::string_view meaning;  // for the config reference
  bool required = true;      // a monitor must wire it; an optional one has a derived default
};

inline constexpr std::array<MonitorColumnInfo, 7> kMonitorColumns{{
    {MonitorColumn::measured, "measured", true, "the sensor's reading"},
    {MonitorColumn::virtual_value, "virtual", true, "the virtual sensor's estimate of the reading"},
    {MonitorColumn::fault_estimate, "fault_estimate", true, "the estimated fault f in y = x + f"},
    {MonitorColumn::recovered, "recovered", true, "the recovered signal handed to the controller"},
    {MonitorColumn::fault, "fault", false, "1 while the channel is flagged faulty, else 0"},
    {MonitorColumn::fault_type, "fault_type", false, "the fault type code (docs/architecture.md)"},
    {MonitorColumn::cannot_judge, "cannot_judge", false,
     "1 while the channel cannot be judged: its virtual sensor is not ready, or a fault no channel can be "
     "singled out for; optional, without a wire 1 where the virtual value is not finite",
     false},
}};
inline constexpr std::size_t kMonitorColumnCount = kMonitorColumns.size();

[[nodiscard]] constexpr const MonitorColumnInfo& monitor_column_info(MonitorColumn column) noexcept {
  return kMonitorColumns[static_cast<std::size_t>(column)];
}

// "<channel>/<key>" plus "_<unit>" for the columns in the signal's unit: "l_foot/p1/measured_N".
[[nodiscard]] std::string monitor_column_name(std::string_view channel, const MonitorColumnInfo& column,
                                              std::string_view unit);
// The name of a monitor `extra` signal's column: "<channel>/<name>_<unit>", no suffix when the
// unit is dimensionless ("1").
[[nodiscard]] std::string extra_column_name(std::string_view channel, std::string_view name,
                                            std::string_view unit);

// Why `name` cannot prefix CSV column names (a comma, a quote, a control character such as a
// newline or NUL, or spaces at either end, which CSV readers trim), or empty when it can.
[[nodiscard]] std::string column_name_problem(std::string_view name);

// Reads a column name back: the channel and the monitor column it names, when `name` is
// "<channel>/<key>" (with "_<unit>" for the columns in the signal's unit); nullopt otherwise.
struct ParsedMonitorColumn {
  std::string channel;
  MonitorColumn column;
};
[[nodiscard]] std::optional<ParsedMonitorColumn> parse_monitor_column(std::string_view name,
                                                                      std::string_view unit);

}  // namespace ftsense
