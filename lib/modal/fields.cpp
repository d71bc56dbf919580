#include "modal/fields.hpp"

#include "core/errors.hpp"

namespace hm::modal {

Eigen::VectorXd modal_superposition(const Eigen::MatrixXd& phi, const Eigen::VectorXd& q) {
  if (phi.cols() != q.size())
    input_error(
        "modal superposition: mode-shape matrix has {} modes (columns) but the modal "
        "coordinate vector has {} entries; expected equal counts",
        phi.cols(), q.size());
  return phi * q;
}

PhysicalFields reconstruct_fields(const Eigen::MatrixXd& phi, const Eigen::VectorXd& y,
                                  const Eigen::VectorXd& v, const Eigen::VectorXd& a) {
  return {modal_superposition(phi, y), modal_superposition(phi, v), modal_superposition(phi, a)};
}

}  // namespace hm::modal
