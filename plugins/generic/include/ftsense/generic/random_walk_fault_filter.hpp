#pragma once
// Random-walk fault Kalman filter (method.md section 5; paper eq. 24-32), per channel j.
//
// Fault model: the sensor reads N_meas = N + eta + v_N, with the fault eta a random walk. State
// x = [eta; N] (per channel; channels are independent because Q and R are diagonal):
//
//   x_k = A x_{k-1} + B u_k + w_k,   A = [1 0; -1 0],   B u_k = [0; N_meas,k]
//   y_k = [0 1] x_k + v_k,           y_k = N_vfs,k (the virtual sensor)
//   w ~ N(0, diag(q_eta, q_N)),  v ~ N(0, r);   paper: q_eta = q_N = 1e-10, r = 1e-4 (T = 1 ms)
//
// So the prediction of the true force is N_meas - eta, the innovation is
// N_vfs - (N_meas - eta), and eta_hat tracks N_meas - N_vfs with a time constant set by Q/R.
// In steady state the posterior fault variance p solves p^2 - q_eta p - q_eta (q_N + r) = 0 and
// the fault gain is K_eta = -p / (p + q_N + r) (about -1e-3 per tick, tau ~ 1 s, with the
// paper's values). `ready` is 1 once p is within `ready_tolerance` of that steady state (before
// that the estimate is an initialisation transient, not evidence) and both inputs are finite on
// this tick: a NaN or Inf virtual value means the virtual sensor is not ready, the channel's state
// holds and no fault is blamed on the sensor.
//
// Covariance: each channel keeps [[a, b], [b, c]] as three numbers, so it is symmetric by
// construction; the update is P = P- - (P- H^T)(P- H^T)^T / S. A non-finite or non-positive
// variance (it cannot happen with valid parameters, but data can be hostile) resets that channel
// and is reported: output `covariance_resets` counts the resets of each channel since reset().
// Output `fault_variance` is p itself, for health monitoring (it stays in (0, P0 + k q_eta]).
// A non-finite input skips the update for that channel: the state holds.
// Units: eta and N in the unit of the inputs (N for forces); q and r in that unit squared.

#include <string_view>
#include <vector>

#include "ftsense/plugin.hpp"

namespace ftsense::generic {

class RandomWalkFaultFilter {
 public:
  static constexpr std::string_view name = "random_walk_fault_filter";
  static constexpr std::string_view summary =
      "Kalman filter of a random-walk sensor fault eta from measured - virtual (paper eq. 24-32)";

  struct Params {
    double fault_process_noise = 1e-10;
    double force_process_noise = 1e-10;
    double measurement_noise = 1e-4;
    double initial_fault_variance = 1e-4;
    double ready_tolerance = 0.1;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kMeasured, kVirtual };
  enum Output : std::size_t { kFaultEstimate, kTrueEstimate, kReady, kFaultVariance, kCovarianceResets };

  RandomWalkFaultFilter(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

  // The fault gain K_eta applied at the last update of channel j, and its steady-state value.
  [[nodiscard]] double fault_gain(std::size_t j) const noexcept { return channels_[j].fault_gain; }
  [[nodiscard]] double steady_state_fault_gain() const noexcept;
  [[nodiscard]] double steady_state_fault_variance() const noexcept { return steady_variance_; }
  [[nodiscard]] double fault_variance(std::size_t j) const noexcept { return channels_[j].p_fault; }
  // Number of covariance resets of all channels since reset() (a health counter for reports).
  [[nodiscard]] std::size_t covariance_resets() const noexcept { return covariance_resets_; }

 private:
  struct Channel {
    double fault = 0.0;     // eta_hat
    double p_fault = 0.0;   // a = var(eta)
    double p_cross = 0.0;   // b = cov(eta, N)
    double p_force = 0.0;   // c = var(N)
    double fault_gain = 0.0;
    double resets = 0.0;    // covariance resets of this channel since reset()
  };
  void reset_channel(Channel& c) const noexcept;

  Ports ports_;
  Params params_;
  double steady_variance_ = 0.0;
  std::vector<Channel> channels_;
  std::size_t covariance_resets_ = 0;
};

}  // namespace ftsense::generic
