#pragma once
// Newmark average-acceleration (β = 1/4, γ = 1/2) for the modal equations
//   ÿ + 2ζω ẏ + ω² y = F(t)
// Kept ONLY as a documented contrast to CFPI (cfpi.hpp): it is unconditionally stable but has a
// period error, ω̄·Δt = 2·atan(ω·Δt/2) for ζ = 0 (−35 % frequency at ω·Δt = 3), so modes that the
// time step does not resolve ring at a wrong frequency. Do not use it in the coupled solver.
// Units as in cfpi.hpp.
#include <Eigen/Core>

namespace hm::modal {

class NewmarkIntegrator {
 public:
  NewmarkIntegrator(Eigen::VectorXd omega, Eigen::VectorXd zeta, double beta = 0.25,
                    double gamma = 0.5);

  /// Sets y, v and the load F at the current time (which defines a = F − 2ζωv − ω²y).
  void set_state(const Eigen::VectorXd& y, const Eigen::VectorXd& v, const Eigen::VectorXd& F);
  /// One step of dt [s]; only the end load F1 enters (Newmark uses the equation at t + Δt).
  void step(const Eigen::VectorXd& F1, double dt);

  const Eigen::VectorXd& y() const { return y_; }
  const Eigen::VectorXd& v() const { return v_; }
  const Eigen::VectorXd& a() const { return a_; }

 private:
  Eigen::VectorXd omega_, zeta_, y_, v_, a_;
  double beta_, gamma_;
};

}  // namespace hm::modal
