// Shared checks for the parameterization tests (tests/param/test_*.cpp). Each check compares
// against an independent computation: directions from the test's own random generator,
// solid angles from subdivided spherical quads (Richardson-extrapolated), reconstruction of
// functions whose exact values are known.
#pragma once

#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <sphbasis/param/param.hpp>
#include <vector>

namespace sphbasis_test {

using sphbasis::vec3;

template <class T>
vec3<T> normalized(double x, double y, double z) {
    const double l = std::sqrt(x * x + y * y + z * z);
    return {static_cast<T>(x / l), static_cast<T>(y / l), static_cast<T>(z / l)};
}

/// Uniform random unit directions (Gaussian vectors normalised), fixed seed.
template <class T>
std::vector<vec3<T>> random_dirs(int count, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g;
    std::vector<vec3<T>> out;
    out.reserve(static_cast<std::size_t>(count));
    while (static_cast<int>(out.size()) < count) {
        const double x = g(rng), y = g(rng), z = g(rng);
        if (x * x + y * y + z * z < 1e-12) continue;
        out.push_back(normalized<T>(x, y, z));
    }
    return out;
}

/// Directions on the hard places of the parameterizations: poles, the equator, the lat-long
/// seam, cube face edges and corners, the octahedral folds (x = 0 or y = 0 with z < 0).
template <class T>
std::vector<vec3<T>> special_dirs() {
    std::vector<vec3<T>> d;
    const double s[] = {-1.0, 1.0};
    for (double a : s) {
        d.push_back(normalized<T>(a, 0, 0));
        d.push_back(normalized<T>(0, a, 0));
        d.push_back(normalized<T>(0, 0, a));
        for (double b : s) {
            d.push_back(normalized<T>(a, b, 0));  // equator, cube edges
            d.push_back(normalized<T>(a, 0, b));
            d.push_back(normalized<T>(0, a, b));
            for (double c : s) d.push_back(normalized<T>(a, b, c));  // cube corners
        }
    }
    for (int k = 0; k < 24; ++k) {
        const double phi = 2 * 3.141592653589793 * (k + 0.25) / 24;
        d.push_back(normalized<T>(std::cos(phi), std::sin(phi), 0));                     // equator
        d.push_back(normalized<T>(std::cos(phi), 0, -std::fabs(std::sin(phi)) - 0.01));  // fold
        d.push_back(normalized<T>(0, std::cos(phi), -std::fabs(std::sin(phi)) - 0.01));  // fold
        d.push_back(normalized<T>(std::fabs(std::cos(phi)), 0, std::sin(phi)));  // latlong seam
        d.push_back(normalized<T>(std::cos(phi), std::sin(phi), 1e-7));  // just off the equator
        d.push_back(normalized<T>(std::cos(phi), std::sin(phi), -1e-7));
    }
    d.push_back(normalized<T>(1e-9, 2e-9, 1));  // near the poles
    d.push_back(normalized<T>(-1e-9, 1e-9, -1));
    d.push_back(normalized<T>(1, 1, 1 + 1e-9));  // near a cube corner
    d.push_back(normalized<T>(1, -1e-12, 0.3));  // just across the lat-long seam
    return d;
}

template <class T>
double angle_between(const vec3<T>& a, const vec3<T>& b) {
    const double cx = double(a.y) * b.z - double(a.z) * b.y;
    const double cy = double(a.z) * b.x - double(a.x) * b.z;
    const double cz = double(a.x) * b.y - double(a.y) * b.x;
    const double d = double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z;
    return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), d);
}

/// direction -> (face, u, v) -> direction returns the direction, to `tol` radians.
template <class P, class T>
void check_roundtrip(const P& p, const std::vector<vec3<T>>& dirs, double tol) {
    double worst = 0;
    for (const auto& d : dirs) {
        const auto t = p.direction_to_uv(d.x, d.y, d.z);
        REQUIRE(t.face >= 0);
        REQUIRE(t.face < p.faces());
        REQUIRE(t.u >= T(0));
        REQUIRE(t.u <= T(1));
        REQUIRE(t.v >= T(0));
        REQUIRE(t.v <= T(1));
        const auto back = p.uv_to_direction(t.face, t.u, t.v);
        const double a = angle_between(d, back);
        if (a > worst) worst = a;
        if (a > tol) {
            INFO("direction " << d.x << " " << d.y << " " << d.z << " face " << t.face << " uv "
                              << t.u << " " << t.v);
            CHECK(a <= tol);
        }
    }
    INFO("worst round-trip angle " << worst);
    CHECK(worst <= tol);
}

