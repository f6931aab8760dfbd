#pragma once
// A small valid pipeline config shared by the core tests.

#include "ftsense/params.hpp"

namespace ftsense::test {

inline Json base_config() {
  return Json::parse(R"({
    "sample_period_s": 0.001,
    "inputs": {
      "measured": {"columns": ["cell/c1/force_N", "cell/c2/force_N", "cell/c3/force_N"], "unit": "N"},
      "reference": {"columns": ["model/c1/force_N", "model/c2/force_N", "model/c3/force_N"], "unit": "N"}
    },
    "stages": [
      {"name": "residual", "plugin": "difference_residual",
       "inputs": {"measured": "input.measured", "virtual": "input.reference"}},
      {"name": "smooth", "plugin": "low_pass", "params": {"cutoff_hz": 2.0},
       "inputs": {"signal": "residual.residual"}},
      {"name": "detect", "plugin": "threshold_detector", "params": {"thresholds": [5.0]},
       "inputs": {"signal": "smooth.filtered"}}
    ],
    "monitor": {
      "channels": ["c1", "c2", "c3"],
      "measured": "input.measured", "virtual": "input.reference",
      "fault_estimate": "smooth.filtered", "recovered": "input.reference",
      "fault": "detect.fault", "fault_type": "detect.fault_type"
    }
  })");
}

}  // namespace ftsense::test
