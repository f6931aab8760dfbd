#pragma once
// The contract every ftsense plugin passes: one typed GoogleTest suite, instantiated per plugin
// set. In a test file of yours (linked with GTest::gtest_main and ftsense::testing):
//
//   #include "ftsense/testing/plugin_contract.hpp"
//   namespace ftsense::testing {  // the suite's namespace (a GoogleTest requirement)
//   using MyPlugins = ::testing::Types<MyVirtualSensor, MyDetector>;
//   INSTANTIATE_TYPED_TEST_SUITE_P(My, PluginContract, MyPlugins);
//   }
//
// A plugin whose defaults are not a valid configuration, or whose inputs need realistic values,
// specialises ftsense::testing::ContractSetup<P> (all members optional in spirit, but a
// specialisation must define all four):
//
//   template <> struct ftsense::testing::ContractSetup<MyPlugin> {
//     static Json params() { return {{"mass_kg", 114.0}}; }
//     static std::size_t input_dim(std::string_view port) { return 3; }
//     static void nominal_input(std::string_view port, std::span<double> v) { ... }
//     static double sample_period_s() { return 1e-3; }
//     // optional: ticks after reset during which a filter may say it is not ready (NaN outputs)
//     static int settle_ticks() { return 100; }
//     // optional: the random walk's step per tick around the nominal inputs (default 1)
//     static double random_step() { return 0.01; }
//     // optional: inputs of 1e-300 are no value of the input at all (a unit quaternion cannot be
//     // tiny), so the plugin must answer NaN ("no value") on every output instead of finite ones
//     static bool tiny_inputs_have_no_value() { return true; }
//   };
//
// What it checks: the parameters described load from JSON without errors and round-trip
// (load(save(p)) == p as JSON); every parameter is documented; ports are well formed; reset and
// step give finite outputs on nominal, tiny (or, if the setup says tiny inputs have no value, NaN
// outputs) and seeded random inputs (after settle_ticks, if the setup gives them), and again 2 s
// after a burst
// of NaN or Inf on any input; reset then replay gives
// bit-identical outputs; step allocates nothing.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "ftsense/plugin.hpp"
#include "ftsense/testing/allocation_counter.hpp"

namespace ftsense::testing {

template <class P>
struct ContractSetup {
  static Json params() { return Json::object(); }
  static std::size_t input_dim(std::string_view /*port*/) { return 3; }
  static void nominal_input(std::string_view /*port*/, std::span<double> values) {
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 1.0 + 0.25 * static_cast<double>(i);
  }
  static double sample_period_s() { return 1e-3; }
};

// A filter that converges after reset may output NaN ("not ready") for this many ticks.
template <class P>
int settle_ticks() {
  if constexpr (requires { ContractSetup<P>::settle_ticks(); }) {
    return ContractSetup<P>::settle_ticks();
  } else {
    return 0;
  }
}

// The random test's step per tick around the nominal inputs: a plugin whose inputs have physical
// limits (a CoM within reach of the feet) is walked more gently than by the default 1 per tick.
template <class P>
double random_step() {
  if constexpr (requires { ContractSetup<P>::random_step(); }) {
    return ContractSetup<P>::random_step();
  } else {
    return 1.0;
  }
}

// Whether inputs of 1e-300 lie outside the inputs' domain, so that NaN is the right answer.
template <class P>
bool tiny_inputs_have_no_value() {
  if constexpr (requires { ContractSetup<P>::tiny_inputs_have_no_value(); }) {
    return ContractSetup<P>::tiny_inputs_have_no_value();
  } else {
    return false;
  }
}

// A plugin wired to buffers of its own, as the pipeline would do it.
template <class P>
class PluginHarness {
 public:
  PluginHarness() {
    Diagnostics diag;
    params_ = load_params<typename P::Params>(ContractSetup<P>::params(), "/params", P::name, diag);
    if (diag.has_errors()) throw ConfigError(diag.errors());
    // First construction tells the input names; the second gets the dims wired to them.
    const StageContext probe(ContractSetup<P>::sample_period_s(), "contract");
    const P first(params_, probe);
    std::vector<std::pair<std::string, std::size_t>> dims;
    for (const auto& in : first.ports().inputs()) {
      dims.emplace_back(in.name, ContractSetup<P>::input_dim(in.name));
    }
    plugin_ = std::make_unique<P>(params_, StageContext(ContractSetup<P>::sample_period_s(), "contract", dims));
    const Ports& ports = plugin_->ports();
    for (const auto& in : ports.inputs()) inputs_.emplace_back(in.dim, 0.0);
    for (const auto& out : ports.outputs()) outputs_.emplace_back(out.dim, 0.0);
    for (auto& v : inputs_) input_spans_.emplace_back(v);
    for (auto& v : outputs_) output_spans_.emplace_back(v);
    io_.inputs = input_spans_;
    io_.outputs = output_spans_;
  }

