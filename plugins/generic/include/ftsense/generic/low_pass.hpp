#pragma once
// First-order low-pass filter, per channel, discretised exactly for a held input:
//
//   y_k = y_{k-1} + a (x_k - y_{k-1}),   a = 1 - exp(-2 pi f_c T)
//
// f_c [Hz] is the cut-off frequency (time constant tau = 1 / (2 pi f_c)), T [s] the pipeline's
// tick period; f_c must be below the Nyquist frequency 1 / (2 T). The first finite sample
// initialises y (or y starts at zero, by parameter). A non-finite input is skipped: y holds its
// last value, so one NaN does not poison the state (detectors see the NaN on their own inputs).
// Units pass through.

#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class LowPass {
 public:
  static constexpr std::string_view name = "low_pass";
  static constexpr std::string_view summary =
      "first-order low-pass y += a (x - y), a = 1 - exp(-2 pi f_c T), per channel";

  enum class Start { first_sample, zero };

  struct Params {
    double cutoff_hz = 1.0;
    Start start = Start::first_sample;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kSignal };
  enum Output : std::size_t { kFiltered };

  LowPass(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  // The smoothing factor a of the recursion above.
  [[nodiscard]] double smoothing_factor() const noexcept { return a_; }

 private:
  Ports ports_;
  double a_ = 0.0;
  Start start_ = Start::first_sample;
  std::vector<double> state_;
  std::vector<unsigned char> initialised_;
};

}  // namespace ftsense::generic
