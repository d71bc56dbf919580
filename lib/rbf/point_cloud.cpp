#include "rbf/point_cloud.hpp"

#include <cmath>

#include <nanoflann.hpp>

namespace hm::rbf {

Points Normalisation::apply(const Points& x) const {
  return (x.rowwise() - centre) / scale;
}

Normalisation bounding_box_normalisation(const Points& x) {
  Normalisation n;
  const Eigen::RowVectorXd lo = x.colwise().minCoeff(), hi = x.colwise().maxCoeff();
  n.centre = 0.5 * (lo + hi);
  const double extent = (hi - lo).maxCoeff();
  n.scale = extent > 0 ? extent : 1.0;
  return n;
}

double bounding_box_diagonal(const Points& x) {
  if (x.rows() == 0) return 0.0;
  return (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm();
}

struct PointTree::Index {
  using Adaptor = nanoflann::KDTreeEigenMatrixAdaptor<Points>;
  explicit Index(const Points& p) : tree(p.cols(), std::cref(p), 16) { tree.index->buildIndex(); }
  Adaptor tree;
};

PointTree::PointTree(Points points)
    : points_(std::move(points)), index_(std::make_unique<Index>(points_)) {}

PointTree::~PointTree() = default;

std::pair<Eigen::Index, double> PointTree::nearest(const double* query) const {
  Eigen::Index idx = -1;
  double d2 = 0;
  index_->tree.query(query, 1, &idx, &d2);
  return {idx, std::sqrt(d2)};
}

std::vector<std::pair<Eigen::Index, double>> PointTree::nearest_k(const double* query,
                                                                  int k) const {
  const size_t n = std::min<size_t>(k, points_.rows());
  std::vector<Eigen::Index> idx(n);
  std::vector<double> d2(n);
  nanoflann::KNNResultSet<double, Eigen::Index> result(n);
  result.init(idx.data(), d2.data());
  index_->tree.index->findNeighbors(result, query, nanoflann::SearchParams());
  std::vector<std::pair<Eigen::Index, double>> out(result.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = {idx[i], std::sqrt(d2[i])};
  return out;
}

std::vector<std::pair<Eigen::Index, double>> PointTree::within(const double* query,
                                                               double radius) const {
  std::vector<std::pair<Eigen::Index, double>> found;
  nanoflann::SearchParams params;
  params.sorted = false;
  index_->tree.index->radiusSearch(query, radius * radius, found, params);  // L2: squared radius
  for (auto& f : found) f.second = std::sqrt(f.second);
  return found;
}

}  // namespace hm::rbf
