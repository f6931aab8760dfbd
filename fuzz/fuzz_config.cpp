// libFuzzer target: the config loader (parse_json_text + Pipeline::build with the reference
// plugins), then a few ticks of the pipeline it built.
//
// Input layout: the config text up to the first NUL byte; the bytes after it (optional) choose
// the tick values: plausible sensor data or anything (NaN, +-Inf, +-1e308, subnormals, ...).
// Without them a fixed pattern is used: four ticks of ordinary values, then hostile ones.
//
// A config may only be rejected with ConfigError (at least one problem, each with a message);
// anything else escaping is a bug. A built pipeline is stepped over fuzzer-chosen values
// (NaN and Inf included) and must not crash; these must never be NaN:
//   - the `recovered` output of every fault_recovery stage (its documented contract);
//   - the monitor's `recovered` signal while every value fed so far was plausible (finite and
//     at most kPlausible in magnitude: 1e308 - (-1e308) overflows in any filter, and a NaN or
//     Inf input may pass straight through when the config wires `recovered` to an input).
// A NaN there aborts with the stage, channel and tick, so libFuzzer keeps the input.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"

namespace {

using ftsense::Pipeline;
using ftsense::SignalRef;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Values worth trying at every input: ordinary forces and positions, edges and non-finite ones.
constexpr double kSpecial[] = {0.0, 1.0, -1.0, 250.0, 9.81, 0.1, -0.1, 1e-300, 5e-324,
                               1e6, -1e6, 1e308, -1e308, kNaN, kInf, -kInf};
constexpr std::size_t kMaxTicks = 16;
constexpr double kPlausible = 1e9;

[[noreturn]] void contract_broken(const std::string& what) {
  std::fprintf(stderr, "fuzz_config: contract broken: %s\n", what.c_str());
  std::abort();
}

struct Watched {
  std::string what;
  SignalRef ref;
  bool only_while_plausible;  // NaN tolerated once an implausible value was fed
};

constexpr double kOrdinary[] = {0.0, 1.0, -1.0, 250.0, 9.81, 0.1, -0.1, 0.7, 1e-3, 1e3};
constexpr std::size_t kDefaultOrdinaryTicks = 4;

// `hostile`: any double; otherwise plausible sensor data only (finite, |x| <= kPlausible).
double pick(FuzzedDataProvider& fdp, bool hostile, std::size_t tick, std::size_t k) {
  if (fdp.remaining_bytes() == 0) {
    // Default pattern: a few ticks of ordinary values, then each kind of hostile value in turn.
    if (tick < kDefaultOrdinaryTicks) return kOrdinary[(tick * 3 + k) % std::size(kOrdinary)] + static_cast<double>(k);
    return kSpecial[(tick * 7 + k) % std::size(kSpecial)];
  }
  if (!hostile) {
    if (fdp.ConsumeBool()) return fdp.PickValueInArray(kOrdinary);
    return fdp.ConsumeFloatingPointInRange<double>(-1e4, 1e4);
  }
  if (fdp.ConsumeBool()) return fdp.PickValueInArray(kSpecial);
  return fdp.ConsumeFloatingPoint<double>();
}

void step_a_few(Pipeline& p, FuzzedDataProvider& fdp) {
  // Every signal the pipeline lists can be looked up by its name.
  for (const auto& [name, unit] : p.signal_names()) {
    try {
      (void)p.signal(name);
    } catch (const ftsense::ConfigError& e) {
      contract_broken("signal_names() lists '" + name + "' but signal() says: " + e.what());
    }
  }
  std::vector<Watched> watched;
  for (std::size_t s = 0; s < p.stage_count(); ++s) {
    ftsense::Stage& stage = p.stage(s);
    if (stage.plugin_name() != "fault_recovery") continue;
    const std::string name = std::string(p.stage_name(s)) + ".recovered";
    watched.push_back({"fault_recovery output " + name, p.signal(name), false});
  }
  if (p.has_monitor()) watched.push_back({"monitor recovered", p.monitor()[ftsense::MonitorColumn::recovered], true});

  const bool hostile = fdp.remaining_bytes() != 0 && fdp.ConsumeBool();
  const std::size_t ticks =
      fdp.remaining_bytes() == 0 ? 8 : fdp.ConsumeIntegralInRange<std::size_t>(1, kMaxTicks);
  bool all_plausible = true;
  for (std::size_t tick = 0; tick < ticks; ++tick) {
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.inputs().size(); ++i) {
      for (double& v : p.input_values(i)) {
        v = pick(fdp, hostile, tick, k++);
        all_plausible = all_plausible && std::isfinite(v) && std::abs(v) <= kPlausible;
      }
    }
    p.step(static_cast<double>(tick) * p.sample_period_s());
    for (const Watched& w : watched) {
      if (w.only_while_plausible && !all_plausible) continue;
      const auto values = p.values(w.ref);
      for (std::size_t j = 0; j < values.size(); ++j) {
        if (std::isnan(values[j])) {
          contract_broken(w.what + "[" + std::to_string(j) + "] is NaN at tick " +
                          std::to_string(tick) + (all_plausible ? " (all inputs plausible so far)" : ""));
        }
      }
    }
  }
  // Back to the initial state and one more tick over the last values.
  p.reset();
  p.step(0.0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ftsense::PluginRegistry registry = ftsense::reference_plugins::registry();
  const char* text = reinterpret_cast<const char*>(data);
  const void* nul = std::memchr(data, 0, size);
  const std::size_t text_size = nul ? static_cast<std::size_t>(static_cast<const std::uint8_t*>(nul) - data) : size;
  FuzzedDataProvider ticks(data + text_size + (nul ? 1 : 0), size - text_size - (nul ? 1 : 0));
  try {
    const ftsense::Json config = ftsense::parse_json_text(std::string_view(text, text_size), "fuzz.json");
    Pipeline pipeline = Pipeline::build(config, registry);
    step_a_few(pipeline, ticks);
  } catch (const ftsense::ConfigError& e) {
    if (e.problems().empty()) contract_broken("ConfigError without problems");
    for (const auto& problem : e.problems()) {
      if (problem.message.empty()) contract_broken("ConfigError problem without a message at '" + problem.path + "'");
    }
  }
  return 0;
}
