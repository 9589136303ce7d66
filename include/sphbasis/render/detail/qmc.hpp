// sphbasis render tier, internal: the bake's quasi-Monte Carlo directions.
//
// Point j of the R2 sequence (core/sampling.hpp), shifted by a per-point Cranley-Patterson
// rotation (c_u, c_v), warped to a cosine-weighted or uniform hemisphere or the uniform sphere
// (the warps of core/sampling.hpp: phi = 2 pi v; r = sqrt(u), z = sqrt(1 - u) for the cosine
// warp; z = 1 - u or 1 - 2u for the uniform ones). The shift of v by c_v is a rotation of the
// azimuth by 2 pi c_v, applied once to the tangent frame instead of per ray, so a ray costs two
// square roots and no trigonometry: the same directions up to rounding. Computed a SIMD batch
// of directions at a time into three arrays (x, y, z), the layout sh::eval_batch reads.
// Not part of the API.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "../../core/constants.hpp"
#include "../../core/frame.hpp"
#include "../../core/sampling.hpp"
#include "../../core/simd.hpp"
#include "rt_math.hpp"

namespace sphbasis::render::detail::rt {

enum class Warp { cosine, uniform_hemisphere, uniform_sphere };

/// u_j, cos(2 pi v_j) and sin(2 pi v_j) of the first n R2 points.
struct QmcTable {
    std::vector<double> u, c, s;
    QmcTable() = default;
    explicit QmcTable(std::size_t n) : u(n), c(n), s(n) {
        for (std::size_t j = 0; j < n; ++j) {
            double uu, vv;
            r2_sequence(j, uu, vv);
            u[j] = uu;
            c[j] = std::cos(constants::two_pi * vv);
            s[j] = std::sin(constants::two_pi * vv);
        }
    }
    std::size_t size() const noexcept { return u.size(); }

    /// Directions 0..size()-1 in world space about frame f (identity for the sphere), as three
    /// arrays (x, y, z), SIMD across directions (core/simd.hpp batches). The one definition of
    /// the bake's directions: the array-of-vectors overload below goes through it.
    void directions(Warp w, const Frame<double>& f, double cu, double cv, double* xs, double* ys,
                    double* zs) const noexcept {
        const double a = constants::two_pi * cv, ca = std::cos(a), sa = std::sin(a);
        const V3 s1 = f.s * ca + f.t * sa, t1 = f.t * ca - f.s * sa, n = f.n;
        const std::size_t m = size();
        const double *U = u.data(), *C = c.data(), *S = s.data();
        std::size_t full = 0;  // directions done in whole batches
#if SPHBASIS_HAS_VECTOR_EXT
        using B = batch<double>;
        constexpr std::size_t W = static_cast<std::size_t>(B::size);
        const B one(1.0), zero(0.0), shift(cu);
        full = m - m % W;
        for (std::size_t j = 0; j < full; j += W) {
            // rotate01 lane-wise: u + cu lies in [0, 2), so x - floor(x) is x - 1 above 1.
            B uu = B::load(U + j) + shift;
            uu = select(uu >= one, uu - one, uu);
            uu = select(uu < one, uu, zero);
            B r, z;
            if (w == Warp::cosine) {
                r = vsqrt(uu);
                z = vsqrt(vmax(zero, one - uu));
            } else {
                z = w == Warp::uniform_hemisphere ? one - uu : one - B(2.0) * uu;
                r = vsqrt(vmax(zero, (one - z) * (one + z)));
            }
            const B x = r * B::load(C + j), y = r * B::load(S + j);
            (x * B(s1.x) + y * B(t1.x) + z * B(n.x)).store(xs + j);
            (x * B(s1.y) + y * B(t1.y) + z * B(n.y)).store(ys + j);
            (x * B(s1.z) + y * B(t1.z) + z * B(n.z)).store(zs + j);
        }
#endif
        for (std::size_t j = full; j < m; ++j) {
            const double uu = rotate01(U[j], cu);
            double r, z;
            if (w == Warp::cosine) {
                r = std::sqrt(uu);
                z = std::sqrt(std::fmax(0.0, 1 - uu));
            } else {
                z = w == Warp::uniform_hemisphere ? 1 - uu : 1 - 2 * uu;
                r = std::sqrt(std::fmax(0.0, (1 - z) * (1 + z)));
            }
            const double x = r * C[j], y = r * S[j];
            xs[j] = x * s1.x + y * t1.x + z * n.x;
            ys[j] = x * s1.y + y * t1.y + z * n.y;
            zs[j] = x * s1.z + y * t1.z + z * n.z;
        }
    }
    /// The same directions as vectors.
    void directions(Warp w, const Frame<double>& f, double cu, double cv, V3* out) const {
        std::vector<double> xyz(3 * size());
        double *xs = xyz.data(), *ys = xs + size(), *zs = ys + size();
        directions(w, f, cu, cv, xs, ys, zs);
        for (std::size_t j = 0; j < size(); ++j) out[j] = {xs[j], ys[j], zs[j]};
    }
};

}  // namespace sphbasis::render::detail::rt
