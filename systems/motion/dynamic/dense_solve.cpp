#include "systems/motion/dynamic/dense_solve.hpp"

#include <cmath>

namespace aloha::dyn {

bool cholesky_factor(double* a, size_t n, size_t stride) {
    for (size_t j = 0; j < n; ++j) {
        double* rj = a + j * stride;
        double d = rj[j];
        for (size_t k = 0; k < j; ++k) d -= rj[k] * rj[k];
        if (!(d > 0.0)) return false;
        d = std::sqrt(d);
        rj[j] = d;
        const double inv = 1.0 / d;
        for (size_t i = j + 1; i < n; ++i) {
            double* ri = a + i * stride;
            double s = ri[j];
            for (size_t k = 0; k < j; ++k) s -= ri[k] * rj[k];
            ri[j] = s * inv;
        }
    }
    return true;
}

void cholesky_solve(const double* l, size_t n, size_t stride, double* b) {
    for (size_t i = 0; i < n; ++i) {
        const double* ri = l + i * stride;
        double s = b[i];
        for (size_t k = 0; k < i; ++k) s -= ri[k] * b[k];
        b[i] = s / ri[i];
    }
    for (size_t i = n; i-- > 0;) {
        double s = b[i];
        for (size_t k = i + 1; k < n; ++k) s -= l[k * stride + i] * b[k];
        b[i] = s / l[i * stride + i];
    }
}

}  // namespace aloha::dyn
