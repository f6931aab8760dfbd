#include "ftsense/generic/tick_noise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace ftsense::generic {

namespace {
// median(|Z|) for a standard normal Z: the 75 % quantile.
constexpr double kMedianAbsNormal = 0.6744897501960817;
// Below this estimate of r the share of changes judges the noise; at or above it, the second
// differences (header).
constexpr double kSecondDifferencesFrom = 0.5;

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

// The median of values v_i >= 0 that are whole multiples of a bin (v_i / bin = k_i), interpolated
// within its bin [k - 1/2, k + 1/2) bin ([0, 1/2) bin for k = 0), in units of the bin.
double binned_median(std::vector<long long> k) {
  std::sort(k.begin(), k.end());
  const double half = 0.5 * static_cast<double>(k.size());
  const long long middle = k[k.size() / 2];
  const auto below = static_cast<double>(std::lower_bound(k.begin(), k.end(), middle) - k.begin());
  const auto in_bin = static_cast<double>(std::upper_bound(k.begin(), k.end(), middle) - k.begin()) - below;
  const double low = middle == 0 ? 0.0 : static_cast<double>(middle) - 0.5;
  const double width = middle == 0 ? 0.5 : 1.0;
  return low + (half - below) / in_bin * width;
}

double plain_median(std::vector<double> v) {
  const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), middle, v.end());
  double median = *middle;
  if (v.size() % 2 == 0) median = 0.5 * (median + *std::max_element(v.begin(), middle));
  return median;
}
}  // namespace

void TickNoise::add(double x) {
  if (!std::isfinite(x)) {
    break_sequence();
    return;
  }
  readings_.push_back(x);
}

void TickNoise::break_sequence() {
  if (!readings_.empty() && !std::isnan(readings_.back())) readings_.push_back(std::nan(""));
}

double TickNoise::change_probability(double r) {
  // Midpoint rule over u in [0, 1) and the levels within 8 r + 2 of it.
  constexpr int kPlaces = 256;
  const int reach = static_cast<int>(std::ceil(8.0 * r)) + 2;
  double stay = 0.0;
  for (int i = 0; i < kPlaces; ++i) {
    const double u = (i + 0.5) / kPlaces;
    for (int l = -reach; l <= reach + 1; ++l) {
      const double p = normal_cdf((l + 0.5 - u) / r) - normal_cdf((l - 0.5 - u) / r);
      stay += p * p;
    }
  }
  return 1.0 - stay / kPlaces;
}

double TickNoise::noise_over_step(double p) {
  double low = std::log(1e-4), high = std::log(1e4);
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (low + high);
    (change_probability(std::exp(mid)) < p ? low : high) = mid;
  }
  return std::exp(0.5 * (low + high));
}

double TickNoise::lattice_step() const {
  std::vector<double> steps;
  for (std::size_t k = 1; k < readings_.size(); ++k) {
    const double d = std::abs(readings_[k] - readings_[k - 1]);
    if (d > 0.0 && std::isfinite(d)) steps.push_back(d);  // NaN (a break) fails d > 0
  }
  if (steps.size() < kMinLatticeSteps) return 0.0;
  const double smallest = *std::min_element(steps.begin(), steps.end());
  double sum = 0.0, multiples = 0.0;
  std::size_t on_lattice = 0;
  for (double d : steps) {
    const double k = std::round(d / smallest);
    if (std::abs(d - k * smallest) <= 0.01 * smallest) {
      ++on_lattice;
      sum += d;
      multiples += k;
    }
  }
  if (static_cast<double>(on_lattice) < 0.99 * static_cast<double>(steps.size())) return 0.0;
  return sum / multiples;
}