/// The texels of random footprints: valid indices, non-negative weights summing to 1.
template <class P, class T>
void check_footprints(const P& p, const std::vector<vec3<T>>& dirs) {
    const T eps = std::numeric_limits<T>::epsilon() * 8;
    for (const auto& d : dirs) {
        const auto fp = p.footprint(d.x, d.y, d.z);
        T sum = 0;
        for (int k = 0; k < 4; ++k) {
            REQUIRE(fp.index[k] < p.texel_count());
            REQUIRE(fp.weight[k] >= T(0));
            sum += fp.weight[k];
        }
        REQUIRE(std::fabs(sum - T(1)) <= eps);
    }
}

/// Van Oosterom-Strackee, retyped here so the test does not lean on the library's copy.
inline double tri_solid_angle(const vec3<double>& a, const vec3<double>& b, const vec3<double>& c) {
    auto dt = [](const vec3<double>& p, const vec3<double>& q) {
        return p.x * q.x + p.y * q.y + p.z * q.z;
    };
    const double det = a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) +
                       a.z * (b.x * c.y - b.y * c.x);
    const double la = std::sqrt(dt(a, a)), lb = std::sqrt(dt(b, b)), lc = std::sqrt(dt(c, c));
    const double den = la * lb * lc + dt(a, b) * lc + dt(a, c) * lb + dt(b, c) * la;
    return 2 * std::atan2(std::fabs(det), den);
}

/// Solid angle of the (face, uv-rectangle) region, as k x k spherical quads with corners from
/// uv_to_direction; Richardson-extrapolated over k and 2k (the chord error is O(1/k^2)).
template <class P>
double subdivided_solid_angle(const P& p, int face, double u0, double u1, double v0, double v1,
                              int k) {
    auto sum_k = [&](int m) {
        std::vector<vec3<double>> g(static_cast<std::size_t>((m + 1) * (m + 1)));
        for (int j = 0; j <= m; ++j)
            for (int i = 0; i <= m; ++i) {
                const double u = u0 + (u1 - u0) * i / m, v = v0 + (v1 - v0) * j / m;
                const auto d = p.uv_to_direction(face, u, v);
                g[static_cast<std::size_t>(j * (m + 1) + i)] = {double(d.x), double(d.y),
                                                                double(d.z)};
            }
        double s = 0;
        for (int j = 0; j < m; ++j)
            for (int i = 0; i < m; ++i) {
                const auto& a = g[static_cast<std::size_t>(j * (m + 1) + i)];
                const auto& b = g[static_cast<std::size_t>(j * (m + 1) + i + 1)];
                const auto& c = g[static_cast<std::size_t>((j + 1) * (m + 1) + i + 1)];
                const auto& d = g[static_cast<std::size_t>((j + 1) * (m + 1) + i)];
                s += tri_solid_angle(a, b, c) + tri_solid_angle(a, c, d);
            }
        return s;
    };
    const double a = sum_k(k), b = sum_k(2 * k);
    return (4 * b - a) / 3;
}

/// Texel solid angles against subdivided_solid_angle over each texel's cell (the cell in
/// (u, v) clipped to [lo, hi]^2, which is [0, 1]^2 except for the shrunk dual maps).
template <class P>
void check_texel_solid_angles(const P& p, double lo, double hi, int k, double rel_tol) {
    double worst = 0;
    for (int face = 0; face < p.faces(); ++face)
        for (int row = 0; row < p.height(); ++row)
            for (int col = 0; col < p.width(); ++col) {
                const double u0 = std::fmax(double(col) / p.width(), lo);
                const double u1 = std::fmin(double(col + 1) / p.width(), hi);
                const double v0 = std::fmax(double(row) / p.height(), lo);
                const double v1 = std::fmin(double(row + 1) / p.height(), hi);
                const double ref = subdivided_solid_angle(p, face, u0, u1, v0, v1, k);
                const double got = double(p.texel_solid_angle(face, col, row));
                const double err = std::fabs(got - ref) / ref;
                if (err > worst) worst = err;
            }
    INFO("worst relative texel solid-angle error " << worst);
    CHECK(worst <= rel_tol);
}

