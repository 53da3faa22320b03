// The dynamic walker's dense solves on Eigen: an in-place LLT of a row-major block (no copy, no
// allocation) and the two triangular solves that use it.
#include "systems/motion/dynamic/dense_solve.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace aloha::dyn {

namespace {
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Block = Eigen::Map<RowMajor, 0, Eigen::OuterStride<>>;
using ConstBlock = Eigen::Map<const RowMajor, 0, Eigen::OuterStride<>>;
}  // namespace

bool cholesky_factor(double* a, size_t n, size_t stride) {
    const auto size = static_cast<Eigen::Index>(n);
    Block block(a, size, size, Eigen::OuterStride<>(static_cast<Eigen::Index>(stride)));
    const Eigen::LLT<Eigen::Ref<RowMajor, 0, Eigen::OuterStride<>>> llt(block);  // factor written into `a`
    return llt.info() == Eigen::Success;
}

void cholesky_solve(const double* l, size_t n, size_t stride, double* b) {
    const auto size = static_cast<Eigen::Index>(n);
    const ConstBlock factor(l, size, size, Eigen::OuterStride<>(static_cast<Eigen::Index>(stride)));
    Eigen::Map<Eigen::VectorXd> x(b, size);
    factor.triangularView<Eigen::Lower>().solveInPlace(x);
    factor.triangularView<Eigen::Lower>().transpose().solveInPlace(x);
}

}  // namespace aloha::dyn
