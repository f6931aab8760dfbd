#include "ftsense/sim/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "ftsense/json_text.hpp"
#include "ftsense/text_file.hpp"

namespace ftsense::sim {

namespace {

using nlohmann::json;

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
  return s;
}

std::string type_name(const json& j) {
  if (j.is_number_integer() || j.is_number_unsigned() || j.is_number_float()) return "number";
  return j.type_name();
}

std::string fmt(double x) {
  std::ostringstream o;
  o.imbue(std::locale::classic());
  o << x;
  return o.str();
}

struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;
  [[nodiscard]] bool contains(double x) const {
    return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
  [[nodiscard]] std::string describe() const {
    std::vector<std::string> parts;
    if (std::isfinite(lo)) parts.push_back((lo_open ? "> " : ">= ") + fmt(lo));
    if (std::isfinite(hi)) parts.push_back((hi_open ? "< " : "<= ") + fmt(hi));
    return join(parts, " and ");
  }
};
Range closed(double lo, double hi) { return {lo, hi, false, false}; }
Range positive(double hi = std::numeric_limits<double>::infinity()) { return {0.0, hi, true, false}; }

/// Reads one JSON object, remembering which keys were used and collecting problems.
class ObjectReader {
 public:
  ObjectReader(const json& j, std::string path, std::vector<std::string>& errors)
      : j_(j), path_(std::move(path)), errors_(errors) {}

  [[nodiscard]] std::string at(const std::string& key) const { return path_ + "/" + key; }

  const json* find(const std::string& key, bool required, const char* expected) {
    allowed_.push_back(key);
    auto it = j_.find(key);
    if (it == j_.end()) {
      if (required) errors_.push_back(at(key) + " is missing (required " + expected + ")");
      return nullptr;
    }
    return &*it;
  }

  void number(const std::string& key, double& out, bool required, Range r) {
    const json* v = find(key, required, "number");
    if (!v) return;
    if (!v->is_number()) {
      errors_.push_back(at(key) + " = " + v->dump() + " has type " + type_name(*v) + ", expected number");
      return;
    }
    const double x = v->get<double>();
    if (!r.contains(x)) {
      errors_.push_back(at(key) + " = " + v->dump() + " is out of range, expected " + r.describe());
      return;
    }
    out = x;
  }
  void number(const std::string& key, std::optional<double>& out, Range r) {
    double x = 0.0;
    const std::size_t before = errors_.size();
    if (j_.contains(key)) {
      number(key, x, false, r);
      if (errors_.size() == before) out = x;
    } else {
      allowed_.push_back(key);
    }
  }
  void integer(const std::string& key, std::int64_t& out, bool required, std::int64_t lo,
               std::int64_t hi) {
    const json* v = find(key, required, "integer");
    if (!v) return;
    if (!v->is_number_integer()) {
      errors_.push_back(at(key) + " = " + v->dump() + " has type " +
                        (v->is_number() ? std::string("non-integer number") : type_name(*v)) +
                        ", expected integer");
      return;
    }
    const bool too_big = v->is_number_unsigned() && v->get<std::uint64_t>() > static_cast<std::uint64_t>(hi);
    const std::int64_t x = too_big ? hi : v->get<std::int64_t>();
    if (too_big || x < lo || x > hi) {
      errors_.push_back(at(key) + " = " + v->dump() + " is out of range, expected >= " +
                        std::to_string(lo) + " and <= " + std::to_string(hi));
      return;
    }
    out = x;
  }
  void string(const std::string& key, std::string& out, bool required) {
    const json* v = find(key, required, "string");
    if (!v) return;
    if (!v->is_string()) {
      errors_.push_back(at(key) + " = " + v->dump() + " has type " + type_name(*v) + ", expected string");
      return;
    }
    out = v->get<std::string>();
  }
  /// Returns the value if it is a string among `choices`, else records a problem (absent and
  /// not required: nullopt, no problem).
  std::optional<std::string> choice(const std::string& key, const std::vector<std::string_view>& choices,
                                    bool required = true) {
    std::string s;
    const std::size_t before = errors_.size();
    string(key, s, required);
    if (errors_.size() != before || !j_.contains(key)) return std::nullopt;
    if (std::find(choices.begin(), choices.end(), s) == choices.end()) {
      std::vector<std::string> c(choices.begin(), choices.end());
      errors_.push_back(at(key) + " = " + ftsense::detail::abbreviated_dump(j_.at(key)) + " is not one of: " + join(c, ", "));
      return std::nullopt;
    }
    return s;
  }
  void vec3(const std::string& key, std::array<double, 3>& out, Range r) {
    const json* v = find(key, false, "array of 3 numbers");
    if (!v) return;
    if (!v->is_array() || v->size() != 3) {
      errors_.push_back(at(key) + " = " + v->dump() + " has type " + type_name(*v) +
                        (v->is_array() ? " of size " + std::to_string(v->size()) : std::string()) +
                        ", expected array of 3 numbers");
      return;
    }
    for (std::size_t i = 0; i < 3; ++i) {
      const json& e = (*v)[i];
      const std::string p = at(key) + "/" + std::to_string(i);
      if (!e.is_number()) {
        errors_.push_back(p + " = " + ftsense::detail::abbreviated_dump(e) + " has type " + type_name(e) + ", expected number");
      } else if (!r.contains(e.get<double>())) {
        errors_.push_back(p + " = " + ftsense::detail::abbreviated_dump(e) + " is out of range, expected " + r.describe());
      } else {
        out[i] = e.get<double>();
      }
    }
  }
  /// Object member: returns nullptr (and records a problem) if present but not an object.
  const json* object(const std::string& key, bool required) {
    const json* v = find(key, required, "object");
    if (v && !v->is_object()) {
      errors_.push_back(at(key) + " = " + v->dump() + " has type " + type_name(*v) + ", expected object");
      return nullptr;
    }
    return v;
  }
  const json* array(const std::string& key, bool required) {
    const json* v = find(key, required, "array");
    if (v && !v->is_array()) {
      errors_.push_back(at(key) + " = " + v->dump() + " has type " + type_name(*v) + ", expected array");
      return nullptr;
    }
    return v;
  }
  /// Reports every key that no accessor asked for.
  void finish() {
    for (auto it = j_.begin(); it != j_.end(); ++it) {
      if (std::find(allowed_.begin(), allowed_.end(), it.key()) == allowed_.end()) {
        std::vector<std::string> allowed(allowed_.begin(), allowed_.end());
        std::sort(allowed.begin(), allowed.end());
        errors_.push_back(at(it.key()) + " = " + ftsense::detail::abbreviated_dump(it.value()) +
                          " is not a known key (allowed here: " + join(allowed, ", ") + ")");
      }
    }
  }