/// A smooth test function (a degree-2 polynomial of the direction) and a degree-3 one.
inline double smooth_f(double x, double y, double z) {
    return 0.3 + x - 0.4 * y + 0.5 * y * z - 0.7 * z * z + 0.2 * x * y;
}
inline double smooth_g(double x, double y, double z) {
    return 1.0 + 0.5 * x * y * z + x * x * x - 0.3 * z * y * y + 0.8 * z;
}

/// Tabulates smooth_f (channel 0) and smooth_g (channel 1) at the texel centres, type V.
template <class V, class P>
std::vector<V> smooth_table(const P& p) {
    return sphbasis::param::tabulate<V>(p, 2, [](auto x, auto y, auto z, V* out) {
        out[0] = static_cast<V>(smooth_f(double(x), double(y), double(z)));
        out[1] = static_cast<V>(smooth_g(double(x), double(y), double(z)));
    });
}

/// Reconstructs a constant exactly (to rounding) everywhere.
template <class P, class T>
void check_constant(const P& p, const std::vector<vec3<T>>& dirs) {
    const std::vector<T> table(p.texel_count(), T(0.7));
    T worst = 0;
    for (const auto& d : dirs) {
        T out;
        sphbasis::param::lookup(p, table.data(), 1, d.x, d.y, d.z, &out);
        worst = std::fmax(worst, std::fabs(out - T(0.7)));
    }
    CHECK(worst <= std::numeric_limits<T>::epsilon() * 4);
}

/// At a texel centre the lookup returns the tabulated value of that direction.
template <class P>
void check_interpolates_at_centres(const P& p, double tol) {
    const auto table = smooth_table<double>(p);
    double worst = 0;
    for (int face = 0; face < p.faces(); ++face)
        for (int row = 0; row < p.height(); ++row)
            for (int col = 0; col < p.width(); ++col) {
                const auto d = p.texel_direction(face, col, row);
                double out[2];
                sphbasis::param::lookup(p, table.data(), 2, d.x, d.y, d.z, out);
                worst = std::fmax(worst, std::fabs(out[0] - smooth_f(d.x, d.y, d.z)));
                worst = std::fmax(worst, std::fabs(out[1] - smooth_g(d.x, d.y, d.z)));
            }
    CHECK(worst <= tol);
}

/// Largest jump of the reconstruction of smooth_f/smooth_g between direction pairs `eps`
/// radians apart across a curve: pairs are (base + eps n, base - eps n) normalised.
template <class P>
double max_jump(const P& p, const std::vector<double>& table, const std::vector<vec3<double>>& base,
                const std::vector<vec3<double>>& normal, double eps) {
    double worst = 0;
    for (std::size_t k = 0; k < base.size(); ++k) {
        const auto& b = base[k];
        const auto& n = normal[k];
        const auto a = normalized<double>(b.x + eps * n.x, b.y + eps * n.y, b.z + eps * n.z);
        const auto c = normalized<double>(b.x - eps * n.x, b.y - eps * n.y, b.z - eps * n.z);
        double oa[2], oc[2];
        sphbasis::param::lookup(p, table.data(), 2, a.x, a.y, a.z, oa);
        sphbasis::param::lookup(p, table.data(), 2, c.x, c.y, c.z, oc);
        worst = std::fmax(worst, std::fmax(std::fabs(oa[0] - oc[0]), std::fabs(oa[1] - oc[1])));
    }
    return worst;
}