  P& plugin() { return *plugin_; }
  const typename P::Params& params() const { return params_; }
  std::vector<std::vector<double>>& inputs() { return inputs_; }
  const std::vector<std::vector<double>>& outputs() const { return outputs_; }

  void fill_nominal() {
    const auto& ports = plugin_->ports();
    for (std::size_t i = 0; i < inputs_.size(); ++i) {
      ContractSetup<P>::nominal_input(ports.inputs()[i].name, inputs_[i]);
    }
  }
  void step(double t) noexcept {
    io_.time_s = t;
    plugin_->step(io_);
  }
  // The first output that is not NaN as "port[index]", or empty.
  std::string first_output_with_a_value() const {
    const auto& ports = plugin_->ports();
    for (std::size_t o = 0; o < outputs_.size(); ++o) {
      for (std::size_t j = 0; j < outputs_[o].size(); ++j) {
        if (!std::isnan(outputs_[o][j])) {
          return ports.outputs()[o].name + "[" + std::to_string(j) + "] = " + std::to_string(outputs_[o][j]);
        }
      }
    }
    return {};
  }
  // The first non-finite output as "port[index]", or empty.
  std::string first_non_finite_output() const {
    const auto& ports = plugin_->ports();
    for (std::size_t o = 0; o < outputs_.size(); ++o) {
      for (std::size_t j = 0; j < outputs_[o].size(); ++j) {
        if (!std::isfinite(outputs_[o][j])) {
          return ports.outputs()[o].name + "[" + std::to_string(j) + "] = " + std::to_string(outputs_[o][j]);
        }
      }
    }
    return {};
  }

