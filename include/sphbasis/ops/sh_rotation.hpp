// sphbasis: rotation of real spherical-harmonic expansions, any band count.
//
// Convention. A rotation (or any orthogonal 3x3 matrix) R acts on the FUNCTION: the rotated
// expansion g of f is g(w) = f(R^T w), so a light at direction d moves to R d. Its matrix D(R)
// is block diagonal, one (2l+1)x(2l+1) block per band, with y(R w) = D(R) y(w) for the vector
// y of basis functions (basis/sh.hpp: real, no Condon-Shortley phase, ACN order), and
//   g_coeffs = D(R) f_coeffs,   D(R1 R2) = D(R1) D(R2),   D(R^T) = D(R)^T = D(R)^{-1}.
// Band 1 is R itself with rows and columns permuted to (y, z, x): D1[i][j] = R[p(i)][p(j)].
// 3x3 matrices are row-major. Improper orthogonal matrices (det = -1) are accepted and give
// the reflected function: D(-R) = (-1)^l D(R) per band, and diag(1, 1, -1) is reflect_z().
//
// Method. Two recurrences, both O(n^3) for n bands and both needing only the previous band, so
// rotate() applies a rotation with O(n^2) scratch memory and never stores the whole matrix:
//   * up to 24 bands, the Ivanic-Ruedenberg recurrence (J. Ivanic, K. Ruedenberg, J. Phys.
//     Chem. 100 (1996) 6342, eqs. 5.1-5.6 and Table 2, with the corrections of J. Phys. Chem. A
//     102 (1998) 9099: the sqrt(1 + delta) factors and the signs of the V term for m < 0).
//     Band l comes from band l-1 and band 1 by u U + v V + w W, O(1) real work per entry, in
//     the real basis, from the matrix itself (no Euler angles, no gimbal lock, exact 0/+-1 input
//     stays exact). The u, v, w factors split into a row part and a column part and are
//     tabulated once per type; the P functions of a band are tabulated first, so each entry is
//     a branch-free sum of five table rows. It is the fastest choice at low degree, but it is
//     NOT stable at high degree: measured max|D D^T - I| grows from 4e-15 at l = 20 and 3e-14
//     at l = 40 to 2e-9 at l = 100 and O(1) by l = 180 (errors grow ~1.2x per band);
//   * above 24 bands, Risbo's recursion (R. Risbo, J. Geodesy 70 (1996) 383): the complex
//     Wigner matrices D^j for j = 0, 1/2, 1, ... from the SU(2) matrix of the rotation's
//     quaternion, each half step a contraction with positive Clebsch-Gordan weights, then one
//     sparse change of basis per band to the real functions. Half of each step is computed,
//     the other half follows from D_{-m',-m} = (-1)^(m'-m) conj(D_{m'm}). Errors grow about
//     linearly: measured max|D D^T - I| ~ 1e-14 at l = 40 and ~ 1e-13 at l = 199. It agrees
//     with Ivanic-Ruedenberg to 3e-15 where both are accurate. The 200-band matrix (1.07e7
//     values, 85 MB in double) builds in well under a second, mostly memory traffic.
// At 1..8 bands (max_fixed_rotation_bands) none of this runs on the hot path: rotate(),
// rotate_quaternion() and Rotation<T>::apply() / apply_transposed() switch on the band count to
// the generated factored code sh::rotate<N> (ops/sh_rotation_fixed.hpp: band 1 is R, band 2 the
// quadratic form R Q R^T, bands 3.. an Euler factorisation read from R; D never formed; within
// 4.4e-6 (float) / 1.6e-14 (double) of the product with D for coefficients in [-1, 1]), and a
// Rotation<T> forms D only when D itself is asked for (see Rotation).
// Why not Euler angles and Wigner-d recurrences in beta: ZYZ angles lose accuracy near
// beta = 0 and pi, and d-recurrences need scaled starting values at high degree; the
// quaternion feeds Risbo's recursion directly and has no such singularity.
//
// Special cases with cheaper or exact forms:
//   * rotate_z(angle): cos(m a), sin(m a) on the pairs (m, -m), O(n^2);
//   * rotate_z90(k): quarter turns about z, a signed permutation, exact;
//   * matrix_90(axis, k) / rotation_90(): quarter turns about x, y or z from the exact integer
//     matrix (no cos(pi/2) = 6e-17 residue);
//   * reflect_z(): z -> -z multiplies y_lm by (-1)^(l+m) (Q_l^m(z) has the parity of l - m).
//     Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed Visibility" (JGT 2009,
//     Sec. 3) say "changes the sign of the basis functions where m is odd"; that is the parity
//     only for even l. reflect(axis) does x -> -x and y -> -y as well.
//   * rotate_zyz(alpha, beta, gamma): D(Rz(a) Ry(b) Rz(c)) = Z(a) X^T Z(b) X Z(c), three z
//     rotations and two applications of the cached quarter turn X about x, O(n^3) with a
//     smaller constant than rebuilding D (the quarter turn maps the y axis to z, so a rotation
//     about y is a z rotation conjugated by X).
//   * frame_to_normal(n): the rotation taking +z to a normal n (the R of Sloan, Lehtinen and
//     Kautz, "Precomputed Radiance Transfer: Theory and Practice", SIGGRAPH 2005 course,
//     "Normal Mapping for PRT": e(n) = y(n)^T C R M l).
// 3x3 matrices, quaternions and frames live in core/frame.hpp (re-exported here under sh::).
// Types users hold: every entry point takes the rotation as a row-major std::array<T, 9>
// (sh::Mat3), a glm::mat3 / dmat3 (column-major, m[col][row]), an Eigen::Matrix3f / Matrix3d
// (m(row, col)), or, where it says so, a quaternion (glm::quat / dquat, Eigen::Quaternionf / d,
// sphbasis::Quat; read by the names w, x, y, z), and coefficient buffers as raw pointers or
// contiguous ranges (.data() and .size(), size checked).
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "../basis/sh.hpp"
#include "../config.hpp"
#include "../core/error.hpp"
#include "../core/frame.hpp"
#include "../core/small_buffer.hpp"
#include "../core/vec.hpp"
#include "sh_rotation_cos_sin.hpp"

// SPHBASIS_SH_ROTATION_AVX512: the float rotation's 3-band kernel, its quaternion-to-matrix and
// its orthonormality check in AVX-512 registers (GCC/clang with AVX-512F enabled, e.g.
// -march=native on such a machine). Define it to 0 to use the scalar code everywhere.
#if !defined(SPHBASIS_SH_ROTATION_AVX512)
#if defined(__AVX512F__) && (defined(__GNUC__) || defined(__clang__))
#define SPHBASIS_SH_ROTATION_AVX512 1
#else
#define SPHBASIS_SH_ROTATION_AVX512 0
#endif
#endif
// SPHBASIS_SH_ROTATION_AVX2: the same kernels (and the 6-8 band rotations' bands >= 3) in 8-lane
// AVX2 registers where AVX-512 is not enabled (GCC/clang with AVX2 and FMA, e.g.
// -march=x86-64-v3 or haswell). Define it to 0 to use the scalar code there.
#if !defined(SPHBASIS_SH_ROTATION_AVX2)
#if !SPHBASIS_SH_ROTATION_AVX512 && defined(__AVX2__) && defined(__FMA__) && \
    (defined(__GNUC__) || defined(__clang__))
#define SPHBASIS_SH_ROTATION_AVX2 1
#else
#define SPHBASIS_SH_ROTATION_AVX2 0
#endif
#endif
#if SPHBASIS_SH_ROTATION_AVX512 || SPHBASIS_SH_ROTATION_AVX2
#include <immintrin.h>
#endif

