#pragma once
// The plugin contract.
//
// A plugin is a plain class:
//
//   class MyFilter {
//    public:
//     static constexpr std::string_view name = "my_filter";          // unique in a plugin set
//     static constexpr std::string_view summary = "one line for the config reference";
//     struct Params { ...; static void describe(ftsense::ParamSchema<Params>&); };
//     MyFilter(const Params&, const ftsense::StageContext&);  // validates, declares ports,
//                                                             // preallocates; may throw ConfigError
//     const ftsense::Ports& ports() const noexcept;
//     void reset() noexcept;                                  // back to the initial state
//     void step(const ftsense::StepIO&) noexcept;             // one tick: no allocation, no throw
//   };
//
// Optional, for the config reference's port tables (docs/config_reference.md), which list every
// plugin's ports without a config by constructing it with example parameters:
//
//     static constexpr std::string_view example_params = R"({"height_m": 0.8})";
//                  // JSON overriding the defaults, one object or an array of them (the table
//                  // lists the union of their ports: a port some parameters add); needed when the
//                  // defaults do not construct (required parameters). Also the schema's examples.
//     static constexpr auto calibrated_params = std::to_array<ftsense::CalibratedParam>({...});
//                  // parameters that are statistics of fault-free inputs, which `ftsense
//                  // calibrate` measures (calibration.hpp)
//     static ftsense::Ports declare_ports(const Params&);
//                  // the ports, when constructing needs more than parameters (a file); the
//                  // constructor then takes its ports from it too.
//
// Lifecycle: constructed once when the pipeline is built, reset() before the first tick and
// whenever the pipeline resets, then step() once per tick. Threading: a plugin object is used by
// one thread at a time; distinct objects share nothing.
//
// Sensing outcomes (a fault, an infeasible problem, not ready yet) are outputs, not exceptions.

#include <concepts>
#include <memory>
#include <string_view>

#include "ftsense/calibration.hpp"
#include "ftsense/params.hpp"
#include "ftsense/ports.hpp"

namespace ftsense {

template <class P>
concept PluginHasName = requires {
  { P::name } -> std::convertible_to<std::string_view>;
};
template <class P>
concept PluginHasSummary = requires {
  { P::summary } -> std::convertible_to<std::string_view>;
};
template <class P>
concept PluginHasParams = requires { typename P::Params; };
template <class P>
concept PluginDescribesParams = requires(ParamSchema<typename P::Params>& schema) {
  { P::Params::describe(schema) } -> std::same_as<void>;
};
template <class P>
concept PluginConstructs = std::constructible_from<P, const typename P::Params&, const StageContext&>;
template <class P>
concept PluginDeclaresPorts = requires(const P& p) {
  { p.ports() } -> std::same_as<const Ports&>;
};
template <class P>
concept PluginResets = requires(P& p) {
  { p.reset() } noexcept;
};
template <class P>
concept PluginSteps = requires(P& p, const StepIO& io) {
  { p.step(io) } noexcept;
};

// The optional members above.
template <class P>
concept PluginHasExampleParams = requires {
  { P::example_params } -> std::convertible_to<std::string_view>;
};
template <class P>
concept PluginHasCalibratedParams = requires {
  { P::calibrated_params.size() } -> std::convertible_to<std::size_t>;
  { P::calibrated_params[0] } -> std::convertible_to<CalibratedParam>;
};
template <class P>
concept PluginDeclaresPortsFromParams = requires(const typename P::Params& params) {
  { P::declare_ports(params) } -> std::same_as<Ports>;
};

template <class P>
concept Plugin = PluginHasName<P> && PluginHasSummary<P> && PluginHasParams<P> &&
                 PluginDescribesParams<P> && PluginConstructs<P> && PluginDeclaresPorts<P> &&
                 PluginResets<P> && PluginSteps<P>;

// Instantiated for every member of a PluginSet: one readable message per broken rule.
template <class P>
constexpr bool check_plugin() {
  static_assert(PluginHasName<P>,
                "ftsense plugin: add `static constexpr std::string_view name = \"...\";`");
  static_assert(PluginHasSummary<P>,
                "ftsense plugin: add `static constexpr std::string_view summary = \"...\";`");
  static_assert(PluginHasParams<P>,
                "ftsense plugin: add a nested `struct Params` (may be empty)");
  if constexpr (PluginHasParams<P>) {
    static_assert(PluginDescribesParams<P>,
                  "ftsense plugin: Params needs `static void describe(ftsense::ParamSchema<Params>&)`");
    static_assert(PluginConstructs<P>,
                  "ftsense plugin: add a constructor `P(const Params&, const ftsense::StageContext&)`");
  }
  static_assert(PluginDeclaresPorts<P>,
                "ftsense plugin: add `const ftsense::Ports& ports() const noexcept`");
  static_assert(PluginResets<P>, "ftsense plugin: add `void reset() noexcept`");
  static_assert(PluginSteps<P>,
                "ftsense plugin: add `void step(const ftsense::StepIO&) noexcept` (it must be "
                "noexcept: a tick never throws)");
  return true;
}

// A constructed plugin behind a virtual interface: the pipeline's view of a stage.
class Stage {
 public:
  virtual ~Stage() = default;
  [[nodiscard]] virtual std::string_view plugin_name() const noexcept = 0;
  [[nodiscard]] virtual const Ports& ports() const noexcept = 0;
  [[nodiscard]] virtual Json params_json() const = 0;
  virtual void reset() noexcept = 0;
  virtual void step(const StepIO& io) noexcept = 0;
};

template <Plugin P>
class StageOf final : public Stage {
 public:
  StageOf(const typename P::Params& params, const StageContext& context)
      : params_(params), plugin_(params_, context) {}

  [[nodiscard]] std::string_view plugin_name() const noexcept override { return P::name; }
  [[nodiscard]] const Ports& ports() const noexcept override { return plugin_.ports(); }
  [[nodiscard]] Json params_json() const override { return save_params(params_); }
  void reset() noexcept override { plugin_.reset(); }
  void step(const StepIO& io) noexcept override { plugin_.step(io); }

  [[nodiscard]] P& plugin() noexcept { return plugin_; }
  [[nodiscard]] const typename P::Params& params() const noexcept { return params_; }

 private:
  typename P::Params params_;
  P plugin_;
};

}  // namespace ftsense
