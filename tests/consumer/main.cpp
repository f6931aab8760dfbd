// Uses the installed ftsense: the reference plugins plus a plugin of its own, added to the set
// without editing ftsense, wired by JSON.

#include <cmath>
#include <iostream>

#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"

// y = gain * x: a user's own plugin.
class Scale {
 public:
  static constexpr std::string_view name = "scale";
  static constexpr std::string_view summary = "y = gain x";
  struct Params {
    double gain = 1.0;
    static void describe(ftsense::ParamSchema<Params>& s) { s.add("gain", &Params::gain, "the factor"); }
  };
  Scale(const Params& p, const ftsense::StageContext& context) : gain_(p.gain) {
    const std::size_t n = context.wired_dim("x", 1);
    ports_.add_input({"x", n, "", "input"});
    ports_.add_output({"y", n, "", "gain * x"});
  }
  const ftsense::Ports& ports() const noexcept { return ports_; }
  void reset() noexcept {}
  void step(const ftsense::StepIO& io) noexcept {
    for (std::size_t i = 0; i < io.out(0).size(); ++i) io.out(0)[i] = gain_ * io.in(0)[i];
  }

 private:
  double gain_;
  ftsense::Ports ports_;
};

using my_plugins = ftsense::reference_plugins::with<Scale>;

int main() {
  const auto config = ftsense::parse_json_text(R"({
    "sample_period_s": 0.001,
    "inputs": {"x": {"columns": ["x"], "unit": "N"}},
    "stages": [
      {"name": "double_it", "plugin": "scale", "params": {"gain": 2.0}, "inputs": {"x": "input.x"}},
      {"name": "smooth", "plugin": "low_pass", "params": {"cutoff_hz": 5.0}, "inputs": {"signal": "double_it.y"}}
    ]})", "consumer");
  ftsense::Pipeline pipeline = ftsense::Pipeline::build(config, my_plugins::registry());
  for (int k = 0; k < 100; ++k) {
    pipeline.input_values(0)[0] = 21.0;
    pipeline.step(k * 1e-3);
  }
  const double y = pipeline.values(pipeline.signal("smooth.filtered"))[0];
  if (std::abs(y - 42.0) > 1e-9) {
    std::cerr << "consumer: expected 42, got " << y << '\n';
    return 1;
  }
  std::cout << "consumer ok: " << y << '\n';
  return 0;
}
