#include <gtest/gtest.h>
#include <cstdio>
#include "mesh/structured.hpp"
#include "modal/modes.hpp"
namespace hm::modal {
TEST(Probe, Orders) {
  const fem::ElasticModel steel{{2.1e11, 0.3, 7850.0}, fem::PlaneAssumption::plane_stress, 1.0};
  for (int n : {2, 3, 4, 6}) {
    const auto m = mesh::structured_box(0.25, 0.05, 0.035, 5 * n, n, n);
    const ModeSet s = compute_modes(m, steel, {}, {7, {}, "b"}, {}, Eigen::Vector3d::Zero(), {}, "b");
    std::printf("3d short n=%d f=%.10f dofs=%ld\n", n, s.frequency_hz(6), s.shapes.rows());
  }
  for (int n : {2, 4, 8, 16}) {
    const auto m = mesh::structured_rectangle(1.0, 0.05, 20 * n, n);
    const ModeSet s = compute_modes(m, steel, {}, {4, {}, "b"}, {}, Eigen::Vector3d::Zero(), {}, "b");
    std::printf("2d n=%d f=%.10f\n", n, s.frequency_hz(3));
    const ModeSet c = compute_modes(m, steel, std::vector<std::string>{"xmin"}, {1, {}, "b"}, {}, Eigen::Vector3d::Zero(), {}, "b");
    std::printf("2d clamped n=%d f=%.10f\n", n, c.frequency_hz(0));
  }
}
}
