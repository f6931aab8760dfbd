#include "ftsense/monitor_columns.hpp"

namespace ftsense {

static_assert([] {
  for (std::size_t i = 0; i < kMonitorColumns.size(); ++i) {
    if (static_cast<std::size_t>(kMonitorColumns[i].column) != i) return false;
  }
  return true;
}(), "kMonitorColumns lists the MonitorColumn values in enum order");

std::string monitor_column_name(std::string_view channel, const MonitorColumnInfo& column, std::string_view unit) {
  std::string name(channel);
  name += '/';
  name += column.key;
  if (column.in_signal_unit) {
    name += '_';
    name += unit;
  }
  return name;
}

std::string extra_column_name(std::string_view channel, std::string_view name, std::string_view unit) {
  std::string out(channel);
  out += '/';
  out += name;
  if (unit != "1") {
    out += '_';
    out += unit;
  }
  return out;
}

std::string column_name_problem(std::string_view name) {
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (c == ',') return "contains a comma, which splits a CSV column";
    if (c == '"') return "contains a quote, which CSV readers take as quoting";
    if (u < 0x20 || u == 0x7f) return "contains a control character (a newline, tab or NUL byte)";
  }
  if (!name.empty() && (name.front() == ' ' || name.back() == ' ')) {
    return "starts or ends with a space, which CSV readers trim";
  }
  return {};
}

std::optional<ParsedMonitorColumn> parse_monitor_column(std::string_view name, std::string_view unit) {
  for (const MonitorColumnInfo& column : kMonitorColumns) {
    std::string tail = "/";
    tail += column.key;
    if (column.in_signal_unit) {
      tail += '_';
      tail += unit;
    }
    if (name.size() > tail.size() && name.substr(name.size() - tail.size()) == tail) {
      return ParsedMonitorColumn{std::string(name.substr(0, name.size() - tail.size())), column.column};
    }
  }
  return std::nullopt;
}

}  // namespace ftsense