 private:
  const json& j_;
  std::string path_;
  std::vector<std::string>& errors_;
  std::vector<std::string> allowed_;
};

// The biped's build (sim/README.md "body"): its size and mass. A robot of another mass keeps the
// default's proportions: every segment's mass scales with the total, so the trunk keeps its share.
void read_body(const json& j, const std::string& path, RobotParams& p, std::vector<std::string>& e) {
  ObjectReader r(j, path, e);
  double mass = p.total_mass_kg;
  r.number("total_mass_kg", mass, false, closed(30.0, 250.0));
  r.number("upper_leg_m", p.upper_leg_m, false, closed(0.15, 0.45));
  r.number("lower_leg_m", p.lower_leg_m, false, closed(0.15, 0.45));
  r.number("sole_ankle_m", p.sole_ankle_m, false, closed(0.05, 0.20));
  r.number("foot_length_m", p.foot_length_m, false, closed(0.12, 0.36));
  r.number("foot_width_m", p.foot_width_m, false, closed(0.07, 0.22));
  r.finish();
  const double scale = mass / p.total_mass_kg;
  p.total_mass_kg = mass;
  for (double* m : {&p.hip_yaw_link_kg, &p.hip_roll_link_kg, &p.thigh_kg, &p.shank_kg, &p.ankle_link_kg, &p.foot_kg,
                    &p.pad_kg})
    *m *= scale;
}

// `leg_scale`: the robot's leg length (hip to sole, straight) over the default's, which the
// pelvis height's default and range follow.
void read_gait(const json& j, const std::string& path, GaitParams& g, double leg_scale, std::vector<std::string>& e) {
  ObjectReader r(j, path, e);
  g.pelvis_height_m *= leg_scale;
  r.number("step_length_m", g.step_length_m, true, closed(0.0, 0.30));
  r.number("step_time_s", g.step_time_s, true, closed(0.5, 3.0));
  r.number("double_support_ratio", g.double_support_ratio, true, closed(0.05, 0.8));
  std::int64_t n = g.num_steps;
  r.integer("num_steps", n, false, 0, 10000);
  g.num_steps = static_cast<int>(n);
  r.number("step_height_m", g.step_height_m, false, closed(0.0, 0.12));
  r.number("initial_stand_s", g.initial_stand_s, false, closed(0.5, 60.0));
  r.number("pelvis_height_m", g.pelvis_height_m, false, closed(0.50 * leg_scale, 0.64 * leg_scale));
  r.number("preview_s", g.preview_s, false, closed(0.5, 3.0));
  r.number("foot_half_spacing_m", g.foot_half_spacing_m, false, closed(0.08, 0.15));
  r.number("com_feedback_gain", g.com_feedback_gain, false, closed(0.0, 10.0));
  r.number("com_feedback_integral_gain_1_s", g.com_feedback_integral_gain_1_s, false, closed(0.0, 20.0));
  r.finish();
}

void read_crawl(const json& j, const std::string& path, CrawlParams& g, std::vector<std::string>& e) {
  ObjectReader r(j, path, e);
  r.number("stride_m", g.stride_m, false, closed(0.0, 0.15));
  r.number("cycle_s", g.cycle_s, false, closed(2.0, 60.0));
  r.number("swing_ratio", g.swing_ratio, false, closed(0.2, 0.8));
  r.number("step_height_m", g.step_height_m, false, closed(0.0, 0.10));
  r.number("body_height_m", g.body_height_m, false, closed(0.22, 0.36));
  r.number("stance_half_width_m", g.stance_half_width_m, false, closed(0.08, 0.20));
  r.number("stability_margin_m", g.stability_margin_m, false, closed(0.0, 0.05));
  r.number("initial_stand_s", g.initial_stand_s, false, closed(0.5, 60.0));
  std::int64_t n = g.num_cycles;
  r.integer("num_cycles", n, false, 0, 10000);
  g.num_cycles = static_cast<int>(n);
  r.finish();
}

void read_sensors(const json& j, const std::string& path, SensorParams& s, std::vector<std::string>& e) {
  ObjectReader r(j, path, e);
  if (const json* f = r.object("force", false)) {
    ObjectReader rf(*f, r.at("force"), e);
    rf.number("noise_std_N", s.force_noise_std_N, false, closed(0.0, 1000.0));
    rf.number("resolution_N", s.force_resolution_N, false, closed(0.0, 1000.0));
    rf.number("zero_below_N", s.force_zero_below_N, closed(0.0, 1000.0));
    rf.finish();
  }
  if (const json* f = r.object("imu", false)) {
    ObjectReader ri(*f, r.at("imu"), e);
    ri.number("acc_noise_std_m_s2", s.acc_noise_std_m_s2, false, closed(0.0, 100.0));
    ri.vec3("acc_bias_m_s2", s.acc_bias_m_s2, closed(-10.0, 10.0));
    ri.number("gyro_noise_std_rad_s", s.gyro_noise_std_rad_s, false, closed(0.0, 10.0));
    ri.vec3("gyro_bias_rad_s", s.gyro_bias_rad_s, closed(-1.0, 1.0));
    if (const json* af = ri.object("acc_fault", false)) {
      ObjectReader ra(*af, ri.at("acc_fault"), e);
      double start = 0.0;
      ra.number("start_s", start, true, closed(0.0, 1e6));
      s.acc_fault_start_s = start;
      ra.number("end_s", s.acc_fault_end_s, closed(0.0, 1e6));
      ra.vec3("offset_m_s2", s.acc_fault_offset_m_s2, closed(-50.0, 50.0));
      ra.finish();
    }
    ri.finish();
  }
  if (const json* f = r.object("encoder", false)) {
    ObjectReader re(*f, r.at("encoder"), e);
    re.number("noise_std_rad", s.encoder_noise_std_rad, false, closed(0.0, 0.1));
    re.finish();
  }
  if (const json* f = r.object("base", false)) {
    ObjectReader rb(*f, r.at("base"), e);
    rb.number("rpy_noise_std_rad", s.base_rpy_noise_std_rad, false, closed(0.0, 0.1));
    rb.finish();
  }
  r.finish();
}

// The fault types a scenario may inject, by name, in code order.
std::vector<std::string_view> sensor_fault_type_names() {
  std::vector<std::string_view> names;
  for (const FaultType t : sensor_fault_types()) names.push_back(to_string(t));
  return names;
}

std::optional<FaultSpec> read_fault(const json& j, const std::string& path, double duration,
                                    const std::vector<std::string_view>& channels, std::vector<std::string>& e) {
  if (!j.is_object()) {
    e.push_back(path + " = " + ftsense::detail::abbreviated_dump(j) + " has type " + type_name(j) + ", expected object");
    return std::nullopt;
  }
  const std::size_t before = e.size();
  ObjectReader r(j, path, e);
  FaultSpec f;
  if (auto ch = r.choice("channel", channels))
    f.channel = static_cast<int>(std::find(channels.begin(), channels.end(), *ch) - channels.begin());
  const auto type = r.choice("type", sensor_fault_type_names());
  if (type) f.type = *fault_type_from_string(*type);
  r.number("start_s", f.start_s, true, closed(0.0, duration));
  r.number("end_s", f.end_s, Range{0.0, duration, true, false});
  if (f.end_s && *f.end_s <= f.start_s && j.contains("start_s"))
    e.push_back(r.at("end_s") + " = " + fmt(*f.end_s) + " is out of range, expected > start_s (" +
                fmt(f.start_s) + ")");
  if (type) {
    switch (f.type) {
      // Up to 1e13 N: a corrupted reading (a burst of 1e12 N) is an offset too.
      case FaultType::offset: r.number("offset_N", f.offset_N, true, closed(-1e13, 1e13)); break;
      case FaultType::drift: r.number("slope_N_s", f.slope_N_s, true, closed(-1e4, 1e4)); break;
      case FaultType::frozen:
        r.number("value_N", f.value_N, closed(-1e5, 1e5));
        r.number("std_N", f.std_N, false, closed(0.0, 1e5));
        break;
      case FaultType::gain: r.number("gain", f.gain, true, closed(-100.0, 100.0)); break;
      case FaultType::noise: r.number("std_N", f.std_N, true, positive(1e5)); break;
      case FaultType::spikes:
        r.number("rate_hz", f.rate_hz, true, positive(1000.0));
        r.number("amplitude_N", f.amplitude_N, true, closed(-1e5, 1e5));
        break;
      case FaultType::invalid: break;
      case FaultType::saturation: {
        std::optional<double> lo;
        r.number("max_N", f.max_N, true, closed(-1e5, 1e5));
        r.number("min_N", lo, closed(-1e5, 1e5));
        if (lo) {
          if (*lo >= f.max_N)
            e.push_back(r.at("min_N") + " = " + fmt(*lo) + " is out of range, expected < max_N (" +
                        fmt(f.max_N) + ")");
          f.min_N = *lo;
        }
        break;
      }
      case FaultType::none:
      case FaultType::unclassified: break;  // not among the choices
    }
    r.finish();  // only when the type is known: otherwise every type-specific key would be flagged
  }
  if (e.size() != before) return std::nullopt;
  return f;
}

}  // namespace

