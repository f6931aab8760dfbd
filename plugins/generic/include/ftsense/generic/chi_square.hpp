#pragma once
// Quantiles for tests on sample variances: the standard normal's and the chi-square's.
//
// A sum of squares of nu independent N(0, s^2) samples is s^2 chi^2_nu; a window of a white
// signal's variance estimate falls below s^2 q(alpha) / nu with probability alpha, where
// q(alpha) = chi_square_quantile(nu, alpha). The chi-square quantile uses the Wilson-Hilferty
// cube-root approximation, chi^2_nu(p) = nu (1 - 2/(9 nu) + z_p sqrt(2/(9 nu)))^3, within about
// 1 % for nu >= 10 at the tail probabilities the detectors use (1e-9 .. 0.5), and kept >= 0.

namespace ftsense::generic {

// z with P(Z <= z) = p for a standard normal Z, 0 < p < 1 (bisection on erfc; setup time only).
[[nodiscard]] double normal_quantile(double p) noexcept;

// x with P(chi^2_nu <= x) = p, nu > 0 (may be fractional), 0 < p < 1.
[[nodiscard]] double chi_square_quantile(double nu, double p) noexcept;
// The same at p = P(Z <= z), z given (no bisection: cheap enough for a step).
[[nodiscard]] double chi_square_quantile_at_z(double nu, double z) noexcept;

}  // namespace ftsense::generic
