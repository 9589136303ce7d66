// sphbasis render tier, internal: the bake's quasi-Monte Carlo directions.
//
// Point j of the R2 sequence (core/sampling.hpp), shifted by a per-point Cranley-Patterson
// rotation (c_u, c_v), warped to a cosine-weighted or uniform hemisphere or the uniform sphere
// (the warps of core/sampling.hpp: phi = 2 pi v; r = sqrt(u), z = sqrt(1 - u) for the cosine
// warp; z = 1 - u or 1 - 2u for the uniform ones). The shift of v by c_v is a rotation of the
// azimuth by 2 pi c_v, applied once to the tangent frame instead of per ray, so a ray costs two
// square roots and no trigonometry: the same directions up to rounding. Not part of the API.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "../../core/constants.hpp"
#include "../../core/frame.hpp"
#include "../../core/sampling.hpp"
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

    /// Directions 0..size()-1 in world space about frame f (identity for the sphere).
    void directions(Warp w, const Frame<double>& f, double cu, double cv, V3* out) const noexcept {
        const double a = constants::two_pi * cv, ca = std::cos(a), sa = std::sin(a);
        const V3 s1 = f.s * ca + f.t * sa, t1 = f.t * ca - f.s * sa, n = f.n;
        const std::size_t m = size();
        for (std::size_t j = 0; j < m; ++j) {
            const double uu = rotate01(u[j], cu);
            double r, z;
            if (w == Warp::cosine) {
                r = std::sqrt(uu);
                z = std::sqrt(std::fmax(0.0, 1 - uu));
            } else {
                z = w == Warp::uniform_hemisphere ? 1 - uu : 1 - 2 * uu;
                r = std::sqrt(std::fmax(0.0, (1 - z) * (1 + z)));
            }
            const double x = r * c[j], y = r * s[j];
            out[j] = {x * s1.x + y * t1.x + z * n.x, x * s1.y + y * t1.y + z * n.y,
                      x * s1.z + y * t1.z + z * n.z};
        }
    }
};

}  // namespace sphbasis::render::detail::rt
