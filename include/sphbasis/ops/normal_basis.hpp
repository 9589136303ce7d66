// sphbasis: the SVD "normal basis" of normal-mapped PRT. For a diffuse surface whose transferred
// incident radiance is an SH vector l' of `bands` bands (quadratic: 3 bands, 9 numbers) in the
// tangent frame, the exit radiance for a normal n of the normal map is
//     e(n) = sum_j A_j(n) l'_j,    A_j(n) = integral of max(n . w, 0) g_j(w) dw,
// with g_j = y_j (the lighting not clamped) or g_j = y_j restricted to the geometric hemisphere
// w_z > 0 (the lighting clamped before the convolution, as the notes recommend: light from
// below the coarse surface cannot reach it). Sampling A at normals n_i of the upper hemisphere
// gives a matrix (rows: normals, columns: the bands^2 lighting functions) whose SVD
// A = U S V^T yields "normal basis" textures (columns of U) and, keeping the first M singular
// values, e(n) = U_M(n) S_M V_M^T l'. The fraction of energy kept by M terms is
// sum_{i <= M} s_i^2 / sum_i s_i^2 (in percent).
//
// Reference: Sloan, Lehtinen and Kautz, "Precomputed Radiance Transfer: Theory and Practice"
// (SIGGRAPH 2005 course), "Normal Mapping for PRT": e(n) = y(n)^T C R M l, its matrix A
// ("rows normal directions, columns quadratic SH light", "the lighting environment should be
// clamped to the hemisphere before this integral happens"), A = U S V^T, and the printed
// accuracies for uniform / cosine-weighted normals: M = 4: 93.9 / 96.4, M = 6: 98.7 / 99.3.
// Those are matched by the *unclamped* variant with the energy sum s_i^2 (the continuous
// problem gives 93.92 / 96.29 and 98.64 / 99.24: within 0.11 of every printed value; the small
// excess is what a coarse grid of normals gives, e.g. 16 x 16 texels of the disk give
// 93.96 / 95.99 and 98.84 / 99.13). The clamped variant the notes recommend gives
// 98.35 / 99.11 and 99.99 / 100.00: clamping removes most of the lighting's energy that only
// normals far from z see, so fewer terms suffice; the printed numbers are not from it.
//
// The continuous problem: with the normals' weight density rho (uniform: 1 per steradian,
// cosine: n_z), the energies are the eigenvalues of the Gram matrix
// G_jk = int_{n_z > 0} A_j(n) A_k(n) rho(n) dn; a quadrature rule (n_i, w_i) gives the rows
// sqrt(w_i rho(n_i)) A(n_i), whose singular values are the square roots of those eigenvalues.
// The normals: Gauss-Legendre in n_z on [0, 1] times uniform azimuths (exact for the unclamped
// columns, polynomials of degree bands - 1; the clamped ones are analytic on the closed
// hemisphere and converge algebraically: 24 rings, the default, give the energies to 1e-5 percent).
// The clamped column at n: the region {w_z > 0, n . w > 0} is a lune between two great circles
// through the axis e = z x n / |z x n|. With w = cos(psi) e + sin(psi) (cos(b) z + sin(b) z'),
// z' = e x z, the lune is psi in [0, pi], b in [theta_n - pi/2, pi/2] (theta_n the angle of n
// from z, n = cos(theta_n) z + sin(theta_n) z'), dw = sin(psi) dpsi db; the integrand is a
// trigonometric polynomial in psi and b, integrated by Gauss-Legendre rules in both.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../basis/sh.hpp"
#include "../core/clamped_cosine.hpp"
#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../core/quadrature.hpp"

