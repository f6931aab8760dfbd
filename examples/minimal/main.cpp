// The smallest ftsense program: build a pipeline from a JSON file, step it over synthetic
// samples, print what it finds. Copy this file and minimal.json to start your own.
//
//   minimal [config.json]
//
// Three force cells measure the same load as a model predicts; at t = 1 s cell c2 gains a
// +20 N offset. The pipeline (difference -> low-pass -> threshold) flags it.

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <numbers>
#include <random>
#include <sstream>

#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"

#ifndef FTSENSE_MINIMAL_CONFIG
#define FTSENSE_MINIMAL_CONFIG "minimal.json"
#endif

int main(int argc, char** argv) {
  const std::string config_path = argc > 1 ? argv[1] : FTSENSE_MINIMAL_CONFIG;
  std::ifstream file(config_path);
  if (!file) {
    std::cerr << config_path << ": cannot open\n";
    return 2;
  }
  std::stringstream text;
  text << file.rdbuf();

  try {
    ftsense::Pipeline pipeline = ftsense::Pipeline::build(
        ftsense::parse_json_text(text.str(), config_path), ftsense::reference_plugins::registry());
    const ftsense::Monitor& monitor = pipeline.monitor();

    constexpr std::uint64_t kSeed = 7;
    std::cout << "noise seed " << kSeed << '\n';
    std::mt19937_64 rng(kSeed);
    std::normal_distribution<double> noise(0.0, 1.0);  // 1 N RMS cell noise

    std::vector<double> first_alarm(monitor.channels.size(), -1.0);
    const double dt = pipeline.sample_period_s();
    for (int k = 0; k < 3000; ++k) {
      const double t = k * dt;
      const double load = 100.0 + 20.0 * std::sin(2.0 * std::numbers::pi * 0.5 * t);
      auto measured = pipeline.input_values(0);
      auto reference = pipeline.input_values(1);
      for (std::size_t c = 0; c < measured.size(); ++c) {
        reference[c] = load;
        measured[c] = load + noise(rng) + ((c == 1 && t >= 1.0) ? 20.0 : 0.0);
      }
      pipeline.step(t);
      const auto fault = pipeline.values(monitor[ftsense::MonitorColumn::fault]);
      for (std::size_t c = 0; c < fault.size(); ++c) {
        if (fault[c] != 0.0 && first_alarm[c] < 0.0) first_alarm[c] = t;
      }
    }
    for (std::size_t c = 0; c < monitor.channels.size(); ++c) {
      std::cout << monitor.channels[c] << ": ";
      if (first_alarm[c] < 0.0) std::cout << "healthy\n";
      else std::cout << "fault from t = " << first_alarm[c] << " s\n";
    }
  } catch (const ftsense::ConfigError& e) {
    for (const auto& p : e.problems()) std::cerr << config_path << ": " << p.text() << '\n';
    return 2;
  }
  return 0;
}
