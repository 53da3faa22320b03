// Small dense linear algebra for the dynamic walk's constraint solve (row-major, stride n).
#pragma once

#include <cstddef>

namespace aloha::dyn {

/// In-place Cholesky of the leading n x n block of `a` (stride `stride`); the lower triangle gets
/// L. Returns false if a pivot is not positive (the caller then regularises).
bool cholesky_factor(double* a, size_t n, size_t stride);

/// Solves L L^T x = b in place for the factor from cholesky_factor.
void cholesky_solve(const double* l, size_t n, size_t stride, double* b);

}  // namespace aloha::dyn
