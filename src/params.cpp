#include "ftsense/params.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

namespace ftsense {

std::string_view to_string(ParamKind kind) {
  switch (kind) {
    case ParamKind::number: return "number";
    case ParamKind::integer: return "integer";
    case ParamKind::boolean: return "boolean";
    case ParamKind::text: return "string";
    case ParamKind::choice: return "choice";
    case ParamKind::number_list: return "array of numbers";
    case ParamKind::point_list: return "array of [x, y] points";
    case ParamKind::text_list: return "array of strings";
  }
  return "?";
}

std::string ParamInfo::rule() const {
  std::string out;
  if (kind == ParamKind::choice) {
    out = "one of: ";
    for (std::size_t i = 0; i < choices.size(); ++i) out += (i ? ", " : "") + choices[i];
    return out;
  }
  if (lower) out += std::string(lower->inclusive ? ">= " : "> ") + format_number(lower->value);
  if (upper) {
    if (!out.empty()) out += " and ";
    out += std::string(upper->inclusive ? "<= " : "< ") + format_number(upper->value);
  }
  const bool list = kind == ParamKind::number_list || kind == ParamKind::point_list ||
                    kind == ParamKind::text_list;
  if (list && !out.empty()) out = "each " + out;
  if (list && (min_count > 0 || max_count != std::numeric_limits<std::size_t>::max())) {
    if (!out.empty()) out += "; ";
    if (min_count == max_count) {
      out += "exactly " + std::to_string(min_count) + " entries";
    } else {
      if (min_count > 0) out += "at least " + std::to_string(min_count) + " entries";
      if (max_count != std::numeric_limits<std::size_t>::max()) {
        if (min_count > 0) out += ", ";
        out += "at most " + std::to_string(max_count) + " entries";
      }
    }
  }
  return out;
}

std::string ParamInfo::what() const {
  return "(" + description + (unit.empty() ? "" : ", " + unit) + ")";
}

std::string PlausibleRange::text(std::string_view unit) const {
  std::string out = format_number(low);
  out.append(" .. ").append(format_number(high));
  if (!unit.empty()) out.append(" ").append(unit);
  if (!reason.empty()) out.append(" (").append(reason).append(")");
  return out;
}

void check_plausible(const PlausibleRange& range, std::string_view unit, double value, const Json& raw,
                     const std::string& path, Diagnostics& diag) {
  if (value >= range.low && value <= range.high) return;
  diag.warning(path, " = " + detail::abbreviated_dump(raw) + " is outside the plausible range " + range.text(unit) +
                         "; check the unit or the value");
}

namespace detail {

std::string abbreviated_dump(const Json& value) {
  std::string s = value.dump();
  constexpr std::size_t kMax = 60;
  if (s.size() > kMax) s = s.substr(0, kMax - 3) + "...";
  return s;
}

void report_type(const ParamInfo& info, const Json& raw, std::string_view expected,
                 const std::string& path, Diagnostics& diag) {
  diag.error(path, " = " + abbreviated_dump(raw) + " has type " + raw.type_name() + ", expected " +
                       std::string(expected) + " " + info.what());
}

void check_number(const ParamInfo& info, double value, const Json& raw, const std::string& path,
                  Diagnostics& diag) {
  const bool below = info.lower && (info.lower->inclusive ? value < info.lower->value
                                                          : value <= info.lower->value);
  const bool above = info.upper && (info.upper->inclusive ? value > info.upper->value
                                                          : value >= info.upper->value);
  if (below || above || !std::isfinite(value)) {
    std::string rule;
    if (info.lower) rule += std::string(info.lower->inclusive ? ">= " : "> ") + format_number(info.lower->value);
    if (info.upper) {
      if (!rule.empty()) rule += " and ";
      rule += std::string(info.upper->inclusive ? "<= " : "< ") + format_number(info.upper->value);
    }
    if (rule.empty()) rule = "a finite number";
    diag.error(path, " = " + abbreviated_dump(raw) + " violates " + rule + " " + info.what());
  }
}

bool read_number(const ParamInfo& info, const Json& raw, const std::string& path, Diagnostics& diag,
                 double& out) {
  if (!raw.is_number()) {
    report_type(info, raw, "number", path, diag);
    return false;
  }
  const double v = raw.get<double>();
  const std::size_t before = diag.errors().size();
  check_number(info, v, raw, path, diag);
  if (diag.errors().size() != before) return false;
  if (info.plausible) check_plausible(*info.plausible, info.unit, v, raw, path, diag);
  out = v;
  return true;
}

bool read_integer(const ParamInfo& info, const Json& raw, const std::string& path,
                  Diagnostics& diag, long long& out) {
  if (!raw.is_number_integer()) {
    report_type(info, raw, "integer", path, diag);
    return false;
  }
  // get<long long>() wraps unsigned values above its range (2^64 - 1 would read as -1).
  if (raw.is_number_unsigned() &&
      raw.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<long long>::max())) {
    diag.error(path, " = " + raw.dump() + " violates the range of a 64-bit integer " + info.what());
    return false;
  }
  const long long v = raw.get<long long>();
  const std::size_t before = diag.errors().size();
  check_number(info, static_cast<double>(v), raw, path, diag);
  if (diag.errors().size() != before) return false;
  if (info.plausible) check_plausible(*info.plausible, info.unit, static_cast<double>(v), raw, path, diag);
  out = v;
  return true;
}

bool check_count(const ParamInfo& info, const Json& raw, const std::string& path,
                 Diagnostics& diag) {
  if (raw.size() < info.min_count || raw.size() > info.max_count) {
    std::string rule;
    if (info.min_count == info.max_count) {
      rule = "exactly " + std::to_string(info.min_count) + " entries";
    } else if (raw.size() < info.min_count) {
      rule = "at least " + std::to_string(info.min_count) + " entries";
    } else {
      rule = "at most " + std::to_string(info.max_count) + " entries";
    }
    diag.error(path, " = " + abbreviated_dump(raw) + " (" + std::to_string(raw.size()) +
                         " entries) violates " + rule + " " + info.what());
    return false;
  }
  return true;
}

}  // namespace detail
}  // namespace ftsense