 private:
  typename P::Params params_{};
  std::unique_ptr<P> plugin_;
  std::vector<std::vector<double>> inputs_;
  std::vector<std::vector<double>> outputs_;
  std::vector<std::span<const double>> input_spans_;
  std::vector<std::span<double>> output_spans_;
  StepIO io_;
};

template <class P>
class PluginContract : public ::testing::Test {};

TYPED_TEST_SUITE_P(PluginContract);

TYPED_TEST_P(PluginContract, ParametersLoadAndConstruct) {
  Diagnostics diag;
  (void)load_params<typename TypeParam::Params>(ContractSetup<TypeParam>::params(), "/params",
                                                TypeParam::name, diag);
  for (const auto& e : diag.errors()) ADD_FAILURE() << e.text();
  EXPECT_NO_THROW(PluginHarness<TypeParam>{});
}

TYPED_TEST_P(PluginContract, ParametersRoundTripThroughJson) {
  PluginHarness<TypeParam> h;
  const Json saved = save_params(h.params());
  Diagnostics diag;
  const auto reloaded = load_params<typename TypeParam::Params>(saved, "/params", TypeParam::name, diag);
  for (const auto& e : diag.errors()) ADD_FAILURE() << e.text();
  EXPECT_EQ(save_params(reloaded), saved);
  // Every described key is saved, so a saved config documents every setting.
  for (const auto& info : param_infos<typename TypeParam::Params>()) {
    EXPECT_TRUE(saved.contains(info.key)) << info.key;
  }
}

TYPED_TEST_P(PluginContract, EveryParameterIsDocumented) {
  EXPECT_FALSE(std::string_view(TypeParam::name).empty());
  EXPECT_FALSE(std::string_view(TypeParam::summary).empty());
  for (const auto& info : param_infos<typename TypeParam::Params>()) {
    EXPECT_FALSE(info.description.empty()) << info.key;
    // snake_case; the last word may be an SI unit symbol with capitals ("min_force_N").
    const std::size_t unit_start = info.key.rfind('_') == std::string::npos ? info.key.size() : info.key.rfind('_');
    for (std::size_t i = 0; i < info.key.size(); ++i) {
      const char c = info.key[i];
      const bool lower = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
      const bool unit_capital = i > unit_start && c >= 'A' && c <= 'Z';
      EXPECT_TRUE(lower || unit_capital) << "parameter keys are snake_case: " << info.key;
    }
  }
}

TYPED_TEST_P(PluginContract, PortsAreWellFormed) {
  PluginHarness<TypeParam> h;
  const Ports& ports = h.plugin().ports();
  EXPECT_FALSE(ports.outputs().empty()) << "a stage must produce something";
  for (const auto* list : {&ports.inputs(), &ports.outputs()}) {
    for (const auto& p : *list) {
      EXPECT_GT(p.dim, 0u) << p.name;
      EXPECT_FALSE(p.name.empty());
      EXPECT_EQ(p.name.find('.'), std::string::npos) << "port names cannot contain '.': " << p.name;
      EXPECT_FALSE(p.description.empty()) << p.name;
    }
  }
}

TYPED_TEST_P(PluginContract, CalibratedParamsNameItsParametersAndInputs) {
  if constexpr (PluginHasCalibratedParams<TypeParam>) {
    PluginHarness<TypeParam> h;
    const Ports& ports = h.plugin().ports();
    const auto params = param_infos<typename TypeParam::Params>();
    for (const CalibratedParam& c : TypeParam::calibrated_params) {
      const bool known = std::any_of(params.begin(), params.end(), [&](const auto& i) { return i.key == c.param; });
      EXPECT_TRUE(known) << "calibrated parameter " << c.param << " is no parameter";
      // calibrate writes a list per channel, or the largest over the channels for a parameter of
      // one number (calibration.hpp): the largest of a centre means nothing.
      for (const auto& i : params) {
        if (i.key != c.param) continue;
        EXPECT_TRUE(i.kind == ParamKind::number_list || i.kind == ParamKind::number)
            << "calibrated parameter " << c.param << " is neither a number nor a list of numbers";
        EXPECT_FALSE(i.kind == ParamKind::number && c.statistic == FaultFreeStatistic::centre)
            << "calibrated parameter " << c.param << ": a centre of one number for all channels";
      }
      EXPECT_TRUE(ports.find_input(c.input).has_value()) << "calibrated from " << c.input << ", no input";
      if (!c.minus_input.empty()) {
        EXPECT_TRUE(ports.find_input(c.minus_input).has_value()) << "calibrated from - " << c.minus_input;
      }
      // A step across guards needs the guards, and only it reads them (the guard input may be an
      // optional port these params leave out: calibrate then leaves the parameter alone).
      EXPECT_EQ(c.statistic == FaultFreeStatistic::guard_step, !c.guard_input.empty())
          << "calibrated parameter " << c.param << ": guard_input goes with the guard_step statistic";
    }
  } else {
    SUCCEED() << "no calibrated parameters";
  }
}

TYPED_TEST_P(PluginContract, NominalInputsGiveFiniteOutputs) {
  PluginHarness<TypeParam> h;
  h.plugin().reset();
  h.fill_nominal();
  for (int k = 0; k < 200 + settle_ticks<TypeParam>(); ++k) {
    h.step(k * ContractSetup<TypeParam>::sample_period_s());
    if (k >= settle_ticks<TypeParam>()) {
      ASSERT_EQ(h.first_non_finite_output(), "") << "tick " << k;
    }
  }
}

TYPED_TEST_P(PluginContract, TinyInputsGiveFiniteOutputs) {
  PluginHarness<TypeParam> h;
  h.plugin().reset();
  for (auto& v : h.inputs()) std::fill(v.begin(), v.end(), 1e-300);
  for (int k = 0; k < 50 + settle_ticks<TypeParam>(); ++k) {
    h.step(k * ContractSetup<TypeParam>::sample_period_s());
    if (k < settle_ticks<TypeParam>()) continue;
    if (tiny_inputs_have_no_value<TypeParam>()) {
      ASSERT_EQ(h.first_output_with_a_value(), "") << "tick " << k << ": tiny inputs have no value";
    } else {
      ASSERT_EQ(h.first_non_finite_output(), "") << "tick " << k;
    }
  }
}

TYPED_TEST_P(PluginContract, RandomInputsAreFiniteAndResetReplaysExactly) {
  constexpr std::uint64_t kSeed = 20261122;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  PluginHarness<TypeParam> h;
  auto run = [&h] {
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    const double scale = random_step<TypeParam>();
    std::vector<double> trace;
    h.plugin().reset();
    h.fill_nominal();
    for (int k = 0; k < 500; ++k) {
      // Perturb around the nominal operating point so plugins with guarded regions are exercised.
      for (auto& v : h.inputs()) {
        for (auto& x : v) x += value(rng) * scale;
      }
      h.step(k * ContractSetup<TypeParam>::sample_period_s());
      if (k >= settle_ticks<TypeParam>()) {
        EXPECT_EQ(h.first_non_finite_output(), "") << "tick " << k;
      }
      for (const auto& o : h.outputs()) trace.insert(trace.end(), o.begin(), o.end());
    }
    return trace;
  };
  const auto first = run();
  const auto second = run();
  ASSERT_EQ(first.size(), second.size());
  EXPECT_EQ(0, std::memcmp(first.data(), second.data(), first.size() * sizeof(double)))
      << "reset() must return the plugin to its initial state";
}

TYPED_TEST_P(PluginContract, RecoversFromNonFiniteInputs) {
  // NaN means "no value" in ftsense and data can be hostile: a burst of NaN or Inf on any one
  // input (or on all of them) must not crash (UBSan: no NaN-to-integer casts), and once the inputs
  // are nominal again every output must be finite within 2 s of ticks: no state latches a NaN.
  constexpr int kBadTicks = 20;
  constexpr int kRecoveryTicks = 2000;
  const double period = ContractSetup<TypeParam>::sample_period_s();
  PluginHarness<TypeParam> h;
  const std::size_t input_count = h.inputs().size();
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()}) {
    for (std::size_t target = 0; target <= input_count; ++target) {  // input_count: all of them
      const std::string what = (target == input_count ? std::string("all inputs")
                                                       : "input '" + h.plugin().ports().inputs()[target].name + "'") +
                               " = " + std::to_string(bad);
      h.plugin().reset();
      h.fill_nominal();
      double t = 0.0;
      for (int k = 0; k < 100; ++k, t += period) h.step(t);
      for (std::size_t i = 0; i < input_count; ++i) {
        if (i == target || target == input_count) std::fill(h.inputs()[i].begin(), h.inputs()[i].end(), bad);
      }
      for (int k = 0; k < kBadTicks; ++k, t += period) h.step(t);
      h.fill_nominal();
      for (int k = 0; k < kRecoveryTicks; ++k, t += period) h.step(t);
      EXPECT_EQ(h.first_non_finite_output(), "") << "2 s after " << kBadTicks << " ticks of " << what;
    }
  }
}

TYPED_TEST_P(PluginContract, StepDoesNotAllocate) {
  PluginHarness<TypeParam> h;
  h.plugin().reset();
  h.fill_nominal();
  h.step(0.0);  // a first step may touch lazily initialised statics of the C++ runtime
  AllocationScope scope;
  for (int k = 1; k < 2000; ++k) h.step(k * ContractSetup<TypeParam>::sample_period_s());
  h.plugin().reset();
  EXPECT_EQ(scope.allocations(), 0u) << "step() and reset() must not allocate";
}

REGISTER_TYPED_TEST_SUITE_P(PluginContract, ParametersLoadAndConstruct,
                            ParametersRoundTripThroughJson, EveryParameterIsDocumented,
                            PortsAreWellFormed, CalibratedParamsNameItsParametersAndInputs,
                            NominalInputsGiveFiniteOutputs,
                            TinyInputsGiveFiniteOutputs, RandomInputsAreFiniteAndResetReplaysExactly,
                            RecoversFromNonFiniteInputs, StepDoesNotAllocate);

}  // namespace ftsense::testing