TickNoise::Analysis TickNoise::analyse() const {
  Analysis a;
  a.resolution = lattice_step();
  const std::size_t n = readings_.size();
  const auto finite = [&](std::size_t k) { return !std::isnan(readings_[k]); };
  if (a.resolution == 0.0) {
    std::vector<double> abs_d2;
    for (std::size_t k = 2; k < n; ++k) {
      const double x = readings_[k], x1 = readings_[k - 1], x2 = readings_[k - 2];
      if (!finite(k) || !finite(k - 1) || !finite(k - 2) || (x == x1 && x1 == x2)) continue;
      abs_d2.push_back(std::abs(x - 2.0 * x1 + x2));
    }
    a.count = abs_d2.size();
    a.sigma = abs_d2.empty() ? std::numeric_limits<double>::quiet_NaN()
                             : plain_median(abs_d2) / (kMedianAbsNormal * std::sqrt(6.0));
    return a;
  }
  const double q = a.resolution;
  // Pairs outside long runs, and their changes; the second differences (in steps) likewise.
  struct Shares {
    std::size_t pairs = 0, changes = 0;
    std::vector<long long> d2_bins;
  };
  const auto shares_without_runs_of = [&](double long_run, bool with_d2) {
    std::vector<bool> kept(n, false);
    for (std::size_t start = 0; start < n;) {
      std::size_t end = start + 1;
      while (end < n && readings_[end] == readings_[start]) ++end;  // NaN equals nothing
      if (finite(start) && static_cast<double>(end - start) < long_run) {
        std::fill(kept.begin() + static_cast<std::ptrdiff_t>(start), kept.begin() + static_cast<std::ptrdiff_t>(end),
                  true);
      }
      start = end;
    }
    Shares s;
    for (std::size_t k = 1; k < n; ++k) {
      if (!kept[k] || !kept[k - 1]) continue;
      ++s.pairs;
      if (readings_[k] != readings_[k - 1]) ++s.changes;
      if (with_d2 && k >= 2 && kept[k - 2]) {
        const double d2 = readings_[k] - 2.0 * readings_[k - 1] + readings_[k - 2];
        s.d2_bins.push_back(std::llround(std::abs(d2) / q));
      }
    }
    return s;
  };
  const auto r_of = [](const Shares& s) {
    if (s.pairs == 0) return std::numeric_limits<double>::quiet_NaN();
    const double share = static_cast<double>(s.changes) / static_cast<double>(s.pairs);
    return share < 1.0 ? noise_over_step(share) : std::numeric_limits<double>::infinity();
  };
  // The long-run bound follows r: from none (all pairs), to the run a reading at the middle of its
  // step stays in with probability kLongRunProbability. Each estimate of r is at least the
  // previous one (fewer runs of repeats left in), so this converges upwards.
  double long_run = std::numeric_limits<double>::infinity();
  double r = r_of(shares_without_runs_of(long_run, false));
  for (int i = 0; i < 30 && std::isfinite(r); ++i) {
    const double stay_in_the_middle = std::erf(1.0 / (2.0 * std::numbers::sqrt2 * r));
    const double next_bound = std::max(3.0, std::ceil(std::log(kLongRunProbability) / std::log(stay_in_the_middle)));
    if (!(next_bound < long_run)) break;
    long_run = next_bound;
    const double next = r_of(shares_without_runs_of(long_run, false));
    if (!(next > r)) break;
    r = next;
  }
  Shares s = shares_without_runs_of(long_run, true);
  a.count = s.pairs;
  if (s.pairs == 0) {
    a.sigma = std::numeric_limits<double>::quiet_NaN();
    return a;
  }
  if (r < kSecondDifferencesFrom || s.d2_bins.empty()) {
    a.sigma = r * q;
    return a;
  }
  const double sigma_d2 = binned_median(std::move(s.d2_bins)) * q / (kMedianAbsNormal * std::sqrt(6.0));
  a.sigma = std::sqrt(std::max(sigma_d2 * sigma_d2 - q * q / 12.0, 0.0));
  return a;
}

std::size_t TickNoise::count() const { return analyse().count; }
double TickNoise::standard_deviation() const { return analyse().sigma; }
double TickNoise::resolution() const { return analyse().resolution; }

}  // namespace ftsense::generic
