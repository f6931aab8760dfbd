#pragma once
// Design of a CUSUM test from a false-alarm target: Siegmund's approximation of the average run
// length, and its inverse.
//
// A one-sided CUSUM on independent unit-variance samples z_n with reference value k,
//
//   S_n = max(0, S_{n-1} + z_n - k),   alarm when S_n >= h,
//
// has, while z_n has mean mu, the average run length (in samples; Siegmund 1985, eq. 2.56)
//
//   ARL(mu) = (exp(-2 D b) + 2 D b - 1) / (2 D^2),   D = mu - k,   b = h + overshoot,
//
// (b^2 when D = 0), where overshoot = 2 * 0.583 * (step standard deviation) = 1.166 for unit
// steps: the mean excess of a Gaussian random walk over a boundary. In control (mu = 0) this is
// the mean time between false alarms; for a shift mu > k it is the mean detection delay.
// All quantities are in units of the sample's standard deviation and in samples.

namespace ftsense::generic {

// Expected overshoot term of a Gaussian random walk whose steps have standard deviation
// `step_std` (2 x 0.583 x step_std).
[[nodiscard]] double cusum_overshoot(double step_std) noexcept;

// ARL(mu) above for drift D = mu - k and boundary b = h + overshoot (both > 0 for a meaningful
// result); samples.
[[nodiscard]] double cusum_average_run_length(double drift, double boundary) noexcept;

// The threshold h >= 0 whose in-control ARL (mu = 0, reference value k > 0) is
// `in_control_arl` samples, for steps with the given overshoot term. When even h = 0 gives a
// longer ARL than asked, h = 0. Solved by bisection on b (ARL is increasing in b).
[[nodiscard]] double cusum_threshold_for_arl(double reference_value, double in_control_arl,
                                             double overshoot) noexcept;

}  // namespace ftsense::generic
