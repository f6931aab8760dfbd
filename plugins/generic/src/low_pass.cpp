#include "ftsense/generic/low_pass.hpp"

#include <cmath>

#include "ftsense/low_pass_gain.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::generic {

void LowPass::Params::describe(ParamSchema<Params>& schema) {
  schema.add("cutoff_hz", &Params::cutoff_hz, "cut-off frequency f_c, below 1 / (2 T)")
      .unit("Hz")
      .greater_than(0.0).plausible(plausible::cutoff_hz());
  schema.add_choice("start", &Params::start, "initial output: the first finite sample, or zero",
                    {{"first_sample", Start::first_sample}, {"zero", Start::zero}});
}

LowPass::LowPass(const Params& params, const StageContext& context) : start_(params.start) {
  a_ = low_pass_gain(params.cutoff_hz, context.sample_period_s());
  const std::size_t dim = context.wired_dim("signal", 1);
  ports_.add_input(PortSpec{"signal", dim, std::string(kAnyUnit), "the signal to smooth"}.sized_by("as wired"));
  ports_.add_output(PortSpec{"filtered", dim, std::string(kAnyUnit), "the low-passed signal"}.sized_by("as `signal`"));
  state_.assign(dim, 0.0);
  initialised_.assign(dim, 0);
}

void LowPass::reset() noexcept {
  std::fill(state_.begin(), state_.end(), 0.0);
  std::fill(initialised_.begin(), initialised_.end(), static_cast<unsigned char>(start_ == Start::zero));
}

void LowPass::step(const StepIO& io) noexcept {
  const auto x = io.in(kSignal);
  const auto y = io.out(kFiltered);
  for (std::size_t j = 0; j < state_.size(); ++j) {
    if (std::isfinite(x[j])) {
      if (initialised_[j]) {
        state_[j] += a_ * (x[j] - state_[j]);
      } else {
        state_[j] = x[j];
        initialised_[j] = 1;
      }
    }
    y[j] = state_[j];
  }
}

}  // namespace ftsense::generic
