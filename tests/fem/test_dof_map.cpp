// Clamping node groups: reduction, expansion and the error for an unknown group.
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "fem/dof_map.hpp"
#include "mesh/structured.hpp"

namespace hm::fem {
namespace {

TEST(DofMap, ClampsEveryComponentOfTheGroups) {
  const mesh::StructureMesh m = mesh::structured_rectangle(1.0, 0.2, 4, 1);
  const std::vector<std::string> groups{"xmin", "ymin"};
  const DofMap dofs = DofMap::clamp_groups(m, groups, "test");
  // xmin: 3 nodes, ymin: 9 nodes, sharing one corner.
  EXPECT_EQ(dofs.clamped_count(), 2 * (3 + 9 - 1));
  EXPECT_EQ(dofs.full_count(), 2 * m.node_count());
  for (mesh::Index n : m.node_groups.at("xmin")) {
    EXPECT_TRUE(dofs.is_clamped(2 * n));
    EXPECT_TRUE(dofs.is_clamped(2 * n + 1));
  }
  const Eigen::MatrixXd full = Eigen::MatrixXd::Random(dofs.full_count(), 2);
  const Eigen::MatrixXd back = dofs.expand(dofs.reduce(full));
  for (Eigen::Index i = 0; i < dofs.full_count(); ++i)
    for (int c = 0; c < 2; ++c) EXPECT_EQ(back(i, c), dofs.is_clamped(i) ? 0.0 : full(i, c));
}

TEST(DofMap, ReducesMatricesToFreeRowsAndColumns) {
  Eigen::SparseMatrix<double> a(6, 6);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) a.insert(i, j) = 10 * i + j;
  const std::vector<mesh::Index> clamped{1};
  const DofMap dofs(3, 2, clamped);  // node 1 → DOFs 2, 3
  const Eigen::MatrixXd r(dofs.reduce(a));
  ASSERT_EQ(r.rows(), 4);
  const std::array<int, 4> kept{0, 1, 4, 5};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_EQ(r(i, j), 10 * kept[i] + kept[j]);
}

TEST(DofMap, UnknownGroupListsTheAvailableOnes) {
  const mesh::StructureMesh m = mesh::structured_box(1, 1, 1, 1, 1, 1);
  const std::vector<std::string> groups{"xmin", "clamp"};
  try {
    DofMap::clamp_groups(m, groups, "scene.toml: bodies.beam.clamped");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string text = e.what();
    for (const char* part :
         {"scene.toml: bodies.beam.clamped", "'clamp'", "xmax, xmin, ymax, ymin, zmax, zmin"})
      EXPECT_NE(text.find(part), std::string::npos) << text << " lacks " << part;
  }
}

}  // namespace
}  // namespace hm::fem
