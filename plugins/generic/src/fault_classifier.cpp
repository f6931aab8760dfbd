#include "ftsense/generic/fault_classifier.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <string>

#include "ftsense/channel_values.hpp"
#include "ftsense/generic/chi_square.hpp"
#include "ftsense/plausible_ranges.hpp"

namespace ftsense::generic {

namespace {

// The four models in the order of the fit table; ties go to the earlier (simpler) one.
constexpr std::array<FaultType, 4> kModels{FaultType::offset, FaultType::drift, FaultType::gain, FaultType::frozen};
enum Model : std::size_t { kOffset, kDrift, kGain, kFrozen };

// |k| below this is no gain to divide by (the recovered value falls back to the reference).
constexpr double kMinGain = 1e-9;

struct ModelFit {
  double rss = std::numeric_limits<double>::infinity();  // weighted: in units of chi^2
  double size = 0.0;      // b, s, k or c
  double onset_s = 0.0;   // time of the onset block
  double sum_vv = 0.0;    // gain only: sum w_i v_i^2 after the onset (the uncertainty of k)
};

// Weighted suffix sums over the blocks i >= i0 that hold a value (each term times w_i).
struct Sums {
  double n = 0.0, e = 0.0, ee = 0.0, x = 0.0, xx = 0.0, ev = 0.0, vv = 0.0, t = 0.0, tt = 0.0, et = 0.0;
};

}  // namespace

void FaultClassifier::Params::describe(ParamSchema<Params>& schema) {
  schema
      .add("residual_noise_density", &Params::residual_noise_density,
           "low-frequency noise density q of the fault-free e = measured - virtual, in its unit times sqrt(s): "
           "the mean of e over w seconds has standard deviation q / sqrt(w); one value applies to all")
      .greater_than(0.0)
      .count_at_least(1);
  schema
      .add("exact_residual", &Params::exact_residual,
           "adds input exact_residual: measured minus a reference exact up to the sensor's own noise on the ticks "
           "where it is finite (unloaded_reading_residual: a channel that carries no load reads zero)");
  schema
      .add("exact_noise_density", &Params::exact_noise_density,
           "low-frequency noise density q_e of exact_residual's fault-free samples (unit times sqrt(s)); one value "
           "applies to all; used when exact_residual is wired")
      .greater_than(0.0)
      .count_at_least(1);
  schema.add("block_s", &Params::block_s, "length of the blocks whose means are fitted (a whole number of ticks)")
      .unit("s")
      .greater_than(0.0)
      .plausible(0.001, 2.0, "from a tick to a couple of seconds");
  schema.add("history_s", &Params::history_s, "how far back the fault's onset is searched and the models fitted")
      .unit("s")
      .greater_than(0.0)
      .plausible(1.0, 600.0, "from a second to ten minutes");
  schema
      .add("same_episode_s", &Params::same_episode_s,
           "a flag that drops for less than this and comes back continues the episode (a detector's chatter)")
      .unit("s")
      .at_least(0.0)
      .plausible(0.0, 10.0, "up to a few seconds");
  schema
      .add("confidence", &Params::confidence,
           "a model is named when every other leaves chi^2_1(confidence) more (log-likelihood ratio)")
      .greater_than(0.5)
      .less_than(1.0);
}

FaultClassifier::FaultClassifier(const Params& params, const StageContext& context)
    : exact_wired_(params.exact_residual) {
  const double period = context.sample_period_s();
  sample_period_s_ = period;
  channels_count_ = context.wired_dim("measured", 1);
  const std::vector<double> density =
      channel_values(params.residual_noise_density, channels_count_, "residual_noise_density");
  ticks_per_block_ = std::max(1, static_cast<int>(std::lround(params.block_s / period)));
  block_s_ = ticks_per_block_ * period;
  const double blocks_in_history = std::ceil(params.history_s / block_s_);
  if (!(blocks_in_history >= 4.0)) {
    throw ConfigError("/params/history_s", " = " + format_number(params.history_s) + " s holds fewer than 4 blocks of " +
                                               format_number(block_s_) + " s: make it longer or block_s shorter");
  }
  if (blocks_in_history > 1e6) {
    throw ConfigError("/params/history_s", " = " + format_number(params.history_s) + " s is more than a million blocks of " +
                                               format_number(block_s_) + " s: make it shorter or block_s longer");
  }
  capacity_ = static_cast<std::size_t>(blocks_in_history);
  same_episode_blocks_ = static_cast<long>(std::ceil(params.same_episode_s / block_s_));
  fits_per_tick_ = (channels_count_ + static_cast<std::size_t>(ticks_per_block_) - 1) /
                   static_cast<std::size_t>(ticks_per_block_);
  const double z = normal_quantile(0.5 + 0.5 * params.confidence);
  margin_ = z * z;
  const std::vector<double> exact_density =
      channel_values(params.exact_noise_density, channels_count_, "exact_noise_density");
  density2_.resize(channels_count_);
  exact_density2_.resize(channels_count_);
  for (std::size_t c = 0; c < channels_count_; ++c) {
    density2_[c] = density[c] * density[c];
    exact_density2_[c] = exact_density[c] * exact_density[c];
  }
  ports_.add_input(PortSpec{"fault", channels_count_, std::string(kDimensionless),
                            "1 while the channel is flagged (isolated) as faulty; 0 or NaN: not"}
                       .sized_by("as `measured`"));
  ports_.add_input(PortSpec{"measured", channels_count_, std::string(kAnyUnit), "the monitored sensor x",
                            PortRole::measured}
                       .sized_by("as wired"));
  ports_.add_input(PortSpec{"virtual", channels_count_, std::string(kAnyUnit),
                            "the reference v: a virtual sensor's estimate of the same quantity",
                            PortRole::virtual_estimate}
                       .sized_by("as `measured`"));
  if (exact_wired_) {
    ports_.add_input(PortSpec{"exact_residual", channels_count_, std::string(kAnyUnit),
                              "measured minus a reference exact up to the sensor's own noise (e.g. 0 for a "
                              "channel that carries no load); NaN on the ticks where no such reference holds"}
                         .sized_by("as `measured`"));
  }
  ports_.add_output(PortSpec{"fault_type", channels_count_, std::string(kDimensionless),
                             "fault type code (fault_type.hpp): the named model while flagged (unclassified "
                             "until one is named), else none"}
                        .sized_by("as `measured`"));
  ports_.add_output(PortSpec{"fault_estimate", channels_count_, std::string(kAnyUnit),
                             "the fault in x's unit, so that x - estimate is the recovered value: b, s (t - t0), "
                             "x (1 - 1/k), or x - v (frozen, unclassified); 0 while not flagged"}
                        .sized_by("as `measured`"));
  block_x_.assign(channels_count_ * capacity_, 0.0);
  block_v_.assign(channels_count_ * capacity_, 0.0);
  block_w_.assign(channels_count_ * capacity_, 0.0);
  block_time_.assign(capacity_, 0.0);
  channels_.assign(channels_count_, Channel{});
}

void FaultClassifier::reset() noexcept {
  std::fill(block_x_.begin(), block_x_.end(), 0.0);
  std::fill(block_v_.begin(), block_v_.end(), 0.0);
  std::fill(block_w_.begin(), block_w_.end(), 0.0);
  std::fill(block_time_.begin(), block_time_.end(), 0.0);
  std::fill(channels_.begin(), channels_.end(), Channel{});
  blocks_ = 0;
  tick_in_block_ = 0;
  next_due_ = 0;
  block_time_sum_ = 0.0;
}

void FaultClassifier::step(const StepIO& io) noexcept {
  const auto fault = io.in(kFault);
  const auto x = io.in(kMeasured);
  const auto v = io.in(kVirtual);
  const std::span<const double> exact = exact_wired_ ? io.in(kExactResidual) : std::span<const double>{};
  const auto type = io.out(kFaultType);
  const auto estimate = io.out(kFaultEstimate);
  block_time_sum_ += io.time_s;
  for (std::size_t c = 0; c < channels_count_; ++c) {
    Channel& ch = channels_[c];
    if (exact_wired_ && std::isfinite(x[c]) && std::isfinite(exact[c])) {
      // The exact reference x - r_e stands in for v on this tick (v is then exact too, or NaN).
      ch.sum_x += x[c];
      ch.sum_v += x[c] - exact[c];
      ++ch.count;
      ++ch.exact_count;
      ch.sum_exact += exact[c];
      ch.sum_exact2 += exact[c] * exact[c];
    } else if (std::isfinite(x[c]) && std::isfinite(v[c])) {
      ch.sum_x += x[c];
      ch.sum_v += v[c];
      ++ch.count;
    }
    const bool flagged = std::isfinite(fault[c]) && fault[c] != 0.0;
    if (flagged && !ch.flagged) {
      const bool same_episode = ch.first_flagged >= 0 && blocks_ - ch.cleared_at < same_episode_blocks_;
      if (!same_episode) {
        // A new episode: its fit starts after the block in which the last one was re-admitted
        // (that block still held faulty samples).
        if (ch.first_flagged >= 0) ch.window_start = std::min(ch.cleared_at + 1, blocks_);
        ch.first_flagged = blocks_;  // the block being filled
        ch.fit = Fit{};
      }
    }
    if (!flagged && ch.flagged) ch.cleared_at = blocks_;
    ch.flagged = flagged;
  }
  if (++tick_in_block_ == ticks_per_block_) {
    const std::size_t slot = static_cast<std::size_t>(blocks_ % static_cast<long>(capacity_));
    block_time_[slot] = block_time_sum_ / ticks_per_block_;
    for (std::size_t c = 0; c < channels_count_; ++c) {
      Channel& ch = channels_[c];
      const double nan = std::numeric_limits<double>::quiet_NaN();
      block_x_[c * capacity_ + slot] = ch.count > 0 ? ch.sum_x / ch.count : nan;
      block_v_[c * capacity_ + slot] = ch.count > 0 ? ch.sum_v / ch.count : nan;
      // 1 / Var(mean e) = n^2 / (n_r q^2 / T + n_e s_e^2): the header's block weight, with the
      // exact ticks' spread s_e^2 = max(q_e^2 / T, their own sample variance).
      const double n = ch.count;
      const double n_exact = ch.exact_count;
      double exact_spread = exact_density2_[c] / sample_period_s_;
      if (ch.exact_count >= 2) {
        const double own = (ch.sum_exact2 - ch.sum_exact * ch.sum_exact / n_exact) / (n_exact - 1.0);
        exact_spread = std::max(exact_spread, own);
      }
      const double spread = (n - n_exact) * density2_[c] / sample_period_s_ + n_exact * exact_spread;
      block_w_[c * capacity_ + slot] = ch.count > 0 ? n * n / spread : 0.0;
      ch.sum_x = ch.sum_v = 0.0;
      ch.sum_exact = ch.sum_exact2 = 0.0;
      ch.count = 0;
      ch.exact_count = 0;
    }
    ++blocks_;
    tick_in_block_ = 0;
    block_time_sum_ = 0.0;
    for (Channel& ch : channels_) ch.due = ch.flagged;
  }
  // The fits of a block's flagged channels are spread over the block's ticks, at most
  // ceil(channels / ticks per block) a tick, so no tick carries them all.
  for (std::size_t fits = 0, looked = 0; fits < fits_per_tick_ && looked < channels_count_; ++looked) {
    const std::size_t c = next_due_;
    next_due_ = (next_due_ + 1) % channels_count_;
    if (!channels_[c].due) continue;
    channels_[c].due = false;
    if (channels_[c].flagged) classify(c);
    ++fits;
  }
  for (std::size_t c = 0; c < channels_count_; ++c) {
    const Channel& ch = channels_[c];
    if (!ch.flagged) {
      type[c] = fault_code(FaultType::none);
      estimate[c] = 0.0;
      continue;
    }
    type[c] = fault_code(ch.fit.type);
    double f = x[c] - v[c];  // frozen, unclassified: recovered = x - (x - v) = v
    switch (ch.fit.type) {
      case FaultType::offset: f = ch.fit.size; break;
      case FaultType::drift: f = ch.fit.size * std::max(0.0, io.time_s - ch.fit.onset_s); break;
      case FaultType::gain:  // named only for k clear of 0; guard the division all the same
        if (std::abs(ch.fit.size) > kMinGain) f = x[c] * (1.0 - 1.0 / ch.fit.size);
        break;
      default: break;
    }
    estimate[c] = std::isfinite(f) ? f : 0.0;
  }
}

void FaultClassifier::classify(std::size_t c) noexcept {
  Channel& ch = channels_[c];
  const long end = blocks_;
  const long start = std::max(ch.window_start, end - static_cast<long>(capacity_));
  if (end - start < 2) return;
  const long last_onset = std::clamp(ch.first_flagged, start, end - 1);
  const double* bx = block_x_.data() + c * capacity_;
  const double* bv = block_v_.data() + c * capacity_;
  const double* bw = block_w_.data() + c * capacity_;
  const auto slot = [&](long i) { return static_cast<std::size_t>(i % static_cast<long>(capacity_)); };
  const double t_ref = block_time_[slot(start)];  // times relative to the window: well conditioned

  double total_ee = 0.0;
  for (long i = start; i < end; ++i) {
    const double e = bx[slot(i)] - bv[slot(i)];
    if (std::isfinite(e)) total_ee += bw[slot(i)] * e * e;
  }
  std::array<ModelFit, 4> best{};
  Sums s;  // over the blocks after i
  for (long i = end - 1; i >= start; --i) {
    const double xi = bx[slot(i)], vi = bv[slot(i)], ti = block_time_[slot(i)] - t_ref;
    const double e = xi - vi;
    const double wi = std::isfinite(e) ? bw[slot(i)] : 0.0;
    if (i <= last_onset && s.n > 0.0) {
      // Onset within block i: e = 0 before it, the model after it; block i itself holds the
      // fault for an unknown share of its ticks (a step there is a ramp's first point), so no
      // model is asked to explain it.
      const double own = wi > 0.0 ? wi * e * e : 0.0;  // an empty block (e NaN) owns no misfit
      const double before = std::max(0.0, total_ee - s.ee - own);
      const double onset_s = ti + t_ref;
      const auto keep = [&](std::size_t m, double after, double size, double vv = 0.0) {
        const double rss = before + std::max(0.0, after);
        // A tie keeps the later onset: a fault that begins on a block's first tick also fits an
        // onset within the block before (its share there is 0), which rounding must not pick.
        const bool better =
            std::isfinite(rss) && (!std::isfinite(best[m].rss) || rss < best[m].rss - 1e-12 * (1.0 + best[m].rss));
        if (better) best[m] = ModelFit{rss, size, onset_s, vv};
      };
      keep(kOffset, s.ee - s.e * s.e / s.n, s.e / s.n);
      const double dd = s.tt - 2.0 * ti * s.t + s.n * ti * ti;  // sum w (t - t_i0)^2
      const double ed = s.et - ti * s.e;                         // sum w e (t - t_i0)
      if (dd > 0.0) keep(kDrift, s.ee - ed * ed / dd, ed / dd);
      // A reference at 0 throughout fits no gain.
      if (s.vv > 0.0) keep(kGain, s.ee - s.ev * s.ev / s.vv, 1.0 + s.ev / s.vv, s.vv);
      keep(kFrozen, s.xx - s.x * s.x / s.n, s.x / s.n);
    }
    if (wi > 0.0) {
      s.n += wi;
      s.e += wi * e;
      s.ee += wi * e * e;
      s.x += wi * xi;
      s.xx += wi * xi * xi;
      s.ev += wi * e * vi;
      s.vv += wi * vi * vi;
      s.t += wi * ti;
      s.tt += wi * ti * ti;
      s.et += wi * e * ti;
    }
  }

  // A gain whose k is not told from 0 is the frozen-at-zero explanation: one hypothesis.
  const ModelFit& gain = best[kGain];
  const bool gain_is_dead = std::isfinite(gain.rss) && gain.size * gain.size * gain.sum_vv < margin_;
  if (gain_is_dead) {
    if (gain.rss < best[kFrozen].rss) best[kFrozen] = ModelFit{gain.rss, 0.0, gain.onset_s, 0.0};
    best[kGain].rss = std::numeric_limits<double>::infinity();
  }
  std::size_t winner = 0;
  for (std::size_t m = 1; m < kModels.size(); ++m) {
    if (best[m].rss < best[winner].rss) winner = m;
  }
  if (!std::isfinite(best[winner].rss)) return;
  bool named = true;
  for (std::size_t m = 0; m < kModels.size(); ++m) {
    if (m != winner && best[m].rss - best[winner].rss < margin_) named = false;
  }
  if (named) {
    ch.fit.type = kModels[winner];
  } else {
    // A named type that another model now fits better by the margin is refuted, though no model
    // stands apart yet (two that fit alike: a reading stuck in the air is an offset and a frozen
    // output at once): the type is unclassified again, and the recovery takes the reference.
    for (std::size_t m = 0; m < kModels.size(); ++m) {
      if (kModels[m] == ch.fit.type && best[m].rss - best[winner].rss >= margin_) ch.fit.type = FaultType::unclassified;
    }
  }
  // The named model's latest fit (its size and onset follow the growing window).
  for (std::size_t m = 0; m < kModels.size(); ++m) {
    if (kModels[m] == ch.fit.type && std::isfinite(best[m].rss)) {
      ch.fit.size = best[m].size;
      ch.fit.onset_s = best[m].onset_s;
    }
  }
}

}  // namespace ftsense::generic
