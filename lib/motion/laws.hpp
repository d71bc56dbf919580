#pragma once
// Scalar motion laws f(t) of prescribed wall motion, evaluated with their first two time
// derivatives so that wall positions, velocities and accelerations are exact (no differencing).
// Time t in s; the value is a displacement in m or an angle in rad.
#include <functional>

namespace hm::motion {

/// A scalar law and its derivatives at one time: f, df/dt, d²f/dt².
struct Jet {
  double value = 0.0;
  double rate = 0.0;
  double accel = 0.0;
};

using ScalarLaw = std::function<Jet(double t)>;

/// f(t) = amplitude · sin(2π·frequency·t + phase); frequency in Hz, phase in rad.
/// Sway A·sin(2πt/T): sine_law(A, 1/T). Roll θ0·sin(2πft): sine_law(θ0, f).
ScalarLaw sine_law(double amplitude, double frequency, double phase = 0.0);

/// The start-up ramp r(s) = s³(10 − 15s + 6s²) on s ∈ [0, 1], 0 before, 1 after, with dr/ds and
/// d²r/ds². CHOICE: this quintic is the lowest-degree polynomial with r, r', r'' equal to 0 at
/// s = 0 and to 1, 0, 0 at s = 1, so a ramped law is C²: velocity and acceleration are
/// continuous at the start and at the end of the ramp (a cubic smoothstep would leave a jump of
/// the acceleration, i.e. a pressure shock in the fluid).
Jet smooth_ramp(double s);

/// g(t) = r(t/ramp_time) · f(t) with its exact derivatives (Leibniz rule). ramp_time in s;
/// ramp_time = 0 returns `law` unchanged. The motion is at rest for t ≤ 0.
ScalarLaw ramped(ScalarLaw law, double ramp_time);

}  // namespace hm::motion
