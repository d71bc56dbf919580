#include "motion/laws.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include "core/errors.hpp"

namespace hm::motion {

ScalarLaw sine_law(double amplitude, double frequency, double phase) {
  const double omega = 2.0 * std::numbers::pi * frequency;
  return [=](double t) {
    const double s = std::sin(omega * t + phase);
    const double c = std::cos(omega * t + phase);
    return Jet{amplitude * s, amplitude * omega * c, -amplitude * omega * omega * s};
  };
}

Jet smooth_ramp(double s) {
  if (s <= 0.0) return {0.0, 0.0, 0.0};
  if (s >= 1.0) return {1.0, 0.0, 0.0};
  const double u = 1.0 - s;
  return {s * s * s * (10.0 - 15.0 * s + 6.0 * s * s), 30.0 * s * s * u * u,
          60.0 * s * u * (1.0 - 2.0 * s)};
}

ScalarLaw ramped(ScalarLaw law, double ramp_time) {
  if (!(ramp_time >= 0.0) || !std::isfinite(ramp_time))
    input_error("start-up ramp time {} s is invalid: expected a finite value >= 0", ramp_time);
  if (ramp_time == 0.0) return law;
  return [law = std::move(law), ramp_time](double t) {
    const Jet r = smooth_ramp(t / ramp_time);
    if (r.value == 1.0 && r.rate == 0.0 && r.accel == 0.0) return law(t);
    const Jet f = law(t);
    const double dr = r.rate / ramp_time;
    const double ddr = r.accel / (ramp_time * ramp_time);
    return Jet{r.value * f.value, dr * f.value + r.value * f.rate,
               ddr * f.value + 2.0 * dr * f.rate + r.value * f.accel};
  };
}

}  // namespace hm::motion
