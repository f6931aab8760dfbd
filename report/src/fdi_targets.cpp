#include "ftsense/report/fdi_targets.hpp"

#include <cmath>
#include <optional>
#include <sstream>

#include "ftsense/report/writers.hpp"  // fixed()

namespace ftsense::report {

namespace {

// A number field of a channel's metrics; nullopt when absent or null (not measured).
std::optional<double> field(const Json& channel, const char* key) {
  const auto it = channel.find(key);
  if (it == channel.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

// A true/false field; false when absent or null.
bool flag(const Json& channel, const char* key) {
  const auto it = channel.find(key);
  return it != channel.end() && it->is_boolean() && it->get<bool>();
}

std::string text(const Json& channel, const char* key) {
  const auto it = channel.find(key);
  return it != channel.end() && it->is_string() ? it->get<std::string>() : "-";
}

// "run channel (type size)": which fault a shortfall is about.
std::string fault_name(const std::string& run, const Json& channel, bool with_size) {
  std::string name = run + " " + text(channel, "channel") + " (" + text(channel, "injected_type");
  if (with_size) {
    if (const auto size = field(channel, "fault_size")) {
      name += ' ';
      name += fixed(*size, 0);
    }
  }
  return name + ")";
}

TargetCheck named(std::string target) {
  TargetCheck check;
  check.target = std::move(target);
  return check;
}

void count(TargetCheck& check, bool met, const std::string& shortfall) {
  ++check.checked;
  if (met) ++check.met;
  else check.shortfalls.push_back(shortfall);
}

}  // namespace

std::vector<TargetCheck> check_targets(const std::vector<ScoredRunMetrics>& runs, const FdiTargets& targets) {
  const std::string& unit = targets.unit;
  TargetCheck detect = named("offsets of " + fixed(targets.offset_min, 0) + " " + unit +
                             " or more and frozen channels detected within " + fixed(targets.detect_loaded_s, 2) +
                             " s of loaded time");
  std::ostringstream drift_text;
  drift_text << "drifts detected within the earlier limits (";
  for (std::size_t i = 0; i < targets.drift_limits.size(); ++i) {
    const DriftLimit& l = targets.drift_limits[i];
    drift_text << (i ? ", " : "") << fixed(l.min_slope_per_s, 0) << " " << unit << "/s within " << fixed(l.delay_s, 0)
               << " s";
  }
  TargetCheck drift = named(drift_text.str() + ")");
  TargetCheck type = named("fault type shown right for at least " + fixed(100.0 * targets.type_right_share, 0) +
                           " % of faulty channels");
  TargetCheck recovered = named("recovered RMSE at most " + fixed(targets.recovered_rmse, 0) + " " + unit +
                                " on faulty channels");
  TargetCheck readmitted = named("re-admitted within " + fixed(targets.readmission_s, 2) + " s after a fault ends");
  TargetCheck quiet = named("no false alarm on fault-free runs");
  TargetCheck quiet_faulty =
      named("no false alarm on runs with faults (outside each fault and its re-admission grace)");

  for (const ScoredRunMetrics& run : runs) {
    const Json summary = run.metrics.value("summary", Json::object());
    const auto alarms = field(summary, "false_alarms_after_warmup");  // absent: not scored
    const Json channels = run.metrics.value("channels", Json::array());
    int faulty = 0;
    for (const Json& c : channels) {
      const std::string injected = text(c, "injected_type");
      if (injected == "-") continue;
      ++faulty;
      const auto delay = field(c, "detection_delay_s");
      const auto loaded = field(c, "loaded_delay_s");
      const auto size = field(c, "fault_size");
      if (injected == "frozen" || (injected == "offset" && size && *size >= targets.offset_min)) {
        count(detect, loaded && *loaded <= targets.detect_loaded_s,
              fault_name(run.name, c, injected == "offset") + ": " + (loaded ? fixed(*loaded, 3) + " s" : "missed"));
      }
      if (injected == "drift") {
        const double rate = std::abs(field(c, "fault_slope_per_s").value_or(0.0));
        for (const DriftLimit& l : targets.drift_limits) {
          if (rate < l.min_slope_per_s) continue;
          count(drift, delay && *delay <= l.delay_s,
                fault_name(run.name, c, false) + " " + fixed(rate, 1) + " " + unit + "/s: " +
                    (delay ? fixed(*delay, 3) + " s" : "missed") + " (limit " + fixed(l.delay_s, 0) + " s)");
          break;
        }
      }
      count(type, flag(c, "type_correct"),
            fault_name(run.name, c, false) + ": shown " + text(c, "shown_type"));
      if (const auto rmse = field(c, "recovered_rmse")) {
        count(recovered, *rmse <= targets.recovered_rmse,
              fault_name(run.name, c, false) + ": " + fixed(*rmse, 1) + " " + unit);
      }
      if (delay && flag(c, "fault_ended")) {
        const auto readmission = field(c, "readmission_s");
        count(readmitted, readmission && *readmission <= targets.readmission_s,
              fault_name(run.name, c, false) + ": " + (readmission ? fixed(*readmission, 3) + " s" : "never"));
      }
    }
    if (alarms) {
      count(faulty == 0 ? quiet : quiet_faulty, *alarms == 0.0,
            run.name + ": " + std::to_string(static_cast<long long>(*alarms)));
    }
  }
  for (TargetCheck* c : {&detect, &drift, &recovered, &readmitted, &quiet, &quiet_faulty}) c->passed = c->met == c->checked;
  type.passed = type.checked == 0 || type.met >= targets.type_right_share * type.checked;
  return {detect, drift, type, recovered, readmitted, quiet, quiet_faulty};
}

std::string shortfall_text(const TargetCheck& check) {
  std::string misses;
  for (const std::string& s : check.shortfalls) {
    if (!misses.empty()) misses += "; ";
    misses += s;
  }
  return misses.empty() ? "-" : misses;
}

Table targets_table(const std::vector<TargetCheck>& checks) {
  Table t{{"target", "applies to", "met", "holds", "shortfall (measured)"}, {}};
  for (const TargetCheck& c : checks) {
    t.rows.push_back(
        {c.target, std::to_string(c.checked), std::to_string(c.met), c.passed ? "yes" : "no", shortfall_text(c)});
  }
  return t;
}

}  // namespace ftsense::report