std::vector<FaultSpec> parse_faults(const json& faults, const std::string& path,
                                    const std::vector<std::string_view>& channels, double duration_s,
                                    std::vector<std::string>& e) {
  std::vector<std::pair<std::size_t, FaultSpec>> ok;
  for (std::size_t i = 0; i < faults.size(); ++i) {
    if (auto f = read_fault(faults[i], path + "/" + std::to_string(i), duration_s, channels, e)) ok.emplace_back(i, *f);
  }
  // Faults on one channel must not overlap in time (one truth label per tick).
  for (std::size_t a = 0; a < ok.size(); ++a)
    for (std::size_t b = a + 1; b < ok.size(); ++b) {
      const FaultSpec &fa_ = ok[a].second, &fb = ok[b].second;
      if (fa_.channel != fb.channel) continue;
      const double ea = fa_.end_s.value_or(std::numeric_limits<double>::infinity());
      const double eb = fb.end_s.value_or(std::numeric_limits<double>::infinity());
      if (fa_.start_s < eb && fb.start_s < ea)
        e.push_back(path + "/" + std::to_string(ok[b].first) + " overlaps " + path + "/" + std::to_string(ok[a].first) +
                    " in time on channel " + std::string(channels[static_cast<std::size_t>(fa_.channel)]) +
                    "; faults on one channel must not overlap (end_s of one <= start_s of the other)");
    }
  std::vector<FaultSpec> out;
  for (auto& [i, f] : ok) out.push_back(f);
  return out;
}