namespace sphbasis::sh {

/// A row-major 3x3 matrix (core/frame.hpp).
template <class T>
using Mat3 = sphbasis::Mat3<T>;

using sphbasis::frame_to_normal;
using sphbasis::matrix_90;
using sphbasis::matrix_from_euler_zyz;
using sphbasis::matrix_from_frame;
using sphbasis::matrix_from_quaternion;
using sphbasis::matrix_rotation_z;
using sphbasis::multiply;
using sphbasis::transpose;

/// Largest band count for which a whole rotation matrix is stored (Rotation, rotation_from_*):
/// 4/3 n^3 values, 1.4e9 at 1024 bands. rotate() streams band by band up to max_bands.
inline constexpr int max_rotation_matrix_bands = 1024;

namespace detail {

using sphbasis::Quatd;
using sphbasis::quaternion_of;
using sphbasis::detail::check_orthonormal;
using sphbasis::detail::default_orthonormal_tolerance;
using sphbasis::detail::SmallBuffer;

/// Band 1 of D(R): rows/columns permuted to (y, z, x). b1[(i+1)*3 + (j+1)], i, j in -1..1.
template <class T>
std::array<T, 9> band1(const Mat3<T>& r) noexcept {
    constexpr int p[3] = {1, 2, 0};  // m = -1 -> y, 0 -> z, 1 -> x
    std::array<T, 9> b{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            b[static_cast<std::size_t>(3 * i + j)] = r[static_cast<std::size_t>(3 * p[i] + p[j])];
    return b;
}

/// Band counts up to this use the Ivanic-Ruedenberg recurrence; above it Risbo's recursion.
inline constexpr int ir_max_bands = 24;

/// The Ivanic-Ruedenberg factors of band l (in double): per column n, 1/sqrt(denominator);
/// per row m, the row parts of u, v and w (u = us[m] invd[n], ...). Four runs of 2l+1 values.
inline void ir_factors(int l, double* f) noexcept {
    const int w = 2 * l + 1;
    double* invd = f;
    double* us = f + w;
    double* vs = f + 2 * w;
    double* ws = f + 3 * w;
    const double dl = l;
    for (int n = -l; n <= l; ++n) {
        const double dn = n;
        const double den = (n > -l && n < l) ? (dl + dn) * (dl - dn) : (2 * dl) * (2 * dl - 1);
        invd[n + l] = 1 / std::sqrt(den);
    }
    for (int m = -l; m <= l; ++m) {
        const int am = m < 0 ? -m : m;
        const double dm = m, dam = am;
        const double d0 = m == 0 ? 1 : 0;
        us[m + l] = std::sqrt((dl + dm) * (dl - dm));
        vs[m + l] = 0.5 * std::sqrt((1 + d0) * (dl + dam - 1) * (dl + dam)) * (1 - 2 * d0);
        ws[m + l] = (m != 0 && am < l - 1) ? -0.5 * std::sqrt((dl - dam - 1) * (dl - dam)) : 0.0;
    }
}

/// All factors for bands 2 <= l < ir_max_bands, built once per type (thread-safe static).
template <class T>
struct IrTable {
    std::vector<T> f;
    std::array<std::size_t, ir_max_bands + 1> off{};
    IrTable() {
        std::size_t n = 0;
        for (int l = 2; l < ir_max_bands; ++l) {
            off[static_cast<std::size_t>(l)] = n;
            n += 4 * static_cast<std::size_t>(2 * l + 1);
        }
        f.resize(n);
        std::vector<double> tmp(4 * static_cast<std::size_t>(2 * ir_max_bands + 1));
        for (int l = 2; l < ir_max_bands; ++l) {
            ir_factors(l, tmp.data());
            for (std::size_t i = 0; i < 4 * static_cast<std::size_t>(2 * l + 1); ++i)
                f[off[static_cast<std::size_t>(l)] + i] = static_cast<T>(tmp[i]);
        }
    }
    const T* band(int l) const noexcept { return f.data() + off[static_cast<std::size_t>(l)]; }
};
template <class T>
const IrTable<T>& ir_table() {
    static const IrTable<T> t;
    return t;
}

/// Scratch values ir_band needs for band l: the three tables P(i, a, .), i = -1, 0, 1.
constexpr std::size_t ir_scratch_size(int l) noexcept {
    return 3 * static_cast<std::size_t>(2 * l - 1) * static_cast<std::size_t>(2 * l + 1);
}

/// One step of the Ivanic-Ruedenberg recurrence: band 2 <= l < ir_max_bands into cur
/// ((2l+1)^2, row-major, entry (m, n) at (m+l)(2l+1) + n+l) from band l-1 in prev and band 1
/// in b1, with the factors of ir_table() and ir_scratch_size(l) values of scratch.
/// The functions P(i, a, b) of Ivanic-Ruedenberg Table 2 are tabulated first (row a, column
/// b), so that every entry is a branch-free sum of five table rows times per-row factors.
template <class T>
void ir_band(int l, const std::array<T, 9>& b1, const T* SPHBASIS_RESTRICT prev,
             T* SPHBASIS_RESTRICT cur, const IrTable<T>& table,
             T* SPHBASIS_RESTRICT scratch) noexcept {
    SPHBASIS_ASSERT(l >= 2 && l < ir_max_bands);
    const int w = 2 * l + 1, pw = 2 * l - 1;
    const T* invd = table.band(l);
    const T* us = invd + w;
    const T* vs = invd + 2 * w;
    const T* ws = invd + 3 * w;
    auto R = [&](int i, int j) { return b1[static_cast<std::size_t>(3 * (i + 1) + (j + 1))]; };
    // P tables: ptab(i, a) points to the 2l+1 values P(i, a, b), b = -l..l.
    auto ptab = [&](int i, int a) { return scratch + ((i + 1) * pw + (a + l - 1)) * w; };
    for (int i = -1; i <= 1; ++i) {
        const T r0 = R(i, 0), rp = R(i, 1), rm = R(i, -1);
        for (int a = 1 - l; a <= l - 1; ++a) {
            const T* mrow = prev + (a + l - 1) * pw;
            T* p = ptab(i, a);
            for (int b = 0; b < pw; ++b) p[b + 1] = r0 * mrow[b];
            p[w - 1] = rp * mrow[pw - 1] - rm * mrow[0];
            p[0] = rp * mrow[0] + rm * mrow[pw - 1];
        }
    }
    const T s2 = T(1.4142135623730951);  // sqrt(2)
    for (int m = -l; m <= l; ++m) {
        const int am = m < 0 ? -m : m;
        const T u = us[m + l], v = vs[m + l], wf = ws[m + l];
        // U: P(0, m, .); V and W: rows of P(1, ., .) and P(-1, ., .) with signed factors.
        const T* pu = ptab(0, am < l ? m : 0);
        const T cu = am < l ? u : T(0);
        const T *pa = ptab(1, 0), *pb = ptab(-1, 0), *pc = ptab(1, 0), *pd = ptab(-1, 0);
        T ca = 0, cb = 0, cc = 0, cd = 0;
        if (m == 0) {
            pa = ptab(1, 1), ca = v;
            pb = ptab(-1, -1), cb = v;
        } else if (m == 1) {
            pa = ptab(1, 0), ca = v * s2;
        } else if (m == -1) {
            pb = ptab(-1, 0), cb = v * s2;
        } else if (m > 0) {
            pa = ptab(1, m - 1), ca = v;
            pb = ptab(-1, 1 - m), cb = -v;
        } else {
            pa = ptab(1, m + 1), ca = v;
            pb = ptab(-1, -m - 1), cb = v;
        }
        if (m != 0 && am < l - 1) {
            if (m > 0) {
                pc = ptab(1, m + 1), cc = wf;
                pd = ptab(-1, -m - 1), cd = wf;
            } else {
                pc = ptab(1, m - 1), cc = wf;
                pd = ptab(-1, 1 - m), cd = -wf;
            }
        }
        T* row = cur + (m + l) * w;
        for (int n = 0; n < w; ++n)
            row[n] = (cu * pu[n] + ca * pa[n] + cb * pb[n] + cc * pc[n] + cd * pd[n]) * invd[n];
    }
}

/// out[0..w) = B in[0..w) for a w x w row-major block B; in and out must not overlap.
template <class T, class C>
SPHBASIS_FORCEINLINE void apply_block(int w, const T* b, const C* in, C* out) {
    for (int i = 0; i < w; ++i) {
        const T* row = b + i * w;
        C acc = in[0] * row[0];
        for (int j = 1; j < w; ++j) acc = acc + in[j] * row[j];
        out[i] = acc;
    }
}
/// out = B^T in.
template <class T, class C>
SPHBASIS_FORCEINLINE void apply_block_transposed(int w, const T* b, const C* in, C* out) {
    for (int j = 0; j < w; ++j) {
        C acc = in[0] * b[j];
        for (int i = 1; i < w; ++i) acc = acc + in[i] * b[i * w + j];
        out[j] = acc;
    }
}

/// Risbo's recursion (R. Risbo, J. Geodesy 70 (1996) 383) for the complex Wigner matrices
/// D^j_{m'm} = <j m'|R|j m> (physics convention, Condon-Shortley phase), j = 0, 1/2, 1, ...
/// Spin 1/2 is the SU(2) matrix of the quaternion, [[a, b], [-conj b, conj a]] with
/// a = w - i z, b = -y - i x; each half step couples D^j with it by the stretched
/// Clebsch-Gordan coefficients sqrt((J +- M)/(2J)), all positive:
///   D^J[P][Q] = ( sqrt(P Q) a D^j[P-1][Q-1] + sqrt(P (n-Q)) b D^j[P-1][Q]
///               - sqrt((n-P) Q) conj(b) D^j[P][Q-1] + sqrt((n-P)(n-Q)) conj(a) D^j[P][Q] ) / n
/// with n = 2J, P = J + M', Q = J + M. Each step is a contraction (an isometry on the
/// symmetric tensors), so rounding errors grow only slowly with the degree.
class Risbo {
  public:
    Risbo(int bands, const Quatd& q) : ar_(q.w), ai_(-q.z), br_(-q.y), bi_(-q.x) {
        const std::size_t w = static_cast<std::size_t>(2 * std::max(bands, 1) - 1);
        re_.assign(w * w, 0.0);
        im_.assign(w * w, 0.0);
        nre_.assign(w * w, 0.0);
        nim_.assign(w * w, 0.0);
        sq_.resize(w + 1);
        for (std::size_t k = 0; k <= w; ++k) sq_[k] = std::sqrt(static_cast<double>(k));
        re_[0] = 1;
    }
    /// Current integer degree l; D^l in re()/im(), entry (m', m) at (l+m')(2l+1) + l+m.
    int degree() const noexcept { return n_ / 2; }
    const double* re() const noexcept { return re_.data(); }
    const double* im() const noexcept { return im_.data(); }
    /// Advances to degree l + 1 (two half steps).
    void next() {
        half_step();
        half_step();
    }

  private:
    void half_step() {
        const int n = n_ + 1;  // new 2J; old matrix is n x n, new one (n+1) x (n+1)
        const double inv = 1.0 / n;
        const double* s = sq_.data();
        // Rows P <= n/2 by the recursion; the others by D_{-m',-m} = (-1)^(m'-m) conj(D_{m'm}).
        for (int P = 0; P <= n / 2; ++P) {
            const double sP = s[P] * inv, sNP = s[n - P] * inv;
            const double* u = P > 0 ? re_.data() + (P - 1) * n : nullptr;  // old row P-1
            const double* ui = P > 0 ? im_.data() + (P - 1) * n : nullptr;
            const double* v = re_.data() + P * n;  // row P
            const double* vi = im_.data() + P * n;
            double* o = nre_.data() + P * (n + 1);
            double* oi = nim_.data() + P * (n + 1);
            for (int Q = 0; Q <= n; ++Q) {
                const double sQ = s[Q], sNQ = s[n - Q];
                double xr = 0, xi = 0;
                if (P > 0) {
                    // a D[P-1][Q-1] sqrt(P Q) + b D[P-1][Q] sqrt(P (n-Q))
                    double tr = 0, ti = 0;
                    if (Q > 0) {
                        const double dr = u[Q - 1], di = ui[Q - 1];
                        tr += sQ * (ar_ * dr - ai_ * di);
                        ti += sQ * (ar_ * di + ai_ * dr);
                    }
                    if (Q < n) {
                        const double dr = u[Q], di = ui[Q];
                        tr += sNQ * (br_ * dr - bi_ * di);
                        ti += sNQ * (br_ * di + bi_ * dr);
                    }
                    xr += sP * tr;
                    xi += sP * ti;
                }
                if (P < n) {
                    // -conj(b) D[P][Q-1] sqrt((n-P) Q) + conj(a) D[P][Q] sqrt((n-P)(n-Q))
                    double tr = 0, ti = 0;
                    if (Q > 0) {
                        const double dr = v[Q - 1], di = vi[Q - 1];
                        tr -= sQ * (br_ * dr + bi_ * di);
                        ti -= sQ * (br_ * di - bi_ * dr);
                    }
                    if (Q < n) {
                        const double dr = v[Q], di = vi[Q];
                        tr += sNQ * (ar_ * dr + ai_ * di);
                        ti += sNQ * (ar_ * di - ai_ * dr);
                    }
                    xr += sNP * tr;
                    xi += sNP * ti;
                }
                o[Q] = xr;
                oi[Q] = xi;
            }
        }
        for (int P = n / 2 + 1; P <= n; ++P) {
            double* o = nre_.data() + P * (n + 1);
            double* oi = nim_.data() + P * (n + 1);
            const double* src = nre_.data() + (n - P) * (n + 1);
            const double* srci = nim_.data() + (n - P) * (n + 1);
            for (int Q = 0; Q <= n; ++Q) {
                const double sg = ((P - Q) & 1) ? -1.0 : 1.0;
                o[Q] = sg * src[n - Q];
                oi[Q] = -sg * srci[n - Q];
            }
        }
        re_.swap(nre_);
        im_.swap(nim_);
        n_ = n;
    }

    double ar_, ai_, br_, bi_;
    int n_ = 0;  // 2j of the current matrix
    std::vector<double> re_, im_, nre_, nim_, sq_;
};

/// Converts the complex D^l (Condon-Shortley, physics convention) of a rotation to the block
/// of this library's real basis: Dreal = conj(U) D U^T with y = U Y, i.e. for m > 0
///   y_lm = ((-1)^m Y^m + Y^-m)/sqrt(2),  y_l,-m = -i ((-1)^m Y^m - Y^-m)/sqrt(2),  y_l0 = Y^0.
/// sign multiplies the block (-1 for an odd band of an improper matrix).
template <class T>
void complex_to_real_block(int l, const double* re, const double* im, double sign, T* out) {
    const int w = 2 * l + 1;
    const double h = constants::inv_sqrt2;
    // Up to two (index, coefficient) pairs of U per real index.
    struct Pair {
        int mu[2];
        double cr[2], ci[2];
        int n;
    };
    auto pairs = [&](int m) {
        Pair p{};
        if (m == 0) {
            p.n = 1;
            p.mu[0] = 0;
            p.cr[0] = 1;
            p.ci[0] = 0;
            return p;
        }
        const int k = m < 0 ? -m : m;
        const double sg = (k & 1) ? -1.0 : 1.0;
        p.n = 2;
        p.mu[0] = k;
        p.mu[1] = -k;
        if (m > 0) {
            p.cr[0] = sg * h, p.ci[0] = 0;
            p.cr[1] = h, p.ci[1] = 0;
        } else {
            p.cr[0] = 0, p.ci[0] = -sg * h;
            p.cr[1] = 0, p.ci[1] = h;
        }
        return p;
    };
    for (int m = -l; m <= l; ++m) {
        const Pair pm = pairs(m);
        for (int n = -l; n <= l; ++n) {
            const Pair pn = pairs(n);
            double acc = 0;
            for (int i = 0; i < pm.n; ++i)
                for (int j = 0; j < pn.n; ++j) {
                    const std::size_t e =
                        static_cast<std::size_t>((l + pm.mu[i]) * w + l + pn.mu[j]);
                    // Re( conj(cm) * D * cn )
                    const double dr = re[e], di = im[e];
                    const double tr = dr * pn.cr[j] - di * pn.ci[j];
                    const double ti = dr * pn.ci[j] + di * pn.cr[j];
                    acc += pm.cr[i] * tr + pm.ci[i] * ti;
                }
            out[(m + l) * w + n + l] = static_cast<T>(sign * acc);
        }
    }
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------
// The stored rotation matrix

/// out = D(R) in for a compile-time band count N in 1..8, D never formed: generated straight-line
/// code, defined in ops/sh_rotation_fixed.hpp (included at the end of this header). Declared here
/// because Rotation<T> and rotate() dispatch to it for bands 1..8.
template <int N, class T, class C>
SPHBASIS_FORCEINLINE void rotate(const Mat3<T>& r, const C* in, C* out) noexcept;

/// Band counts up to this go through the factored rotate<N> (Rotation<T>::apply, rotate(),
/// rotate_quaternion()).
inline constexpr int max_fixed_rotation_bands = 8;

// The block products of ops/sh_rotation_fixed.hpp (GNU vectors where available), used by a
// prepared Rotation (Rotation::prepare).
#if !defined(SPHBASIS_SH_ROTATION_VECTOR)
#if defined(__GNUC__) || defined(__clang__)
#define SPHBASIS_SH_ROTATION_VECTOR 1
#else
#define SPHBASIS_SH_ROTATION_VECTOR 0
#endif
#endif
namespace detail {
template <int L, bool Transposed, class T, class C>
SPHBASIS_FORCEINLINE void rotation_fixed_apply(const T* SPHBASIS_RESTRICT d, const C* in,
                                               C* out) noexcept;
#if SPHBASIS_SH_ROTATION_VECTOR
template <int L, class T>
SPHBASIS_FORCEINLINE void rotation_fixed_apply_vec(const T* SPHBASIS_RESTRICT cols, const T* in,
                                                   T* out) noexcept;
#endif
}  // namespace detail

namespace detail {
/// rotate<bands>(r, in, out) for bands in 1..max_fixed_rotation_bands (a run-time switch).
template <class T, class C>
void rotate_fixed_dispatch(int bands, const Mat3<T>& r, const C* in, C* out) noexcept {
    const bool done =
        with_fixed_bands(bands, [&](auto n) { sh::rotate<decltype(n)::value, T, C>(r, in, out); });
    SPHBASIS_ASSERT(done);
    (void)done;
}

/// rotate_fixed_dispatch() inlined where the optimiser knows the band count (a Rotation built
/// and applied in one scope with a literal band count, rotate(3, ...)): the switch folds to one
/// rotate<N> and the matrix stays in registers; otherwise the out-of-line switch.
template <class T, class C>
SPHBASIS_FORCEINLINE void rotate_fixed(int bands, const Mat3<T>& r, const C* in, C* out) noexcept {
#if (defined(__GNUC__) || defined(__clang__)) && !defined(SPHBASIS_NO_FORCEINLINE)
    if (__builtin_constant_p(bands)) {
        with_fixed_bands(bands, [&](auto n) SPHBASIS_INLINE_LAMBDA {
            sh::rotate<decltype(n)::value, T, C>(r, in, out);
        });
        return;
    }
#endif
    rotate_fixed_dispatch(bands, r, in, out);
}

/// True when every entry of R is finite and max |R R^T - I| <= tol, as straight-line code (the
/// six distinct entries of the symmetric R R^T). A NaN entry makes some error NaN and the
/// comparison false; an infinite one makes a diagonal error infinite.
template <class T>
SPHBASIS_FORCEINLINE bool orthonormal_within(const Mat3<T>& r, T tol) noexcept {
    const T a0 = r[0], a1 = r[1], a2 = r[2], b0 = r[3], b1 = r[4], b2 = r[5];
    const T c0 = r[6], c1 = r[7], c2 = r[8];
    const T e00 = std::fabs(a0 * a0 + a1 * a1 + a2 * a2 - T(1));
    const T e11 = std::fabs(b0 * b0 + b1 * b1 + b2 * b2 - T(1));
    const T e22 = std::fabs(c0 * c0 + c1 * c1 + c2 * c2 - T(1));
    const T e01 = std::fabs(a0 * b0 + a1 * b1 + a2 * b2);
    const T e02 = std::fabs(a0 * c0 + a1 * c1 + a2 * c2);
    const T e12 = std::fabs(b0 * c0 + b1 * c1 + b2 * c2);
    // One branch for the caller: & (not &&) evaluates every comparison.
    return (e00 <= tol) & (e11 <= tol) & (e22 <= tol) & (e01 <= tol) & (e02 <= tol) & (e12 <= tol);
}

/// matrix_from_quaternion() (core/frame.hpp) with a fast path: when the squared norm is in
/// [1e-12, 1e12] (all components finite, no under- or overflow that matters) the matrix is
/// formed directly with one division; otherwise (zero, non-finite, extreme scales) the careful
/// scaled form runs and throws where it throws. The two agree to rounding.
template <class T>
SPHBASIS_FORCEINLINE Mat3<T> quaternion_matrix(T w, T x, T y, T z) {
    const T n2 = w * w + x * x + y * y + z * z;
    if (!(n2 >= T(1e-12) && n2 <= T(1e12))) return matrix_from_quaternion(w, x, y, z);
    const T s = T(2) / n2;
    const T xs = x * s, ys = y * s, zs = z * s;
    const T wx = w * xs, wy = w * ys, wz = w * zs;
    const T xx = x * xs, xy = x * ys, xz = x * zs;
    const T yy = y * ys, yz = y * zs, zz = z * zs;
    return {T(1) - (yy + zz), xy - wz, xz + wy, xy + wz,         T(1) - (xx + zz),
            yz - wx,          xz - wy, yz + wx, T(1) - (xx + yy)};
}

#if SPHBASIS_SH_ROTATION_AVX512
/// A row-major 3x3 float matrix in lanes 0..8 of a 16-lane register (lanes 9..15 zero).
// The maskz_ forms with a full mask throughout (as core/simd.hpp does): GCC 12's unmasked
// intrinsics pass an undefined vector through and trip -Wuninitialized in users' -Wall builds.
SPHBASIS_FORCEINLINE __m512 perm16(__m512i idx, __m512 v) noexcept {
    return _mm512_maskz_permutexvar_ps(__mmask16(0xFFFF), idx, v);
}

/// Read from memory at rest (a user's matrix): one masked load. A matrix just written by scalar
/// stores would stall that load (no store forwarding into it): use mat3_avx512 for those.
SPHBASIS_FORCEINLINE __m512 load_mat3_avx512(const float* r) noexcept {
    return _mm512_maskz_loadu_ps(0x1ff, r);
}
/// The same from nine scalars (a matrix the compiler holds in registers or just stored).
SPHBASIS_FORCEINLINE __m512 mat3_avx512(const Mat3<float>& m) noexcept {
    return _mm512_setr_ps(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], 0, 0, 0, 0, 0, 0,
                          0);
}

/// orthonormal_within() on a matrix in lanes 0..8: the six distinct entries of R R^T as lanes
/// 0..5 (00, 11, 22, 01, 02, 12), each the sum over the columns j of R[a][j] R[b][j].
SPHBASIS_FORCEINLINE bool orthonormal_within_avx512(__m512 rv, float tol) noexcept {
    const __m512i ia = _mm512_setr_epi32(0, 3, 6, 0, 0, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
    const __m512i ib = _mm512_setr_epi32(0, 3, 6, 3, 6, 6, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
    const __m512i one = _mm512_set1_epi32(1);
    const __m512i ia1 = _mm512_add_epi32(ia, one), ib1 = _mm512_add_epi32(ib, one);
    const __m512i ia2 = _mm512_add_epi32(ia1, one), ib2 = _mm512_add_epi32(ib1, one);
    __m512 e = _mm512_setr_ps(-1, -1, -1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
    e = _mm512_fmadd_ps(perm16(ia, rv), perm16(ib, rv), e);
    e = _mm512_fmadd_ps(perm16(ia1, rv), perm16(ib1, rv), e);
    e = _mm512_fmadd_ps(perm16(ia2, rv), perm16(ib2, rv), e);
    // |e| <= tol, false for NaN (ordered compare): all six lanes must pass.
    const __m512 ae = _mm512_abs_ps(e);
    return _mm512_mask_cmp_ps_mask(0x3f, ae, _mm512_set1_ps(tol), _CMP_LE_OQ) == 0x3f;
}

/// quaternion_matrix() into lanes 0..8 (row-major), lanes 9..15 zero: R = I + s (S1 P Q + S2 U
/// V) with P, Q, U, V lane permutations of (w, x, y, z), S1, S2 signs and s = 2 / |q|^2:
///        00   01   02   10   11   12   20   21   22
///   PQ: -yy   xy   xz   xy  -xx   yz   xz   yz  -xx
///   UV: -zz  -wz   wy   wz  -zz  -wx  -wy   wx  -yy
/// Outside the fast range of quaternion_matrix() (zero, non-finite, extreme scales) the scalar
/// matrix_from_quaternion() runs (and throws where it throws).
SPHBASIS_FORCEINLINE __m512 quaternion_matrix_avx512(float w, float x, float y, float z) {
    const float n2 = w * w + x * x + y * y + z * z;
    if (!(n2 >= 1e-12f && n2 <= 1e12f)) {
        const Mat3<float> m = matrix_from_quaternion(w, x, y, z);
        return load_mat3_avx512(m.data());
    }
    const float s = 2.0f / n2;
    const __m512 q = _mm512_zextps128_ps512(_mm_setr_ps(w, x, y, z));
    const __m512i ip = _mm512_setr_epi32(2, 1, 1, 1, 1, 2, 1, 2, 1, 0, 0, 0, 0, 0, 0, 0);
    const __m512i iq = _mm512_setr_epi32(2, 2, 3, 2, 1, 3, 3, 3, 1, 0, 0, 0, 0, 0, 0, 0);
    const __m512i iu = _mm512_setr_epi32(3, 0, 0, 0, 3, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0);
    const __m512i iv = _mm512_setr_epi32(3, 3, 2, 3, 3, 1, 2, 1, 2, 0, 0, 0, 0, 0, 0, 0);
    const __m512 s1 = _mm512_setr_ps(-1, 1, 1, 1, -1, 1, 1, 1, -1, 0, 0, 0, 0, 0, 0, 0);
    const __m512 s2 = _mm512_setr_ps(-1, -1, 1, 1, -1, -1, -1, 1, -1, 0, 0, 0, 0, 0, 0, 0);
    const __m512 id = _mm512_setr_ps(1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0);
    __m512 t = _mm512_mul_ps(perm16(ip, q), perm16(iq, q));
    t = _mm512_mul_ps(t, s1);
    t = _mm512_fmadd_ps(_mm512_mul_ps(perm16(iu, q), s2), perm16(iv, q), t);
    return _mm512_fmadd_ps(t, _mm512_set1_ps(s), id);
}

/// Bands 0..2 of out = D(R) in (lanes 0..8) for R in lanes 0..8 of rv; reads in[0..9).
/// Lane L computes sum_j A_j[L] C_j[L]: band 1 (lanes 1..3) with A_j = R[p(L)][j] (p = y, z,
/// x) and C_j = the input (x, y, z); band 2 with the traceless symmetric Q of the coefficients
/// (see rotate_direct in ops/sh_rotation_fixed.hpp) as the bilinear forms r_a^T Q r_b of rows
/// of R, C_j = (Q r_b)_j: lanes 4..9 hold the pairs (a, b) = (0,1), (1,2), (2,2), (0,2), (0,0),
/// (1,1), scaled so that lane 8 + lane 9 is h (M00 - M11).
SPHBASIS_FORCEINLINE __m512 rotate_low_bands_avx512(__m512 rv, const float* in) noexcept {
    const __m512i ia0 = _mm512_setr_epi32(0, 3, 6, 0, 0, 3, 6, 0, 0, 3, 0, 0, 0, 0, 0, 0);
    const __m512i ib0 = _mm512_setr_epi32(0, 0, 0, 0, 3, 6, 6, 6, 0, 3, 0, 0, 0, 0, 0, 0);
    const __m512i one = _mm512_set1_epi32(1);
    const __m512i ia1 = _mm512_add_epi32(ia0, one), ia2 = _mm512_add_epi32(ia1, one);
    const __m512i ib1 = _mm512_add_epi32(ib0, one), ib2 = _mm512_add_epi32(ib1, one);
    const __mmask16 band2 = 0x3f0, band1 = 0x00e;
    const __m512 a0 = perm16(ia0, rv), a1 = perm16(ia1, rv), a2 = perm16(ia2, rv);
    const __m512 b0 = _mm512_maskz_permutexvar_ps(band2, ib0, rv),
                 b1 = _mm512_maskz_permutexvar_ps(band2, ib1, rv),
                 b2 = _mm512_maskz_permutexvar_ps(band2, ib2, rv);
    const float a = 0.57735026918962576f;  // 1/sqrt(3)
    const float c0 = in[6], c2 = in[8];
    const float qxy = in[4], qyz = in[5], qxz = in[7];
    const float qzz = c0 * (a + a), qxx = c2 - c0 * a, qyy = -c2 - c0 * a;
    __m512 cx = _mm512_maskz_mov_ps(band1, _mm512_set1_ps(in[3]));
    __m512 cy = _mm512_maskz_mov_ps(band1, _mm512_set1_ps(in[1]));
    __m512 cz = _mm512_maskz_mov_ps(band1, _mm512_set1_ps(in[2]));
    cx = _mm512_fmadd_ps(_mm512_set1_ps(qxx), b0, cx);
    cy = _mm512_fmadd_ps(_mm512_set1_ps(qxy), b0, cy);
    cz = _mm512_fmadd_ps(_mm512_set1_ps(qxz), b0, cz);
    cx = _mm512_fmadd_ps(_mm512_set1_ps(qxy), b1, cx);
    cy = _mm512_fmadd_ps(_mm512_set1_ps(qyy), b1, cy);
    cz = _mm512_fmadd_ps(_mm512_set1_ps(qyz), b1, cz);
    cx = _mm512_fmadd_ps(_mm512_set1_ps(qxz), b2, cx);
    cy = _mm512_fmadd_ps(_mm512_set1_ps(qyz), b2, cy);
    cz = _mm512_fmadd_ps(_mm512_set1_ps(qzz), b2, cz);
    __m512 o = _mm512_mul_ps(a0, cx);
    o = _mm512_fmadd_ps(a1, cy, o);
    o = _mm512_fmadd_ps(a2, cz, o);
    const float k = 0.86602540378443865f, h = 0.5f;  // sqrt(3)/2, 1/2
    o = _mm512_mul_ps(o, _mm512_setr_ps(1, 1, 1, 1, 1, 1, k, 1, h, -h, 0, 0, 0, 0, 0, 0));
    const __m512i oi = _mm512_castps_si512(o);
    const __m512 next =  // lane L+1 -> L
        _mm512_castsi512_ps(_mm512_maskz_alignr_epi32(__mmask16(0xFFFF), oi, oi, 1));
    o = _mm512_mask_add_ps(o, 0x100, o, next);
    return _mm512_mask_mov_ps(o, 0x1, _mm512_set1_ps(in[0]));
}

/// Lanes 0..8 of v into out[0..9): an 8-lane store and a scalar one, never a 16-lane masked
/// store (whose 64-byte span, masked-off lanes included, blocks later loads of whatever data
/// follows out until it retires).
SPHBASIS_FORCEINLINE void store_low_bands_avx512(float* out, __m512 v) noexcept {
    const __m256d lo = _mm512_maskz_extractf64x4_pd(__mmask8(0xF), _mm512_castps_pd(v), 0);
    _mm256_storeu_ps(out, _mm256_castpd_ps(lo));
    _mm_store_ss(out + 8, _mm512_maskz_extractf32x4_ps(__mmask8(0xF), v, 2));
}
#endif

#if SPHBASIS_SH_ROTATION_AVX2
/// Lanes of v picked by idx (vpermps).
SPHBASIS_FORCEINLINE __m256 perm8(__m256i idx, __m256 v) noexcept {
    return _mm256_permutevar8x32_ps(v, idx);
}

/// orthonormal_within() on R as r[0..7] in lo and r[8] in r8: lanes 0..5 of R R^T - I are the
/// pairs of rows (0,0), (1,1), (2,2), (0,1), (0,2), (1,2), each a sum over the columns j of
/// R[a][j] R[b][j] (r[8] blended into the lanes of column 2 that read row 2).
SPHBASIS_FORCEINLINE bool orthonormal_within_avx2(__m256 lo, __m256 r8, float tol) noexcept {
    const __m256 a0 = perm8(_mm256_setr_epi32(0, 3, 6, 0, 0, 3, 0, 0), lo);
    const __m256 b0 = perm8(_mm256_setr_epi32(0, 3, 6, 3, 6, 6, 0, 0), lo);
    const __m256 a1 = perm8(_mm256_setr_epi32(1, 4, 7, 1, 1, 4, 1, 1), lo);
    const __m256 b1 = perm8(_mm256_setr_epi32(1, 4, 7, 4, 7, 7, 1, 1), lo);
    const __m256 a2 =
        _mm256_blend_ps(perm8(_mm256_setr_epi32(2, 5, 0, 2, 2, 5, 2, 2), lo), r8, 0x04);
    const __m256 b2 =
        _mm256_blend_ps(perm8(_mm256_setr_epi32(2, 5, 0, 5, 0, 0, 2, 2), lo), r8, 0x34);
    __m256 e = _mm256_fmadd_ps(a0, b0, _mm256_setr_ps(-1, -1, -1, 0, 0, 0, 0, 0));
    e = _mm256_fmadd_ps(a1, b1, e);
    e = _mm256_fmadd_ps(a2, b2, e);
    const __m256 ae = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), e);
    // |e| <= tol, false for NaN (ordered compare): lanes 0..5 must pass.
    const int pass = _mm256_movemask_ps(_mm256_cmp_ps(ae, _mm256_set1_ps(tol), _CMP_LE_OQ));
    return (pass & 0x3f) == 0x3f;
}

/// Bands 1..2 of out = D(R) in (out[1..9), returned as 8 lanes) for R as r[0..7] in lo and r[8]
/// in r8; reads in[1..9). Band 2 as in rotate_low_bands_avx512: the bilinear forms
/// r_a^T Q r_b of rows of R, lanes 0..5 the pairs (0,1), (1,2), (2,2), (0,2), (0,0), (1,1), C_j =
/// (Q r_b)_j, lane 4 minus lane 5 (times 1/2) the last output; band 1 (rows y, z, x of R times
/// (x, y, z)) in lanes 0..2 of a second register, blended in below the shifted band 2.
SPHBASIS_FORCEINLINE __m256 rotate_low_bands_avx2(__m256 lo, __m256 r8, const float* in) noexcept {
    const __m256 a0 = perm8(_mm256_setr_epi32(0, 3, 6, 0, 0, 3, 0, 0), lo);
    const __m256 a1 = perm8(_mm256_setr_epi32(1, 4, 7, 1, 1, 4, 1, 1), lo);
    const __m256 a2 =
        _mm256_blend_ps(perm8(_mm256_setr_epi32(2, 5, 0, 2, 2, 5, 2, 2), lo), r8, 0x04);
    const __m256 b0 = perm8(_mm256_setr_epi32(3, 6, 6, 6, 0, 3, 0, 0), lo);
    const __m256 b1 = perm8(_mm256_setr_epi32(4, 7, 7, 7, 1, 4, 1, 1), lo);
    const __m256 b2 =
        _mm256_blend_ps(perm8(_mm256_setr_epi32(5, 0, 0, 0, 2, 5, 2, 2), lo), r8, 0x0e);
    const float a = 0.57735026918962576f;  // 1/sqrt(3)
    const float c0 = in[6], c2 = in[8];
    const __m256 qxy = _mm256_set1_ps(in[4]), qyz = _mm256_set1_ps(in[5]),
                 qxz = _mm256_set1_ps(in[7]);
    const __m256 qzz = _mm256_set1_ps(c0 * (a + a)), qxx = _mm256_set1_ps(c2 - c0 * a),
                 qyy = _mm256_set1_ps(-c2 - c0 * a);
    const __m256 cx = _mm256_fmadd_ps(qxz, b2, _mm256_fmadd_ps(qxy, b1, _mm256_mul_ps(qxx, b0)));
    const __m256 cy = _mm256_fmadd_ps(qyz, b2, _mm256_fmadd_ps(qyy, b1, _mm256_mul_ps(qxy, b0)));
    const __m256 cz = _mm256_fmadd_ps(qzz, b2, _mm256_fmadd_ps(qyz, b1, _mm256_mul_ps(qxz, b0)));
    __m256 o = _mm256_fmadd_ps(a2, cz, _mm256_fmadd_ps(a1, cy, _mm256_mul_ps(a0, cx)));
    const float k = 0.86602540378443865f, h = 0.5f;  // sqrt(3)/2, 1/2
    o = _mm256_mul_ps(o, _mm256_setr_ps(1, 1, k, 1, h, -h, 0, 0));
    o = _mm256_add_ps(o, perm8(_mm256_setr_epi32(6, 6, 6, 6, 5, 6, 6, 6), o));  // lane 4 += lane 5
    // band 1: lanes 0..2 = rows 1, 2, 0 of R times (x, y, z) = (in[3], in[1], in[2])
    const __m256 e0 = perm8(_mm256_setr_epi32(3, 6, 0, 0, 0, 0, 0, 0), lo);
    const __m256 e1 = perm8(_mm256_setr_epi32(4, 7, 1, 1, 1, 1, 1, 1), lo);
    const __m256 e2 =
        _mm256_blend_ps(perm8(_mm256_setr_epi32(5, 0, 2, 2, 2, 2, 2, 2), lo), r8, 0x02);
    const __m256 b = _mm256_fmadd_ps(
        e2, _mm256_set1_ps(in[2]),
        _mm256_fmadd_ps(e1, _mm256_set1_ps(in[1]), _mm256_mul_ps(e0, _mm256_set1_ps(in[3]))));
    const __m256 hi = perm8(_mm256_setr_epi32(0, 0, 0, 0, 1, 2, 3, 4), o);  // outputs 4..8
    return _mm256_blend_ps(b, hi, 0xf8);
}

/// R (row-major, 9 floats at r) as the two registers of the AVX2 kernels: r[0..7], r[8].
SPHBASIS_FORCEINLINE __m256 mat3_lo_avx2(const float* r) noexcept { return _mm256_loadu_ps(r); }
SPHBASIS_FORCEINLINE __m256 mat3_r8_avx2(const float* r) noexcept { return _mm256_set1_ps(r[8]); }

/// Bands 0..2 of out = D(R) in (out[0..9)); every read of in before the first write.
SPHBASIS_FORCEINLINE void rotate_three_bands_avx2(const float* r, const float* in,
                                                  float* out) noexcept {
    const float c0 = in[0];
    const __m256 v = rotate_low_bands_avx2(mat3_lo_avx2(r), mat3_r8_avx2(r), in);
    _mm256_storeu_ps(out + 1, v);
    out[0] = c0;
}
#endif

/// check_orthonormal() with the straight-line test first: the message (and its std::string)
/// is built only when the check fails.
template <class T>
SPHBASIS_FORCEINLINE void check_orthonormal_fast(const Mat3<T>& r, T tol, const char* fn) {
#if SPHBASIS_SH_ROTATION_AVX512
    if constexpr (std::is_same_v<T, float>) {
        if (!orthonormal_within_avx512(mat3_avx512(r), tol)) check_orthonormal(r, tol, fn);
        return;
    }
#endif
#if SPHBASIS_SH_ROTATION_AVX2
    if constexpr (std::is_same_v<T, float>) {
        if (!orthonormal_within_avx2(mat3_lo_avx2(r.data()), mat3_r8_avx2(r.data()), tol))
            check_orthonormal(r, tol, fn);
        return;
    }
#endif
    if (!orthonormal_within(r, tol)) check_orthonormal(r, tol, fn);
}
template <class T, class S>
Mat3<T> mat3_cast(const Mat3<S>& m) noexcept {
    if constexpr (std::is_same_v<T, S>) {
        return m;
    } else {
        Mat3<T> r;
        for (std::size_t i = 0; i < 9; ++i) r[i] = static_cast<T>(m[i]);
        return r;
    }
}

/// The coefficient pointers of an input and an output buffer of n values each, checked
/// (null pointer, short range) with fn in the message; one static_assert sentence for
/// mismatched or read-only buffers.
template <class In, class Out>
SPHBASIS_FORCEINLINE auto coefficient_buffers(const char* fn, const In& in, Out& out,
                                              std::size_t n) {
    using CI = std::remove_const_t<sphbasis::detail::buffer_element_t<const In>>;
    using CO = sphbasis::detail::buffer_element_t<Out>;
    static_assert(!std::is_const_v<CO>,
                  "sphbasis::sh: the output coefficient buffer must be writable (not const).");
    static_assert(std::is_same_v<CI, CO>,
                  "sphbasis::sh: the input and output coefficient buffers must hold the same "
                  "coefficient type.");
    const CI* pin = sphbasis::detail::buffer_data(fn, "input", in, n);
    CO* pout = sphbasis::detail::buffer_data(fn, "output", out, n);
    return std::pair<const CI*, CO*>(pin, pout);
}

inline std::size_t coefficient_count(int bands) noexcept {
    return static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
}
}  // namespace detail

/// D(R) for `bands` bands: block l is (2l+1)x(2l+1), row-major, entry (m, n) at
/// offset(l) + (m+l)(2l+1) + n+l. Memory: sum (2l+1)^2 = n(4n^2 - 1)/3 values.
///
/// Lazy D at 1..8 bands. A Rotation built by from_matrix / from_quaternion (and the
/// rotation_from_* helpers) with 1 <= bands <= max_fixed_rotation_bands stores only the checked
/// 3x3 matrix R: apply() runs the factored rotate<bands> (ops/sh_rotation_fixed.hpp, D never
/// formed; within a few ulp per band of the product with D) and apply_transposed() runs it with
/// R^T. D itself (data(), size(), block(), operator(), transposed()) is built on first access
/// by the same recurrence as above 8 bands, so it is bit-identical to an eagerly built D. The
/// first access is thread-safe: concurrent const use of one Rotation from several threads is
/// allowed (each racing thread may build D, one result is published by an atomic
/// compare-exchange, the others are discarded). Construction allocates nothing at <= 8 bands;
/// the first access to D allocates it. Copies and moves are value copies (a copy duplicates D
/// if it has been built, else stays lazy). The mutable data() builds D and from then on this
/// object applies D (so edits through it take effect), as a Rotation with more than 8 bands
/// always does; prepare() (4..8 bands) makes apply() multiply by D for a rotation applied to
/// many vectors. Float rotations on AVX-512 targets (SPHBASIS_SH_ROTATION_AVX512) keep R in a
/// 16-lane register image: from_quaternion forms it in registers, from_matrix checks it there
/// (the six entries of R R^T lane-wise), and apply() at 3 bands runs bands 0..2 as one
/// register computation (detail::rotate_low_bands_avx512; at 4..8 bands the same kernel does
/// bands 0..2 of rotate<N>). Measured (float, one thread, the peer harness): build + apply
/// 3 bands about 6 ns from a matrix, 7 ns from a quaternion. With AVX2 and no AVX-512
/// (SPHBASIS_SH_ROTATION_AVX2) the check and bands 0..2 run the same way in 8 lanes
/// (detail::orthonormal_within_avx2, rotate_low_bands_avx2) and bands >= 3 of rotate<4..8> one
/// band per 8-lane register: 8 / 12 ns (3 bands) and 48 / 56 ns (6 bands) from a matrix / a
/// quaternion at -march=x86-64-v3.
template <class T>
class Rotation {
    static_assert(std::is_floating_point_v<T>, "sphbasis::sh::Rotation: T is float or double.");

  public:
    using value_type = T;

    Rotation() = default;
    Rotation(const Rotation& o)
        : bands_(o.bands_),
          fixed_(o.fixed_),
          r_(o.r_),
          data_(o.data_),
          cols_(o.cols_),
          lazy_(o.lazy_copy()) {}
    Rotation(Rotation&& o) noexcept
        : bands_(o.bands_),
          fixed_(o.fixed_),
          r_(o.r_),
          data_(std::move(o.data_)),
          cols_(std::move(o.cols_)),
          lazy_(o.lazy_.load(std::memory_order_relaxed)) {
        // No read-modify-write: a moved-from object is not in concurrent use.
        o.lazy_.store(nullptr, std::memory_order_relaxed);
        o.bands_ = 0;
        o.fixed_ = false;
    }
    Rotation& operator=(const Rotation& o) {
        if (this != &o) {
            Rotation t(o);
            swap(t);
        }
        return *this;
    }
    Rotation& operator=(Rotation&& o) noexcept {
        if (this != &o) {
            Rotation t(std::move(o));
            swap(t);
        }
        return *this;
    }
    ~Rotation() { delete lazy_.load(std::memory_order_acquire); }

    /// Offset of block l in data().
    static constexpr std::size_t offset(int l) noexcept {
        const std::size_t L = static_cast<std::size_t>(l);
        return L * (4 * L * L - 1) / 3;
    }

    /// D(R) of an orthogonal 3x3 matrix: a row-major std::array<T, 9> (Mat3), a glm::mat3 /
    /// dmat3 (column-major) or an Eigen::Matrix3f / Matrix3d (see core/frame.hpp). Throws
    /// std::invalid_argument for bands outside [0, max_rotation_matrix_bands] or a matrix that
    /// is not orthonormal within `tolerance` (max |R R^T - I|; default 3e-5 for float, 1e-6 for
    /// double). At 1..8 bands only R is stored (D is built on first access, see above).
    /// Otherwise cost O(n^3): 4/3 n^3 entries at about 15 flops each; memory n(4n^2 - 1)/3
    /// entries of T (double: 256 bands 179 MB, 1024 bands 11.5 GB), checked against
    /// SPHBASIS_MAX_TABLE_BYTES before allocating.
    template <class M>
    SPHBASIS_FORCEINLINE static Rotation from_matrix(
        int bands, const M& r, T tolerance = detail::default_orthonormal_tolerance<T>()) {
        const char* fn = "sh::Rotation::from_matrix";
        sphbasis::detail::check_range(fn, "bands", bands, 0, max_rotation_matrix_bands);
#if SPHBASIS_SH_ROTATION_AVX512
        if constexpr (vec_ && std::is_same_v<M, Mat3<T>>) {
            const __m512 rv = detail::load_mat3_avx512(r.data());  // the caller's matrix
            if (!detail::orthonormal_within_avx512(rv, tolerance))
                detail::check_orthonormal(r, tolerance, fn);
            return build_vec(bands, rv);
        }
#endif
        const Mat3<T> m = detail::mat3_cast<T>(to_mat3(r, fn));
        detail::check_orthonormal_fast(m, tolerance, fn);
        return build(bands, m);
    }

    /// D of the quaternion (w, x, y, z): normalised if not unit; zero or non-finite throws.
    SPHBASIS_FORCEINLINE static Rotation from_quaternion(int bands, T w, T x, T y, T z) {
        sphbasis::detail::check_range("sh::Rotation::from_quaternion", "bands", bands, 0,
                                      max_rotation_matrix_bands);
#if SPHBASIS_SH_ROTATION_AVX512
        if constexpr (vec_) return build_vec(bands, detail::quaternion_matrix_avx512(w, x, y, z));
#endif
        return build(bands, detail::quaternion_matrix(w, x, y, z));
    }
    /// D of a quaternion type: glm::quat / dquat, Eigen::Quaternionf / d, sphbasis::Quat.
    template <class Q>
    static Rotation from_quaternion(int bands, const Q& q) {
        const auto p = to_quat(q);
        return from_quaternion(bands, T(p.w), T(p.x), T(p.y), T(p.z));
    }

  private:
#if SPHBASIS_SH_ROTATION_AVX512
    /// Float rotations keep R as 16 lanes (0..8 row-major, then zeros) for the AVX-512 kernels.
    static constexpr bool vec_ = std::is_same_v<T, float>;
#else
    static constexpr bool vec_ = false;
#endif
    /// The checked matrix, row-major.
    Mat3<T> mat() const noexcept {
        Mat3<T> m;
        for (std::size_t i = 0; i < 9; ++i) m[i] = r_[i];
        return m;
    }
#if SPHBASIS_SH_ROTATION_AVX512
    /// build() from R in lanes 0..8 of rv (one 16-lane store, read back by apply() as one load).
    SPHBASIS_FORCEINLINE static Rotation build_vec(int bands, __m512 rv) {
        Rotation out;  // one named result: returned without a move
        if (bands >= 1 && bands <= max_fixed_rotation_bands) {
            out.bands_ = bands;
            out.fixed_ = true;
            _mm512_storeu_ps(out.r_.data(), rv);
        } else {
            Mat3<T> m;
            _mm512_mask_storeu_ps(m.data(), 0x1ff, rv);
            out.init(bands, m);
        }
        return out;
    }
#endif
    static Rotation build(int bands, const Mat3<T>& r) {
#if SPHBASIS_SH_ROTATION_AVX512
        if constexpr (vec_) return build_vec(bands, detail::mat3_avx512(r));
#endif
        Rotation out;
        out.init(bands, r);
        return out;
    }
    /// Sets up a default-constructed Rotation: at 1..8 bands R only, else D.
    void init(int bands, const Mat3<T>& r) {
        Rotation& out = *this;
        out.bands_ = bands;
        for (std::size_t i = 0; i < 9; ++i) out.r_[i] = r[i];
        if (bands >= 1 && bands <= max_fixed_rotation_bands) {
            out.fixed_ = true;  // D on first access
            return;
        }
        // sum_l (2l + 1)^2 = n (4 n^2 - 1)/3 entries: n = 1024, double: 11.5 GB.
        const double bytes = double(bands) * (4.0 * double(bands) * bands - 1) / 3 * sizeof(T);
        if (!(bytes <= static_cast<double>(SPHBASIS_MAX_TABLE_BYTES)))
            sphbasis::detail::check_table_bytes("sh::Rotation", bytes,
                                                std::to_string(bands) + " bands");
        out.data_.assign(offset(bands), T(0));
        build_d(bands, r, out.data_.data());
    }

    /// The n(4n^2 - 1)/3 values of D(R) into d (zero-initialised).
    static void build_d(int bands, const Mat3<T>& r, T* d) {
        if (bands == 0) return;
        d[0] = T(1);
        if (bands == 1) return;
        if (bands > detail::ir_max_bands) {
            bool improper = false;
            detail::Risbo risbo(bands, detail::quaternion_of(r, improper));
            for (int l = 1; l < bands; ++l) {
                risbo.next();
                detail::complex_to_real_block(l, risbo.re(), risbo.im(),
                                              improper && (l & 1) ? -1.0 : 1.0, d + offset(l));
            }
            return;
        }
        const std::array<T, 9> b1 = detail::band1(r);
        std::copy(b1.begin(), b1.end(), d + offset(1));
        const detail::IrTable<T>& table = detail::ir_table<T>();
        detail::SmallBuffer<T, 512> scratch(detail::ir_scratch_size(bands - 1));
        for (int l = 2; l < bands; ++l)
            detail::ir_band(l, b1, d + offset(l - 1), d + offset(l), table, scratch.data());
    }

    /// D, built on first access when fixed_ (thread-safe publication, see the class comment).
    const std::vector<T>& d() const {
        if (!fixed_) return data_;
        if (const std::vector<T>* p = lazy_.load(std::memory_order_acquire)) return *p;
        auto fresh = std::make_unique<std::vector<T>>(offset(bands_), T(0));
        build_d(bands_, mat(), fresh->data());
        std::vector<T>* expected = nullptr;
        if (lazy_.compare_exchange_strong(expected, fresh.get(), std::memory_order_acq_rel,
                                          std::memory_order_acquire))
            return *fresh.release();
        return *expected;  // another thread published first; ours is freed
    }
    std::vector<T>* lazy_copy() const {
        const std::vector<T>* p = lazy_.load(std::memory_order_acquire);
        return p ? new std::vector<T>(*p) : nullptr;
    }
    void swap(Rotation& o) noexcept {
        std::swap(bands_, o.bands_);
        std::swap(fixed_, o.fixed_);
        std::swap(r_, o.r_);
        data_.swap(o.data_);
        cols_.swap(o.cols_);
        std::vector<T>* a = lazy_.load(std::memory_order_relaxed);
        lazy_.store(o.lazy_.load(std::memory_order_relaxed), std::memory_order_relaxed);
        o.lazy_.store(a, std::memory_order_relaxed);
    }

  public:
    int bands() const noexcept { return bands_; }
    /// Number of stored values, n(4n^2 - 1)/3 (builds D if it is lazy).
    std::size_t size() const { return d().size(); }
    const T* data() const { return d().data(); }
    /// Mutable D: builds it if lazy, and from then on apply() uses D (edits take effect).
    T* data() {
        if (fixed_) {
            data_ = d();
            fixed_ = false;
            cols_.clear();
            delete lazy_.exchange(nullptr, std::memory_order_acq_rel);
        }
        return data_.data();
    }
    /// Block l, (2l+1)^2 values row-major.
    const T* block(int l) const { return d().data() + offset(l); }
    /// Entry (m, n) of band l (|m|, |n| <= l < bands()): d y_lm(Rw) / d y_ln(w).
    T operator()(int l, int m, int n) const {
        SPHBASIS_ASSERT(l >= 0 && l < bands_ && m >= -l && m <= l && n >= -l && n <= l);
        return d()[offset(l) + static_cast<std::size_t>((m + l) * (2 * l + 1) + n + l)];
    }
    /// For a rotation applied to many vectors, at 4..8 bands: forms D (if it is not formed yet)
    /// and from then on apply() and apply_transposed() multiply by D, block after block
    /// (column-major copies of the blocks; for float/double coefficients 16-lane column vectors
    /// times broadcast inputs) instead of running the factored rotate<bands> (measured, float,
    /// 6 bands: 20 against 30 ns per vector). A no-op at 1..3 bands, where the factored form is
    /// the faster one (3 bands: 4.4 ns, the product 14 ns), above 8 bands (D is always used
    /// there) and when prepared. Not thread-safe against concurrent use of this object (like any
    /// non-const call).
    void prepare() {
        if (!fixed_ || bands_ <= 3 || !cols_.empty()) return;
        const std::vector<T>& dm = d();
        cols_.assign(offset(bands_) + 16, T(0));
        for (int l = 0; l < bands_; ++l) {
            const int w = 2 * l + 1;
            const T* b = dm.data() + offset(l);
            T* c = cols_.data() + offset(l);
            for (int i = 0; i < w; ++i)
                for (int j = 0; j < w; ++j) c[j * w + i] = b[i * w + j];
        }
    }
    /// True after prepare() at 4..8 bands (apply() multiplies by D).
    bool prepared() const noexcept { return !cols_.empty(); }

    /// True while D has not been formed (apply runs rotate<bands>); false above 8 bands.
    bool lazy() const noexcept {
        return fixed_ && lazy_.load(std::memory_order_acquire) == nullptr;
    }

    /// The contiguous-range overloads (not both pointers: those take the pointer overloads).
    template <class In, class Out>
    using ranges_only =
        std::enable_if_t<!(std::is_pointer_v<In> && std::is_pointer_v<std::decay_t<Out>>), int>;

    /// out = D in for coefficient vectors of bands() bands (bands()^2 values): raw pointers or
    /// contiguous ranges (.data(), .size() >= bands()^2). The coefficient type C is any type
    /// with C + C and C * T (float, double, RGB). in == out is allowed. Cost sum (2l+1)^2, or
    /// rotate<bands()> at 1..8 bands.
    template <class C>
    SPHBASIS_FORCEINLINE void apply(const C* in, C* out) const {
        apply_impl<false>(in, out, "sh::Rotation::apply");
    }
    /// apply() on contiguous ranges (.data(), .size() >= bands()^2; checked).
    template <class In, class Out, ranges_only<In, Out> = 0>
    void apply(const In& in, Out&& out) const {
        apply_ranges<false>("sh::Rotation::apply", in, out);
    }
    /// out = D^T in: the inverse rotation.
    template <class C>
    SPHBASIS_FORCEINLINE void apply_transposed(const C* in, C* out) const {
        apply_impl<true>(in, out, "sh::Rotation::apply_transposed");
    }
    /// apply_transposed() on contiguous ranges.
    template <class In, class Out, ranges_only<In, Out> = 0>
    void apply_transposed(const In& in, Out&& out) const {
        apply_ranges<true>("sh::Rotation::apply_transposed", in, out);
    }
    /// apply() on a std::vector; throws std::invalid_argument unless it has bands()^2 entries.
    template <class C>
    std::vector<C> apply(const std::vector<C>& in) const {
        const std::size_t n = detail::coefficient_count(bands_);
        if (in.size() != n)
            sphbasis::detail::throw_invalid(
                "sh::Rotation::apply",
                std::to_string(n) + " coefficients, got " + std::to_string(in.size()));
        std::vector<C> out(in.size());
        if (!in.empty()) apply(in.data(), out.data());
        return out;
    }

    /// D^T = D(R^T), the inverse rotation (at 1..8 bands: lazy again, with R^T; its D, when
    /// formed, is D(R^T) from the recurrence, equal to the transpose of D(R) to rounding).
    Rotation transposed() const {
        if (fixed_) return build(bands_, transpose(mat()));
        Rotation t = *this;
        for (int l = 1; l < bands_; ++l) {
            const int w = 2 * l + 1;
            T* b = t.data_.data() + offset(l);
            for (int i = 0; i < w; ++i)
                for (int j = i + 1; j < w; ++j) std::swap(b[i * w + j], b[j * w + i]);
        }
        return t;
    }

  private:
    template <bool Transposed, class In, class Out>
    void apply_ranges(const char* fn, const In& in, Out& out) const {
        const auto p = detail::coefficient_buffers(fn, in, out, detail::coefficient_count(bands_));
        apply_impl<Transposed>(p.first, p.second, fn);
    }
    template <bool Transposed, class C>
    SPHBASIS_FORCEINLINE void apply_impl(const C* in, C* out, const char* fn) const {
        if (bands_ == 0) return;
        if (!in) sphbasis::detail::throw_null_buffer(fn, "input");
        if (!out) sphbasis::detail::throw_null_buffer(fn, "output");
        if (fixed_) {
            if (!cols_.empty()) {
                apply_cols<Transposed>(in, out);
                return;
            }
#if SPHBASIS_SH_ROTATION_AVX512
            if constexpr (vec_ && !Transposed && std::is_same_v<C, float>) {
                if (bands_ == 3) {
                    const __m512 rv = _mm512_loadu_ps(r_.data());
                    detail::store_low_bands_avx512(out, detail::rotate_low_bands_avx512(rv, in));
                    return;
                }
            }
#endif
#if SPHBASIS_SH_ROTATION_AVX2
            if constexpr (!Transposed && std::is_same_v<T, float> && std::is_same_v<C, float>) {
                if (bands_ == 3) {
                    detail::rotate_three_bands_avx2(r_.data(), in, out);
                    return;
                }
            }
#endif
            if constexpr (Transposed)
                detail::rotate_fixed(bands_, transpose(mat()), in, out);
            else
                detail::rotate_fixed(bands_, mat(), in, out);
            return;
        }
        apply_d<Transposed>(in, out);
    }
    /// out = D in (D^T in) from the column-major blocks of prepare().
    template <bool Transposed, class C>
    void apply_cols(const C* in, C* out) const noexcept {
        const T* c = cols_.data();
        detail::with_fixed_bands(bands_, [&](auto n) {
            constexpr int N = decltype(n)::value;
#if SPHBASIS_SH_ROTATION_VECTOR
            if constexpr (!Transposed && std::is_same_v<C, T>) {
                detail::rotation_fixed_apply_vec<N>(c, in, out);
                return;
            }
#endif
            detail::rotation_fixed_apply<N, !Transposed>(c, in, out);
        });
    }
    /// out = D in (D^T in) from the stored blocks.
    template <bool Transposed, class C>
    void apply_d(const C* in, C* out) const {
        out[0] = in[0] * data_[0];
        detail::SmallBuffer<C, 16> buf(static_cast<std::size_t>(2 * bands_ - 1));
        for (int l = 1; l < bands_; ++l) {
            const int w = 2 * l + 1, k0 = l * l;
            for (int j = 0; j < w; ++j) buf[static_cast<std::size_t>(j)] = in[k0 + j];
            const T* b = data_.data() + offset(l);
            if (Transposed)
                detail::apply_block_transposed(w, b, buf.data(), out + k0);
            else
                detail::apply_block(w, b, buf.data(), out + k0);
        }
    }

    int bands_ = 0;
    bool fixed_ = false;  // 1..8 bands from a matrix: apply through rotate<bands_>(mat())
    std::array<T, vec_ ? 16 : 9> r_{};  // the checked matrix (row-major; float: zero-padded)
    std::vector<T> data_;               // D when !fixed_
    std::vector<T> cols_;               // after prepare(): D's blocks column-major, then 16 zeros
    mutable std::atomic<std::vector<T>*> lazy_{nullptr};  // D when fixed_, once built
};

/// D(R) of an orthogonal matrix (std::array<T, 9> row-major, glm::mat3 / dmat3, Eigen::Matrix3f
/// / d); see Rotation::from_matrix. The scalar type is that of the matrix.
template <class M>
SPHBASIS_FORCEINLINE Rotation<rotation_scalar_t<M>> rotation_from_matrix(
    int bands, const M& r,
    rotation_scalar_t<M> tolerance =
        detail::default_orthonormal_tolerance<rotation_scalar_t<M>>()) {
    return Rotation<rotation_scalar_t<M>>::from_matrix(bands, r, tolerance);
}

/// D of the quaternion (w, x, y, z); a non-unit quaternion is normalised, a zero or
/// non-finite one throws std::invalid_argument.
template <class T>
SPHBASIS_FORCEINLINE Rotation<T> rotation_from_quaternion(int bands, T w, T x, T y, T z) {
    return Rotation<T>::from_quaternion(bands, w, x, y, z);
}
/// D of a quaternion type (glm::quat / dquat, Eigen::Quaternionf / d, sphbasis::Quat).
template <class Q>
Rotation<rotation_scalar_t<Q>> rotation_from_quaternion(int bands, const Q& q) {
    return Rotation<rotation_scalar_t<Q>>::from_quaternion(bands, q);
}

/// D of the ZYZ Euler angles: R = Rz(alpha) Ry(beta) Rz(gamma) (matrix_from_euler_zyz).
template <class T>
Rotation<T> rotation_from_euler_zyz(int bands, T alpha, T beta, T gamma) {
    return Rotation<T>::from_matrix(bands, matrix_from_euler_zyz(alpha, beta, gamma));
}

/// D of the rotation taking +z to the normal n (frame_to_normal). Its transpose takes
/// world-space coefficients into that tangent frame: the R of Sloan, Lehtinen and Kautz (2005)
/// in e(n) = y(n)^T C R M l.
template <class T>
Rotation<T> rotation_to_normal(int bands, T nx, T ny, T nz) {
    return Rotation<T>::from_matrix(bands, frame_to_normal(nx, ny, nz));
}
/// rotation_to_normal() of any 3-vector type (glm::vec3, Eigen::Vector3d, vec3).
template <class D, std::enable_if_t<!std::is_arithmetic_v<D>, int> = 0>
Rotation<direction_scalar_t<D>> rotation_to_normal(int bands, const D& n) {
    return rotation_to_normal(bands, component<0>(n), component<1>(n), component<2>(n));
}

/// D of k exact quarter turns about axis 0 (x), 1 (y) or 2 (z) (matrix_90).
template <class T>
Rotation<T> rotation_90(int bands, int axis, int quarter_turns) {
    return Rotation<T>::from_matrix(bands, matrix_90<T>(axis, quarter_turns));
}

// ---------------------------------------------------------------------------------------------
// Applying rotations without storing the matrix

namespace detail {
/// rotate() after its checks: bands >= 1, r orthogonal, in and out non-null.
template <class T, class C>
void rotate_checked(int bands, const Mat3<T>& r, const C* in, C* out) {
    if (bands <= max_fixed_rotation_bands) {
        rotate_fixed(bands, r, in, out);
        return;
    }
    out[0] = in[0] * T(1);
    if (bands == 1) return;
    const std::size_t wmax = static_cast<std::size_t>(2 * bands - 1);
    if (bands > detail::ir_max_bands) {
        bool improper = false;
        detail::Risbo risbo(bands, detail::quaternion_of(r, improper));
        std::vector<T> blk(wmax * wmax);
        std::vector<C> buf(wmax);
        for (int l = 1; l < bands; ++l) {
            risbo.next();
            detail::complex_to_real_block(l, risbo.re(), risbo.im(),
                                          improper && (l & 1) ? -1.0 : 1.0, blk.data());
            const int w = 2 * l + 1, k0 = l * l;
            for (int j = 0; j < w; ++j) buf[static_cast<std::size_t>(j)] = in[k0 + j];
            detail::apply_block(w, blk.data(), buf.data(), out + k0);
        }
        return;
    }
    const std::array<T, 9> b1 = detail::band1(r);
    detail::SmallBuffer<T, 1024> mats(2 * wmax * wmax + detail::ir_scratch_size(bands - 1));
    T* prev = mats.data();
    T* cur = prev + wmax * wmax;
    T* scratch = cur + wmax * wmax;
    const detail::IrTable<T>& table = detail::ir_table<T>();
    detail::SmallBuffer<C, 16> buf(wmax);
    std::copy(b1.begin(), b1.end(), prev);
    for (int j = 0; j < 3; ++j) buf[static_cast<std::size_t>(j)] = in[1 + j];
    detail::apply_block(3, prev, buf.data(), out + 1);
    for (int l = 2; l < bands; ++l) {
        detail::ir_band(l, b1, prev, cur, table, scratch);
        const int w = 2 * l + 1, k0 = l * l;
        for (int j = 0; j < w; ++j) buf[static_cast<std::size_t>(j)] = in[k0 + j];
        detail::apply_block(w, cur, buf.data(), out + k0);
        std::swap(prev, cur);
    }
}
}  // namespace detail

namespace detail {
/// The buffer checks of rotate() and rotate_quaternion(), then rotate_checked(). Pointers take
/// the direct path (one null compare each); ranges are size-checked first.
template <class T, class In, class Out>
SPHBASIS_FORCEINLINE void rotate_entry(const char* fn, int bands, const Mat3<T>& r, const In& in,
                                       Out& out) {
    if constexpr (std::is_pointer_v<In> && std::is_pointer_v<std::remove_cv_t<Out>>) {
        static_assert(std::is_same_v<std::remove_const_t<std::remove_pointer_t<In>>,
                                     std::remove_pointer_t<std::remove_cv_t<Out>>>,
                      "sphbasis::sh: the output coefficient buffer must be writable and hold the "
                      "coefficient type of the input.");
        if (bands == 0) return;
        if (!in) sphbasis::detail::throw_null_buffer(fn, "input");
        if (!out) sphbasis::detail::throw_null_buffer(fn, "output");
        if (bands <= max_fixed_rotation_bands)
            rotate_fixed(bands, r, in, static_cast<std::remove_cv_t<Out>>(out));
        else
            rotate_checked(bands, r, in, static_cast<std::remove_cv_t<Out>>(out));
    } else {
        const auto p = coefficient_buffers(fn, in, out, coefficient_count(bands));
        if (bands == 0) return;
        if (bands <= max_fixed_rotation_bands)
            rotate_fixed(bands, r, p.first, p.second);
        else
            rotate_checked(bands, r, p.first, p.second);
    }
}

/// The row-major matrix of a rotation argument: a matrix type checked to be orthonormal within
/// tol, or a quaternion type (orthonormal by construction).
template <class R>
Mat3<rotation_scalar_t<R>> checked_rotation_matrix(const R& r, rotation_scalar_t<R> tol,
                                                   const char* fn) {
    if constexpr (is_quaternion_v<R>) {
        (void)tol;
        (void)fn;
        const auto p = to_quat(r);
        return quaternion_matrix(p.w, p.x, p.y, p.z);
    } else {
        const Mat3<rotation_scalar_t<R>> m = to_mat3(r, fn);
        check_orthonormal_fast(m, tol, fn);
        return m;
    }
}
}  // namespace detail

/// out = D(R) in for `bands` bands without storing D: each band is built from the previous
/// one and applied at once (O(n^2) scratch memory, O(n^3) time, up to max_bands bands).
/// R is a matrix (std::array<T, 9> row-major, glm::mat3 / dmat3 column-major, Eigen::Matrix3f
/// / d), checked to be orthonormal within `tolerance`, or a quaternion (glm::quat, Eigen::
/// Quaternion, sphbasis::Quat; normalised, not checked). in and out are raw pointers or
/// contiguous ranges of bands^2 coefficients; C is any type with C + C and C * T (RGB
/// coefficients rotate with one matrix build). in == out is allowed. Throws
/// std::invalid_argument for bad bands, null or short buffers or a non-orthonormal matrix.
template <class R, class In, class Out>
void rotate(int bands, const R& r, const In& in, Out&& out,
            rotation_scalar_t<R> tolerance =
                detail::default_orthonormal_tolerance<rotation_scalar_t<R>>()) {
    using T = rotation_scalar_t<R>;
    const char* fn = "sh::rotate";
    sphbasis::detail::check_range(fn, "bands", bands, 0, max_bands);
    const Mat3<T> m = detail::checked_rotation_matrix(r, tolerance, fn);
    detail::rotate_entry(fn, bands, m, in, out);
}

/// rotate() by the quaternion (w, x, y, z) (normalised if not unit; zero/non-finite throws).
/// The matrix of a quaternion is orthonormal by construction, so it is not checked again.
template <class T, class In, class Out>
void rotate_quaternion(int bands, T w, T x, T y, T z, const In& in, Out&& out) {
    const char* fn = "sh::rotate_quaternion";
    sphbasis::detail::check_range(fn, "bands", bands, 0, max_bands);
    const Mat3<T> r = detail::quaternion_matrix(w, x, y, z);
    detail::rotate_entry(fn, bands, r, in, out);
}
/// rotate() by a quaternion type (glm::quat / dquat, Eigen::Quaternionf / d, sphbasis::Quat).
template <class Q, class In, class Out>
void rotate_quaternion(int bands, const Q& q, const In& in, Out&& out) {
    const auto p = to_quat(q);
    rotate_quaternion(bands, p.w, p.x, p.y, p.z, in, out);
}

namespace detail {
// cos_sin<Full>(a, c, s): generated, sh_rotation_cos_sin.hpp.

template <class T, class C>
void rotate_z_checked(int bands, T angle, const C* in, C* out) noexcept {
    for (int l = 0; l < bands; ++l) out[index(l, 0)] = in[index(l, 0)];
    const double a = static_cast<double>(angle);
    double c1, s1;
    cos_sin<!std::is_same_v<T, float>>(a, c1, s1);
    double cm = 1, sm = 0;
    for (int m = 1; m < bands; ++m) {
        if (m % 16 == 0) {
            cm = std::cos(m * a);
            sm = std::sin(m * a);
        } else {
            const double c = cm * c1 - sm * s1;
            sm = sm * c1 + cm * s1;
            cm = c;
        }
        const T c = T(cm), s = T(sm);
        for (int l = m; l < bands; ++l) {
            const C cc = in[index(l, m)], ss = in[index(l, -m)];
            out[index(l, m)] = cc * c + ss * (-s);
            out[index(l, -m)] = ss * c + cc * s;
        }
    }
}
}  // namespace detail

/// Rotation by `angle` radians about z, O(n^2): for each m > 0 the pair (c = coefficient of
/// y_lm ~ cos(m phi), s = coefficient of y_l,-m ~ sin(m phi)) becomes
///   c' = c cos(m a) - s sin(m a),   s' = s cos(m a) + c sin(m a).
/// cos(m a), sin(m a) come from std::cos/std::sin every 16 orders and complex multiplication
/// between, so the error stays at a few ulp for any band count. in and out are raw pointers or
/// contiguous ranges of bands^2 coefficients; in == out is allowed. A non-finite angle throws
/// std::invalid_argument (as rotate() does for a non-finite matrix).
template <class T, class In, class Out>
void rotate_z(int bands, T angle, const In& in, Out&& out) {
    check_bands(bands, "sh::rotate_z");
    if (!std::isfinite(static_cast<double>(angle)))
        sphbasis::detail::throw_invalid(
            "sh::rotate_z", "a finite angle, got " + std::to_string(static_cast<double>(angle)));
    const auto [pin, pout] =
        detail::coefficient_buffers("sh::rotate_z", in, out, detail::coefficient_count(bands));
    if (bands == 0) return;
    detail::rotate_z_checked(bands, angle, pin, pout);
}

namespace detail {
/// D of the quarter turn about x for `bands` bands (rotation_90(bands, 0, 1)), built once per
/// (T, bands) and kept for the life of the process (thread-safe; after the first call of a
/// thread for a band count, no lock).
template <class T>
const Rotation<T>& quarter_turn_x(int bands) {
    thread_local int last_bands = -1;
    thread_local const Rotation<T>* last = nullptr;
    if (bands == last_bands) return *last;
    static std::mutex mutex;
    static std::map<int, std::unique_ptr<const Rotation<T>>> cache;
    const std::lock_guard<std::mutex> lock(mutex);
    auto& slot = cache[bands];
    if (!slot) slot = std::make_unique<const Rotation<T>>(rotation_90<T>(bands, 0, 1));
    last_bands = bands;
    last = slot.get();
    return *slot;
}
}  // namespace detail

/// Rotation by the ZYZ Euler angles (radians), R = Rz(alpha) Ry(beta) Rz(gamma) as in
/// matrix_from_euler_zyz(), without building D(R): with X = D(quarter turn about x) and Z(a)
/// the z rotation (rotate_z),
///   D(R) = Z(alpha) X^T Z(beta) X Z(gamma),
/// since X^T Z(beta) X is the rotation by beta about y. X is built once per band count and
/// coefficient scalar and cached (detail::quarter_turn_x). Cost 2 sum (2l+1)^2 + O(n^2), about
/// 1.5x the apply of a stored Rotation; the result agrees with rotate() of the same matrix to
/// rounding. C is any type with C + C and C * S, S = coefficient_scalar_t<C> (the angles are
/// converted to S). in and out are raw pointers or contiguous ranges of bands^2 coefficients;
/// in == out is allowed. Throws std::invalid_argument for bands outside
/// [0, max_rotation_matrix_bands] or null or short buffers.
template <class T, class In, class Out>
void rotate_zyz(int bands, T alpha, T beta, T gamma, const In& in, Out&& out) {
    static_assert(std::is_floating_point_v<T>,
                  "sphbasis::sh::rotate_zyz: the angles are float or double.");
    const char* fn = "sh::rotate_zyz";
    sphbasis::detail::check_range(fn, "bands", bands, 0, max_rotation_matrix_bands);
    const auto [pin, pout] =
        detail::coefficient_buffers(fn, in, out, detail::coefficient_count(bands));
    if (bands == 0) return;
    using C = std::remove_pointer_t<decltype(pout)>;
    using S = coefficient_scalar_t<C>;
    const Rotation<S>& x = detail::quarter_turn_x<S>(bands);
    detail::rotate_z_checked(bands, S(gamma), pin, pout);
    x.apply(pout, pout);
    detail::rotate_z_checked(bands, S(beta), pout, pout);
    x.apply_transposed(pout, pout);
    detail::rotate_z_checked(bands, S(alpha), pout, pout);
}

/// Rotation by k quarter turns (k * 90 degrees) about z: exact (a signed permutation of the
/// (m, -m) pairs). in and out are raw pointers or contiguous ranges; in == out is allowed.
template <class In, class Out>
void rotate_z90(int bands, int quarter_turns, const In& in, Out&& out) {
    check_bands(bands, "sh::rotate_z90");
    const auto [pin, pout] =
        detail::coefficient_buffers("sh::rotate_z90", in, out, detail::coefficient_count(bands));
    if (bands == 0) return;
    using C = std::remove_pointer_t<decltype(pout)>;
    const int k = ((quarter_turns % 4) + 4) % 4;
    for (int l = 0; l < bands; ++l) pout[index(l, 0)] = pin[index(l, 0)];
    for (int m = 1; m < bands; ++m) {
        const int r = (m * k) % 4;  // cos(m k pi/2), sin(m k pi/2) in {0, +-1}
        for (int l = m; l < bands; ++l) {
            const C cc = pin[index(l, m)], ss = pin[index(l, -m)];
            switch (r) {
                case 0:
                    pout[index(l, m)] = cc;
                    pout[index(l, -m)] = ss;
                    break;
                case 1:
                    pout[index(l, m)] = -ss;
                    pout[index(l, -m)] = cc;
                    break;
                case 2:
                    pout[index(l, m)] = -cc;
                    pout[index(l, -m)] = -ss;
                    break;
                default:
                    pout[index(l, m)] = ss;
                    pout[index(l, -m)] = -cc;
                    break;
            }
        }
    }
}

/// The reflection of the function through a coordinate plane: axis 2 maps z -> -z and
/// multiplies y_lm by (-1)^(l+m); axis 1 (y -> -y) negates m < 0; axis 0 (x -> -x) multiplies
/// by (-1)^m for m >= 0 and (-1)^(m+1) for m < 0. Exact. in and out are raw pointers or
/// contiguous ranges; in == out is allowed. C needs unary -.
template <class In, class Out>
void reflect(int bands, int axis, const In& in, Out&& out) {
    check_bands(bands, "sh::reflect");
    if (axis < 0 || axis > 2)
        sphbasis::detail::throw_invalid("sh::reflect",
                                        "axis 0 (x), 1 (y) or 2 (z), got " + std::to_string(axis));
    const auto [pin, pout] =
        detail::coefficient_buffers("sh::reflect", in, out, detail::coefficient_count(bands));
    if (bands == 0) return;
    using C = std::remove_pointer_t<decltype(pout)>;
    for (int l = 0; l < bands; ++l)
        for (int m = -l; m <= l; ++m) {
            bool neg;
            const int am = m < 0 ? -m : m;
            if (axis == 2)
                neg = ((l + am) & 1) != 0;
            else if (axis == 1)
                neg = m < 0;
            else
                neg = m >= 0 ? (am & 1) != 0 : (am & 1) == 0;
            const C v = pin[index(l, m)];
            pout[index(l, m)] = neg ? -v : v;
        }
}

/// z -> -z (flipping the hemisphere; Iwanicki and Sloan 2009, Sec. 3): y_lm picks up
/// (-1)^(l+m).
template <class In, class Out>
void reflect_z(int bands, const In& in, Out&& out) {
    reflect(bands, 2, in, out);
}

}  // namespace sphbasis::sh

// rotate<N> (declared above, used by Rotation<T> and rotate() at 1..8 bands).
#include "sh_rotation_fixed.hpp"
