#include "ftsense/generic/tick_noise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "ftsense/generic/sample_median.hpp"

namespace ftsense::generic {

namespace {
// Below this estimate of r the share of changes judges the noise; at or above it, the second
// differences (header).
constexpr double kSecondDifferencesFrom = 0.5;

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

}  // namespace

void TickNoise::add(double x) {
  if (!std::isfinite(x)) {
    break_sequence();
    return;
  }
  readings_.push_back(x);
  analysis_.reset();
}

void TickNoise::break_sequence() {
  if (!readings_.empty() && !std::isnan(readings_.back())) readings_.push_back(std::nan(""));
  analysis_.reset();
}

double TickNoise::change_probability(double r) {
  // Two readings at the same place u differ by D = n_1 - n_2 ~ N(0, 2 r^2) (in steps); over u
  // uniform they share a level with probability E[max(0, 1 - |D|)]. With s = sqrt(2) r:
  // E = erf(1 / (s sqrt 2)) - s sqrt(2 / pi) (1 - exp(-1 / (2 s^2))).
  const double stay =
      std::erf(0.5 / r) - 2.0 * r / std::sqrt(std::numbers::pi) * -std::expm1(-0.25 / (r * r));
  return 1.0 - stay;
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
  // The smallest step that recurs (on 1 % of the changes or more): a driver's clamp to 0 or a
  // reset puts a few changes off the lattice, and a continuous reading has no recurring step
  // (nor has a log printed with fixed decimals much finer than its noise: each multiple of the
  // decimal is too rare).
  std::sort(steps.begin(), steps.end());
  const double recurring = std::max(2.0, 0.01 * static_cast<double>(steps.size()));
  double smallest = 0.0;
  for (std::size_t i = 0; i < steps.size();) {
    std::size_t j = i;
    while (j < steps.size() && steps[j] <= steps[i] * (1.0 + 1e-3)) ++j;
    if (static_cast<double>(j - i) >= recurring) {
      smallest = steps[i];
      break;
    }
    i = j;
  }
  if (smallest == 0.0) return 0.0;
  double sum = 0.0, multiples = 0.0;
  std::size_t on_lattice = 0;
  for (double d : steps) {
    const double k = std::round(d / smallest);
    if (k >= 1.0 && std::abs(d - k * smallest) <= 0.01 * smallest) {
      ++on_lattice;
      sum += d;
      multiples += k;
    }
  }
  if (static_cast<double>(on_lattice) < kOnLatticeShare * static_cast<double>(steps.size())) return 0.0;
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
                             : sample_median(abs_d2) / (kMedianAbsStandardNormal * std::sqrt(6.0));
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
        const double bins = std::abs(readings_[k] - 2.0 * readings_[k - 1] + readings_[k - 2]) / q;
        if (bins < 1e15) s.d2_bins.push_back(std::llround(bins));  // (not an overflow)
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
  // step stays in with probability kLongRunProbability. Each step shortens the bound and is kept
  // only while r rises (leaving a run out also leaves out the changes at its ends, so r need not
  // rise): at most 30 steps, and the statistics below use the bound r was measured with.
  double long_run = std::numeric_limits<double>::infinity();
  double r = r_of(shares_without_runs_of(long_run, false));
  for (int i = 0; i < 30 && std::isfinite(r); ++i) {
    // ln P(stay) in the middle of a step, = ln(1 - erfc(...)): exact where erf rounds to 1.
    const double log_stay = std::log1p(-std::erfc(1.0 / (2.0 * std::numbers::sqrt2 * r)));
    if (!(log_stay < 0.0)) break;  // no run is unlikely: none is left out
    const double next_bound = std::max(3.0, std::ceil(std::log(kLongRunProbability) / log_stay));
    if (!(next_bound < long_run)) break;
    const double next = r_of(shares_without_runs_of(next_bound, false));
    if (!(next > r)) break;  // the bound stays where r was measured
    long_run = next_bound;
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
  const double sigma_d2 = binned_median(std::move(s.d2_bins)) * q / (kMedianAbsStandardNormal * std::sqrt(6.0));
  a.sigma = std::sqrt(std::max(sigma_d2 * sigma_d2 - q * q / 12.0, 0.0));
  return a;
}

const TickNoise::Analysis& TickNoise::analysis() const {
  if (!analysis_) analysis_ = analyse();
  return *analysis_;
}

std::size_t TickNoise::count() const { return analysis().count; }
double TickNoise::standard_deviation() const { return analysis().sigma; }
double TickNoise::resolution() const { return analysis().resolution; }

}  // namespace ftsense::generic
