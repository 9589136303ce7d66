// Shared helper of the rotation tests (tests/ops/test_sh_rotation*.cpp): a random orthogonal
// 3x3 matrix from a normally distributed quaternion (uniform over rotations), optionally made
// improper.
#pragma once

#include <cstddef>
#include <random>
#include <sphbasis/core/frame.hpp>

namespace sphbasis::test {

/// How random_rotation_matrix makes the matrix improper (det = -1), if at all.
enum class Improper {
    no,         // the rotation itself
    negate,     // -R
    reflect_z,  // R followed by z -> -z (the last row negated)
};

/// A random row-major rotation (from four normal deviates: w, x, y, z, in that order), formed
/// in double and rounded to T, made improper as asked.
template <class T>
Mat3<T> random_rotation_matrix(std::mt19937& rng, Improper improper = Improper::no) {
    std::normal_distribution<double> nd;
    const double w = nd(rng), x = nd(rng), y = nd(rng), z = nd(rng);
    Mat3<double> r = matrix_from_quaternion(w, x, y, z);
    for (std::size_t k = 0; k < 9; ++k)
        if (improper == Improper::negate || (improper == Improper::reflect_z && k >= 6))
            r[k] = -r[k];
    Mat3<T> out;
    for (std::size_t k = 0; k < 9; ++k) out[k] = T(r[k]);
    return out;
}

}  // namespace sphbasis::test
