#include "ftsense/generic/random_walk_fault_filter.hpp"

#include <cmath>

namespace ftsense::generic {

void RandomWalkFaultFilter::Params::describe(ParamSchema<Params>& schema) {
  schema.add("fault_process_noise", &Params::fault_process_noise,
             "q_eta: variance of the fault's random-walk step per tick (unit of the signal, squared)")
      .greater_than(0.0);
  schema.add("force_process_noise", &Params::force_process_noise,
             "q_N: process noise variance of the true-signal state per tick")
      .greater_than(0.0);
  schema.add("measurement_noise", &Params::measurement_noise,
             "r: variance of the virtual sensor's error (the filter's measurement)")
      .greater_than(0.0);
  schema.add("initial_fault_variance", &Params::initial_fault_variance,
             "P0 of the fault state (the true-signal state starts with q_N)")
      .greater_than(0.0);
  schema.add("ready_tolerance", &Params::ready_tolerance,
             "ready once |var(eta) - steady-state var(eta)| <= this fraction of the steady state")
      .greater_than(0.0)
      .at_most(1.0);
}

RandomWalkFaultFilter::RandomWalkFaultFilter(const Params& params, const StageContext& context)
    : params_(params) {
  const double q = params.fault_process_noise;
  const double s = params.force_process_noise + params.measurement_noise;
  steady_variance_ = 0.5 * (q + std::sqrt(q * q + 4.0 * q * s));
  const std::size_t dim = context.wired_dim("measured", 1);
  ports_.add_input(PortSpec{"measured", dim, std::string(kAnyUnit), "the monitored sensor N_meas", PortRole::measured}
                       .sized_by("as wired"));
  ports_.add_input(PortSpec{"virtual", dim, std::string(kAnyUnit), "the virtual sensor N_vfs", PortRole::virtual_estimate}
                       .sized_by("as `measured`"));
  ports_.add_output(PortSpec{"fault_estimate", dim, std::string(kAnyUnit), "eta_hat, the estimated sensor fault"}
                        .sized_by("as `measured`"));
  ports_.add_output(PortSpec{"true_estimate", dim, std::string(kAnyUnit), "the filter's estimate of the true signal N"}
                        .sized_by("as `measured`"));
  ports_.add_output(PortSpec{"ready", dim, std::string(kDimensionless),
                     "1 once the fault variance has converged and both inputs are finite (0: virtual "
                     "sensor not ready, the state holds)"}.sized_by("as `measured`"));
  ports_.add_output(PortSpec{"fault_variance", dim, std::string(kAnyUnitSquared),
                     "posterior variance p of eta_hat (unit of the signal, squared), for health monitoring"}
                        .sized_by("as `measured`"));
  ports_.add_output(PortSpec{"covariance_resets", dim, std::string(kDimensionless),
                     "number of covariance resets of the channel since reset (non-finite or non-positive P)"}
                        .sized_by("as `measured`"));
  channels_.resize(dim);
  reset();
}

double RandomWalkFaultFilter::steady_state_fault_gain() const noexcept {
  return -steady_variance_ /
         (steady_variance_ + params_.force_process_noise + params_.measurement_noise);
}

void RandomWalkFaultFilter::reset_channel(Channel& c) const noexcept {
  c.p_fault = params_.initial_fault_variance;
  c.p_cross = 0.0;
  c.p_force = params_.force_process_noise;
  c.fault_gain = 0.0;
}

void RandomWalkFaultFilter::reset() noexcept {
  for (auto& c : channels_) {
    c.fault = 0.0;
    c.resets = 0.0;
    reset_channel(c);
  }
  covariance_resets_ = 0;
}

void RandomWalkFaultFilter::step(const StepIO& io) noexcept {
  const auto measured = io.in(kMeasured);
  const auto estimate = io.in(kVirtual);
  const auto fault_out = io.out(kFaultEstimate);
  const auto true_out = io.out(kTrueEstimate);
  const auto ready_out = io.out(kReady);
  const auto variance_out = io.out(kFaultVariance);
  const auto resets_out = io.out(kCovarianceResets);
  const double q_fault = params_.fault_process_noise;
  const double q_force = params_.force_process_noise;
  const double r = params_.measurement_noise;
  for (std::size_t j = 0; j < channels_.size(); ++j) {
    Channel& c = channels_[j];
    const double u = measured[j];
    const double y = estimate[j];
    const bool inputs_finite = std::isfinite(u) && std::isfinite(y);
    if (inputs_finite) {
      // Predict: x- = A x + B u; with A = [1 0; -1 0] only var(eta) survives the propagation.
      const double a = c.p_fault;
      const double prior_fault_var = a + q_fault;
      const double prior_cross = -a;
      const double prior_force_var = a + q_force;
      const double predicted_force = u - c.fault;
      // Update with y = N_vfs, H = [0 1].
      const double innovation_var = prior_force_var + r;
      const double gain_fault = prior_cross / innovation_var;
      const double gain_force = prior_force_var / innovation_var;
      const double innovation = y - predicted_force;
      c.fault += gain_fault * innovation;
      c.fault_gain = gain_fault;
      c.p_fault = prior_fault_var - prior_cross * prior_cross / innovation_var;
      c.p_cross = prior_cross - prior_cross * prior_force_var / innovation_var;
      c.p_force = prior_force_var - prior_force_var * prior_force_var / innovation_var;
      true_out[j] = predicted_force + gain_force * innovation;
      if (!(c.p_fault > 0.0 && c.p_force > 0.0 && std::isfinite(c.p_fault) && std::isfinite(c.fault))) {
        c.fault = std::isfinite(c.fault) ? c.fault : 0.0;
        reset_channel(c);
        ++covariance_resets_;
        c.resets += 1.0;
      }
    } else {
      true_out[j] = std::isfinite(u) ? u - c.fault : y;
    }
    fault_out[j] = c.fault;
    const bool converged = std::abs(c.p_fault - steady_variance_) <= params_.ready_tolerance * steady_variance_;
    ready_out[j] = inputs_finite && converged ? 1.0 : 0.0;
    variance_out[j] = c.p_fault;
    resets_out[j] = c.resets;
  }
}

}  // namespace ftsense::generic