namespace sphbasis {

/// How the normals (rows of A) are weighted over the upper hemisphere.
enum class NormalWeighting {
    uniform,  ///< every direction alike (density 1 per steradian)
    cosine    ///< density n_z: normals near the geometric normal (tangent-space z) count more
};

/// Settings of normal_basis().
struct NormalBasisSettings {
    int bands = 3;        ///< SH bands of the transferred lighting (columns: bands^2), 1..8
    bool clamped = true;  ///< restrict the lighting to w_z > 0 before the cosine convolution
    NormalWeighting weighting = NormalWeighting::uniform;
    int rings =
        0;  ///< Gauss-Legendre rings in n_z (2 rings + 2 azimuths); 0: 24 clamped, bands + 1 not
};

/// The SVD of the weighted normal matrix and its cumulative energies.
struct NormalBasis {
    Eigen::MatrixXd u;                   ///< rows x bands^2, the normal-basis functions at the rows
    Eigen::VectorXd singular_values;     ///< bands^2, descending
    Eigen::MatrixXd v;                   ///< bands^2 x bands^2
    std::vector<double> energy_percent;  ///< [M - 1]: percent of sum s^2 kept by M terms
    DirectionalRule normals;  ///< the rows' normals and quadrature weights (density folded)
};

namespace detail {
inline void check_normal_basis_settings(const char* fn, const NormalBasisSettings& s) {
    check_range(fn, "bands", s.bands, 1, 8);
    check_range(fn, "rings", s.rings, 0, 4096);
    if (s.weighting != NormalWeighting::uniform && s.weighting != NormalWeighting::cosine)
        throw_invalid(fn, "weighting uniform or cosine, got " +
                              std::to_string(static_cast<int>(s.weighting)));
}
}  // namespace detail

namespace detail {
/// convolved_lighting_columns() after its checks, with the Gauss-Legendre rule (t, wt) of
/// 2 bands + 8 nodes on [-1, 1] and scratch y (bands^2) given.
inline void convolved_columns(int bands, bool clamped, double nx, double ny, double nz,
                              const std::vector<double>& t, const std::vector<double>& wt,
                              double* y, double* out) {
    const int nc = bands * bands;
    if (!clamped) {
        double a[8];
        clamped_cosine_factors(bands, a);
        sh::eval(bands, nx, ny, nz, out);
        for (int l = 0; l < bands; ++l)
            for (int m = -l; m <= l; ++m) out[sh::index(l, m)] *= constants::pi * a[l];
        return;
    }
    // Lune frame: e = z x n normalised (any horizontal axis when n = z), z' = e x z.
    const double s = std::sqrt(nx * nx + ny * ny);
    const double ex = s > 1e-300 ? -ny / s : 1.0, ey = s > 1e-300 ? nx / s : 0.0;
    const double zpx = ey, zpy = -ex;        // e x (0, 0, 1)
    const double theta = std::atan2(s, nz);  // n = cos(theta) z + sin(theta) z'
    const int q = static_cast<int>(t.size());
    const double b0 = theta - constants::pi / 2, b1 = constants::pi / 2;
    std::fill(out, out + nc, 0.0);
    for (int i = 0; i < q; ++i) {
        const double psi = constants::pi / 2 * (t[static_cast<std::size_t>(i)] + 1);
        const double wpsi = constants::pi / 2 * wt[static_cast<std::size_t>(i)];
        const double cp = std::cos(psi), sp = std::sin(psi);
        for (int k = 0; k < q; ++k) {
            const double b = b0 + (b1 - b0) / 2 * (t[static_cast<std::size_t>(k)] + 1);
            const double wb = (b1 - b0) / 2 * wt[static_cast<std::size_t>(k)];
            const double cb = std::cos(b), sb = std::sin(b);
            const double wx = cp * ex + sp * sb * zpx, wy = cp * ey + sp * sb * zpy, wz = sp * cb;
            const double cosine = sp * std::cos(b - theta);  // n . w
            const double w = wpsi * wb * sp * cosine;
            sh::eval(bands, wx, wy, wz, y);
            for (int j = 0; j < nc; ++j) out[j] += w * y[j];
        }
    }
}
}  // namespace detail

/// The convolved lighting functions at one normal (nx, ny, nz) (unit, nz >= 0): out[j] =
/// integral of max(n . w, 0) y_j(w) dw over the sphere (clamped = false: pi a_l y_j(n),
/// core/clamped_cosine.hpp) or over w_z > 0 only (clamped = true; header comment), for
/// j < bands^2. Cost: clamped O((2 bands + 8)^2 bands^2), else O(bands^2). Throws
/// std::invalid_argument for bands outside 1..8.
inline void convolved_lighting_columns(int bands, bool clamped, double nx, double ny, double nz,
                                       double* out) {
    detail::check_range("convolved_lighting_columns", "bands", bands, 1, 8);
    std::vector<double> t, wt, y(static_cast<std::size_t>(bands * bands));
    gauss_legendre(2 * bands + 8, t, wt);
    detail::convolved_columns(bands, clamped, nx, ny, nz, t, wt, y.data(), out);
}

/// The weighted normal matrix: rows sqrt(w_i rho(n_i)) A(n_i) over the quadrature rule of the
/// header comment (stored in `normals` if non-null, its w holding w_i rho(n_i)), columns the
/// bands^2 convolved lighting functions. Throws std::invalid_argument for bands outside 1..8
/// or rings outside 0..4096.
inline Eigen::MatrixXd normal_basis_matrix(const NormalBasisSettings& settings,
                                           DirectionalRule* normals = nullptr) {
    const char* fn = "normal_basis_matrix";
    detail::check_normal_basis_settings(fn, settings);
    const int bands = settings.bands, nc = bands * bands;
    const int rings = settings.rings > 0 ? settings.rings : (settings.clamped ? 24 : bands + 1);
    const int nphi = 2 * rings + 2;
    std::vector<double> t, wt;
    gauss_legendre(rings, t, wt);
    DirectionalRule rule;
    Eigen::MatrixXd a(static_cast<Eigen::Index>(rings) * nphi, nc);
    std::vector<double> col(static_cast<std::size_t>(nc)), ys(col.size()), qt, qw;
    gauss_legendre(2 * bands + 8, qt, qw);
    Eigen::Index row = 0;
    for (int i = 0; i < rings; ++i) {
        const double z = 0.5 * (t[static_cast<std::size_t>(i)] + 1);
        const double sn = std::sqrt((1 - z) * (1 + z));
        double w = 0.5 * wt[static_cast<std::size_t>(i)] * constants::two_pi / nphi;
        if (settings.weighting == NormalWeighting::cosine) w *= z;
        for (int j = 0; j < nphi; ++j, ++row) {
            const double phi = (j + 0.5) * constants::two_pi / nphi;
            const double x = sn * std::cos(phi), y = sn * std::sin(phi);
            detail::convolved_columns(bands, settings.clamped, x, y, z, qt, qw, ys.data(),
                                      col.data());
            const double sw = std::sqrt(w);
            for (int c = 0; c < nc; ++c) a(row, c) = sw * col[static_cast<std::size_t>(c)];
            rule.x.push_back(x);
            rule.y.push_back(y);
            rule.z.push_back(z);
            rule.w.push_back(w);
        }
    }
    if (normals) *normals = std::move(rule);
    return a;
}

/// The SVD normal basis (header comment): A = U S V^T of normal_basis_matrix(settings) by
/// Eigen's JacobiSVD, and the cumulative energies in percent, energy_percent[M - 1] =
/// 100 sum_{i < M} s_i^2 / sum_i s_i^2 (100 at M = bands^2). Cost: clamped, about
/// 1000 (2 bands + 8)^2 bands^2 multiply-adds at the automatic 24 rings (a few ms for 3 bands).
/// Throws as normal_basis_matrix().
/// (A template only so that JacobiSVD is compiled where normal_basis() is called, not in every
/// file that includes the umbrella header: it was most of the umbrella's parse time and memory.)
template <class Matrix = Eigen::MatrixXd>
NormalBasis normal_basis(const NormalBasisSettings& settings) {
    NormalBasis r;
    const Matrix a = normal_basis_matrix(settings, &r.normals);
    Eigen::JacobiSVD<Matrix> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
    r.u = svd.matrixU();
    r.singular_values = svd.singularValues();
    r.v = svd.matrixV();
    const Eigen::Index n = r.singular_values.size();
    double total = 0;
    for (Eigen::Index i = 0; i < n; ++i) total += r.singular_values(i) * r.singular_values(i);
    if (!(total > 0) || !std::isfinite(total))
        sphbasis::detail::throw_runtime(
            "normal_basis", "a nonzero finite matrix, got energy " + std::to_string(total));
    double acc = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
        acc += r.singular_values(i) * r.singular_values(i);
        r.energy_percent.push_back(i + 1 == n ? 100.0 : 100.0 * acc / total);
    }
    return r;
}

/// normal_basis(settings).energy_percent.
template <class Matrix = Eigen::MatrixXd>
std::vector<double> normal_basis_energy(const NormalBasisSettings& settings) {
    return normal_basis<Matrix>(settings).energy_percent;
}

}  // namespace sphbasis