/// Mean squared reconstruction error of smooth_f and smooth_g at random directions.
template <class P>
double smooth_mse(const P& p, int points) {
    const auto table = smooth_table<double>(p);
    const auto dirs = random_dirs<double>(points, 99);
    double sum = 0;
    for (const auto& d : dirs) {
        double out[2];
        sphbasis::param::lookup(p, table.data(), 2, d.x, d.y, d.z, out);
        const double e0 = out[0] - smooth_f(d.x, d.y, d.z), e1 = out[1] - smooth_g(d.x, d.y, d.z);
        sum += e0 * e0 + e1 * e1;
    }
    return sum / (2.0 * points);
}

/// Convergence of the smooth reconstruction (smooth_mse, 20000 points) from a map to one of twice
/// the resolution: with a seamless filter (`seamless`, `seamless2`) the error falls like h^4
/// (ratio > 10); with a clamping one (`clamped`, `clamped2`) the seams add an h^3 term (ratio > 4);
/// at the finer resolution the seamless error is the smaller. The names label the two in INFO.
template <class P>
void check_seam_convergence(const P& seamless, const P& seamless2, const P& clamped,
                            const P& clamped2, const char* seamless_name,
                            const char* clamped_name) {
    const double sa = smooth_mse(seamless, 20000), sb = smooth_mse(seamless2, 20000);
    const double ca = smooth_mse(clamped, 20000), cb = smooth_mse(clamped2, 20000);
    INFO(seamless_name << " " << sa << " -> " << sb << ", " << clamped_name << " " << ca << " -> "
                       << cb);
    CHECK(sa / sb > 10);  // h^4
    CHECK(ca / cb > 4);   // the seams add an h^3 term
    CHECK(sb < cb);
}

/// Integral over the sphere (or the upper hemisphere) of pdf(x, y, z) d(omega), by the
/// midpoint rule in (theta, phi) with d(omega) = sin(theta) d(theta) d(phi).
template <class F>
double integrate_sphere(F&& pdf, bool hemisphere, int m) {
    const double pi = 3.141592653589793;
    const double theta_max = hemisphere ? pi / 2 : pi;
    const double dt = theta_max / m, dp = 2 * pi / (2 * m);
    double sum = 0;
    for (int i = 0; i < m; ++i) {
        const double t = (i + 0.5) * dt, st = std::sin(t), ct = std::cos(t);
        double row = 0;
        for (int j = 0; j < 2 * m; ++j) {
            const double ph = (j + 0.5) * dp;
            row += pdf(st * std::cos(ph), st * std::sin(ph), ct);
        }
        sum += row * st;
    }
    return sum * dt * dp;
}

/// |d dir/du x d dir/dv| (central differences) at (u, v): the solid angle per unit area of
/// the square, which must equal 1/pdf.
template <class F>
double jacobian(F&& to_dir, double u, double v, double h) {
    const auto a = to_dir(u + h, v), b = to_dir(u - h, v), c = to_dir(u, v + h),
               d = to_dir(u, v - h);
    const double du[3] = {(a.x - b.x) / (2 * h), (a.y - b.y) / (2 * h), (a.z - b.z) / (2 * h)};
    const double dv[3] = {(c.x - d.x) / (2 * h), (c.y - d.y) / (2 * h), (c.z - d.z) / (2 * h)};
    const double cx = du[1] * dv[2] - du[2] * dv[1], cy = du[2] * dv[0] - du[0] * dv[2],
                 cz = du[0] * dv[1] - du[1] * dv[0];
    return std::sqrt(cx * cx + cy * cy + cz * cz);
}

/// The standard round-trip set of a map p over directions of type T: round trips and footprints
/// at random and special directions, a constant reconstructed at random directions and, with
/// `constant_at_special`, at the special ones.
template <class T, class P>
void check_map_round_trips(const P& p, double tol, bool constant_at_special = true) {
    check_roundtrip(p, random_dirs<T>(20000, 1), tol);
    check_roundtrip(p, special_dirs<T>(), tol);
    check_footprints(p, random_dirs<T>(5000, 2));
    check_footprints(p, special_dirs<T>());
    check_constant(p, random_dirs<T>(5000, 3));
    if (constant_at_special) check_constant(p, special_dirs<T>());
}

}  // namespace sphbasis_test