ScenarioError::ScenarioError(std::vector<std::string> problems)
    : std::runtime_error(join(problems, "\n")), problems_(std::move(problems)) {}

Scenario parse_scenario(const json& doc) {
  std::vector<std::string> e;
  Scenario s;
  if (!doc.is_object())
    throw ScenarioError({"(document root) = " + ftsense::detail::abbreviated_dump(doc) + " has type " + type_name(doc) +
                         ", expected object"});
  ObjectReader r(doc, "", e);
  r.string("name", s.name, false);
  r.string("description", s.description, false);
  r.number("duration_s", s.duration_s, true, Range{0.0, 3600.0, true, false});
  std::int64_t seed = 1;
  r.integer("seed", seed, false, 0, std::numeric_limits<std::int64_t>::max());
  s.seed = static_cast<std::uint64_t>(seed);
  r.number("log_period_s", s.log_period_s, Range{0.0, 1.0, false, true});
  const std::size_t before_robot = e.size();
  const std::vector<std::string_view> robots(kRobotKindNames.begin(), kRobotKindNames.end());
  if (const auto k = r.choice("robot", robots, false))
    s.robot_kind = static_cast<RobotKind>(std::find(robots.begin(), robots.end(), *k) - robots.begin());
  const bool quadruped = s.robot_kind == RobotKind::quadruped;
  const bool robot_known = e.size() == before_robot;
  if (quadruped) s.sensors.force_noise_std_N = kQuadrupedForceNoiseStdN;
  if (!robot_known) {
    // Unknown robot: its gait keys and channel names are unknown too; accept the keys unread.
    (void)r.find("gait", false, "object");
    (void)r.find("body", false, "object");
    (void)r.find("faults", false, "array");
  } else if (quadruped) {
    if (const json* g = r.object("gait", false)) read_crawl(*g, r.at("gait"), s.crawl, e);
  } else {
    if (const json* b = r.object("body", false)) read_body(*b, r.at("body"), s.robot, e);
    const RobotParams standard;
    const double leg_scale = (s.robot.upper_leg_m + s.robot.lower_leg_m + s.robot.sole_ankle_m) /
                             (standard.upper_leg_m + standard.lower_leg_m + standard.sole_ankle_m);
    if (const json* g = r.object("gait", true)) read_gait(*g, r.at("gait"), s.gait, leg_scale, e);
  }
  if (const json* se = r.object("sensors", false)) read_sensors(*se, r.at("sensors"), s.sensors, e);
  if (robot_known) {
    if (const json* fa = r.array("faults", true)) {
      const std::vector<std::string_view> channels =
          quadruped ? std::vector<std::string_view>(kQuadrupedForceChannels.begin(), kQuadrupedForceChannels.end())
                    : std::vector<std::string_view>(kForceChannels.begin(), kForceChannels.end());
      s.faults = parse_faults(*fa, r.at("faults"), channels, s.duration_s, e);
    }
  }
  r.finish();
  if (!e.empty()) throw ScenarioError(std::move(e));
  s.robot.hip_half_width_m = s.gait.foot_half_spacing_m;
  return s;
}

