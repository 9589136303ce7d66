// sphbasis: the ambient cube, the six-colour irradiance basis of Valve's Source engine.
//
// Reference: G. McTaggart, "Half-Life 2 / Valve Source Shading", GDC 2004 (Valve technical
// report), "ambient cube": one colour per face of the cube (+x, -x, +y, -y, +z, -z), blended with
// the squared components of the unit normal n:
//   f(n) = n_x^2 C[n_x >= 0 ? +x : -x] + n_y^2 C[n_y >= 0 ? +y : -y] + n_z^2 C[n_z >= 0 ? +z : -z].
// As a linear basis: six functions, indices 0..5 = +x, -x, +y, -y, +z, -z,
//   A_{+x}(n) = max(n_x, 0)^2,  A_{-x}(n) = max(-n_x, 0)^2,  ... (likewise y, z).
// Properties (tests/basis/test_ambient_cube.cpp checks them against quadrature and
// tools/gen/gen_engine_bases_reference.py's exact values):
//   * partition of unity: sum_k A_k(n) = |n|^2 = 1, so a constant c is stored as c on every face;
//   * at a face direction the function of that face is 1 and the others 0 (interpolating);
//   * Gram matrix on the sphere: <A_k, A_k> = int max(x,0)^4 = 2 pi/5, faces of one axis 0,
//     faces of different axes int max(x,0)^2 max(y,0)^2 = pi/15. Not orthonormal: fits solve it.
//   * on the upper hemisphere A_{-z} is zero: a tangent-space (hemisphere) fit has five
//     independent functions. Count 5 is that hemispherical ambient cube, the first five functions
//     (+x, -x, +y, -y, +z; what a tangent-space lightmap stores, and the IMSE benchmark's row);
//     count 6 the whole cube (probes).
// Domain: the whole sphere. Cost: 3 squares, 3 selects (6 stores). Continuous, C^1 (the squares
// vanish with their derivative at each face boundary).
#pragma once

#include "../config.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "basis.hpp"

namespace sphbasis::ambient_cube::detail {

template <bool Full>
struct Kernel {
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z,
                                         Store&& store) const noexcept {
        const V zero = V(scalar_t<V>(0));
        const V x2 = x * x, y2 = y * y, z2 = z * z;
        // n >= 0 goes to the + face (the value is 0 at n = 0 either way).
        store(0, select(x >= zero, x2, zero));
        store(1, select(x >= zero, zero, x2));
        store(2, select(y >= zero, y2, zero));
        store(3, select(y >= zero, zero, y2));
        store(4, select(z >= zero, z2, zero));
        if constexpr (Full) store(5, select(z >= zero, zero, z2));
    }
};

}  // namespace sphbasis::ambient_cube::detail

namespace sphbasis {

/// The ambient cube as a basis (basis/basis.hpp): 6 functions on the sphere, +x, -x, +y, -y, +z,
/// -z, or the first 5 (the upper hemisphere, where -z is zero); not orthonormal (the fits solve
/// the Gram matrix).
struct AmbientCube {
    static constexpr const char* name = "ambient-cube";
    static constexpr Domain domain = Domain::sphere;
    static constexpr bool orthonormal = false;
    static bool valid_count(int n) noexcept { return n == 5 || n == 6; }
    static int max_count() noexcept { return 6; }
    static const char* count_rule() noexcept { return "5 (upper hemisphere) or 6"; }
    /// Precondition: valid_count(n).
    template <class F>
    static decltype(auto) with_kernel(int n, F&& f) {
        if (n == 5) return f(ambient_cube::detail::Kernel<false>{});
        return f(ambient_cube::detail::Kernel<true>{});
    }
};

}  // namespace sphbasis
