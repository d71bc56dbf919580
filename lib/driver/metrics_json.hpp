#pragma once
// The JSON of one curve comparison, shared by fsi-report's metrics.json and fsi-study's
// study.json (one spelling of the keys users' scripts read). Private to lib/driver.
#include <nlohmann/json.hpp>

#include "driver/report_stage.hpp"

namespace hm::driver {

inline nlohmann::ordered_json curve_metrics_json(const CurveMetrics& m) {
  return {{"peak", m.peak},
          {"peak_time_s", m.peak_time},
          {"reference_peak", m.reference_peak},
          {"reference_peak_time_s", m.reference_peak_time},
          {"peak_error", m.peak_error},
          {"peak_time_error_s", m.peak_time_error},
          {"rms", m.rms},
          {"rms_relative", m.rms_relative},
          {"window_s", {m.window_start, m.window_end}},
          {"reference_samples", m.samples},
          {"run_samples_missing", m.missing},
          {"probe_without_fluid", m.without_fluid}};
}

}  // namespace hm::driver