namespace {
// The strict reader's problems (position or JSON Pointer first) as scenario problems.
[[noreturn]] void rethrow_as_scenario_error(const ftsense::ConfigError& ex) {
  std::vector<std::string> p;
  for (const auto& d : ex.problems()) p.push_back(d.text());
  throw ScenarioError(std::move(p));
}
}  // namespace

Scenario parse_scenario_text(const std::string& text) {
  json doc;
  try {
    // Strict: duplicate keys (the last duration_s would silently win), numbers beyond a double and
    // nesting deeper than a scenario needs are errors, with their position.
    doc = ftsense::parse_json_text(text, "scenario");
  } catch (const ftsense::ConfigError& ex) {
    rethrow_as_scenario_error(ex);
  }
  return parse_scenario(doc);
}

Scenario load_scenario(const std::filesystem::path& path) {
  std::string text;
  json doc;
  try {
    text = ftsense::read_text_file(path, "scenario file");
    doc = ftsense::parse_json_text(text, path.string());  // its messages start with path:line:column
  } catch (const ftsense::TextFileError& ex) {
    throw ScenarioError({ex.what()});
  } catch (const ftsense::ConfigError& ex) {
    rethrow_as_scenario_error(ex);
  }
  try {
    return parse_scenario(doc);
  } catch (const ScenarioError& ex) {
    std::vector<std::string> p;
    for (const auto& m : ex.problems()) p.push_back(path.string() + ": " + m);
    throw ScenarioError(std::move(p));
  }
}

}  // namespace ftsense::sim
