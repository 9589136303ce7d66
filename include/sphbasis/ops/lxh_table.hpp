// sphbasis: L x H tables. For distant lighting L (RGB, N bands) and a visibility function V
// (K bands), the diffuse reflection integral
//     I(n) = integral of L(w) V(w) H_n(w) dw,    H_n(w) = max(n . w, 0),
// equals V . (L x H)(n), where (L x H)(n) is the projection onto K bands of the product
// L(w) H_n(w): K^2 RGB coefficients per normal. Tabulating them over the normals (a cube map, a
// dual paraboloid, ... any parameterization of param/) turns the shading of a normal-mapped
// surface with precomputed visibility into one lookup and a K^2 dot product per channel.
// (I is the irradiance-like integral of the reference's eq. 4; a white Lambertian surface
// reflects I / pi.)
//
// Reference: Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed Visibility"
// (JGT 2009), sec. 3 (eq. 4, tables over normals), 3.2 (cube map, dual paraboloid), 3.3 (the
// row-scaling construction, the symmetries, blending between lighting environments).
//
// The row-scaling construction. With P_L the product matrix of the lighting
// (ops/sh_product.hpp, sh::product_matrix: P_L h = proj_K(L h) for h of C bands) and c(n) the SH
// vector of H_n, c_lm(n) = pi a_l y_lm(n) (Funk-Hecke, core/clamped_cosine.hpp),
//     (L x H)(n) = P_L c(n) = sum_j c_j(n) P_L[:, j]:
// the columns of P_L scaled by the clamped-cosine coefficients of the texel's normal and summed
// (the reference's "rows": it stores the transpose). Columns with a_l = 0 (odd l >= 3) are skipped.
//
// Truncation of H. H_n is not band-limited, but the Gaunt coefficient Gamma_ijk of y_i (L, l_i
// <= N-1), y_j (H) and y_k (result, l_k <= K-1) vanishes unless l_j <= l_i + l_k <= N + K - 2.
// So C = N + K - 1 bands of H give the K-band projection of L * H_n *exactly* (the default,
// cosine_bands = 0); fewer bands (the reference keeps 9 rows, C = 3) drop the H bands
// l = C .. N+K-2, an error e(n) = P_tail c_tail(n) with, per channel and every unit n,
//     |e(n)|_2 <= ||P_tail||_F * pi * sqrt(sum_{l=C}^{N+K-2} a_l^2 (2l+1)/(4 pi))
// (the addition theorem: sum_m y_lm(n)^2 = (2l+1)/(4 pi)); lxh_truncation_bound() returns it.
// Since a_l = 0 for odd l >= 3, C = 3 is exact when N + K - 2 < 4 (N + K <= 5), e.g. N = 3, K = 2;
// with N = K = 3 the dropped band is l = 4 (a_4 = -1/24).
//
// The symmetric construction (reference sec. 3.3: "negating a SH function in Z simply changes
// the sign of the basis functions where m is odd", 90 degree z rotations for the side faces of a
// cube map). In this library's real SH (no Condon-Shortley phase)
//     y_lm(x, y, -z) = (-1)^(l+m) y_lm(x, y, z)      (P_l^|m|(-t) = (-1)^(l+|m|) P_l^|m|(t)),
// and a rotation by k 90 degrees about z, phi -> phi + k pi/2, multiplies the complex pair
// z_lm = y_l,m + i y_l,-m (m > 0: y_l,m ~ cos(m phi), y_l,-m ~ sin(m phi)) by i^(mk). With
// Q_lm = P[:, (l,m)] + i P[:, (l,-m)], the table at the image n' = Z^f R^k n of a normal n is
//     T(n') = sum_p (-1)^(p f) [ A_p + Re sum_{r=0..3} i^(r k) G_rp ],
//     A_p  = sum_{l = p mod 2} c_l0 P[:, (l,0)],
//     G_rp = sum_{m > 0, m = r mod 4, l + m = p mod 2} conj(Q_lm) z_lm(n),
// a 4-point DFT over r, so the up to 8 texels of an orbit of {Z^f R^k} share one SH evaluation
// and one pass over the columns. Orbits are found from the texel directions (any
// parameterization: those of param/ are closed under both symmetries when their resolution is
// even; texels without partners are simply computed alone). Two texels belong to one orbit when
// their canonical images agree to the key quantum (2^-40 for double texel directions, 2^-21
// for float), so the symmetric table equals the plain one to rounding (double) or to the
// direction's float rounding (float); tested against it.
//
// Layout: table[(texel * K^2 + k) * 3 + channel], float; lookups go through param::lookup with
// channels() = 3 K^2. Blending between lighting environments: the table is linear in L, so
// blend_lxh_tables((1 - t) A + t B) equals the table of the blended lighting.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "../basis/sh.hpp"
#include "../core/clamped_cosine.hpp"
#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../param/param.hpp"
#include "sh_product.hpp"

namespace sphbasis {

/// Band limits of lxh tables: lighting and visibility 1..16 bands.
inline constexpr int max_lxh_bands = 16;

/// The product matrix of an RGB lighting for L x H tables: P_L (K^2 x C^2 per channel) stored by
/// columns, column j (an H coefficient) holding 3 K^2 doubles (coefficient k, then channel).
struct LxhMatrix {
    int lighting_bands = 0;       ///< N
    int visibility_bands = 0;     ///< K
    int cosine_bands = 0;         ///< C: H bands kept (N + K - 1 = exact)
    std::vector<double> columns;  ///< C^2 columns of 3 K^2: columns[(j * K^2 + k) * 3 + c]
    std::vector<double> cosine;   ///< pi a_l for l < C (the clamped cosine's zonal factors)
    std::size_t column_size() const noexcept {
        return 3 * static_cast<std::size_t>(visibility_bands) *
               static_cast<std::size_t>(visibility_bands);
    }
};

/// Counts of a table build (what the symmetric construction shared).
struct LxhBuildStats {
    std::size_t texels = 0;  ///< texels written
    std::size_t orbits = 0;  ///< SH evaluations (= texels for the plain construction)
};

/// An L x H table over a parameterization (header comment for the layout).
template <class Param>
struct LxhTable {
    Param param;
    int lighting_bands = 0, visibility_bands = 0, cosine_bands = 0;
    std::vector<float> data;  ///< texel_count() * channels()
    LxhBuildStats stats;

    std::size_t channels() const noexcept {
        return 3 * static_cast<std::size_t>(visibility_bands) *
               static_cast<std::size_t>(visibility_bands);
    }
    /// The bilinearly filtered K^2 RGB coefficients at direction (x, y, z) (any finite non-zero
    /// vector; param/param.hpp), into out[channels()].
    template <class T>
    void lookup(T x, T y, T z, float* out) const noexcept {
        param::lookup(param, data.data(), channels(), x, y, z, out);
    }
    /// I(n) = V . (L x H)(n) per channel for a visibility vector v of K^2 coefficients at normal
    /// (x, y, z), from the filtered table. Cost: one lookup and 3 K^2 multiply-adds.
    template <class V, class T>
    std::array<double, 3> shade(const V* v, T x, T y, T z) const {
        std::vector<float> t(channels());
        lookup(x, y, z, t.data());
        std::array<double, 3> out{0, 0, 0};
        const int kk = visibility_bands * visibility_bands;
        for (int k = 0; k < kk; ++k)
            for (int c = 0; c < 3; ++c)
                out[static_cast<std::size_t>(c)] +=
                    static_cast<double>(v[k]) * t[static_cast<std::size_t>(k * 3 + c)];
        return out;
    }
};

namespace detail {

inline void check_lxh_bands(const char* fn, int n, int k, int c) {
    check_range(fn, "lighting bands", n, 1, max_lxh_bands);
    check_range(fn, "visibility bands", k, 1, max_lxh_bands);
    check_range(fn, "cosine bands", c, 0, n + k - 1);
}

inline void check_lxh_lighting(const char* fn, int n, const double* rgb) {
    if (!rgb) throw_invalid(fn, "a lighting buffer of 3 N^2 doubles, got a null pointer");
    const std::size_t cnt = 3 * static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    for (std::size_t i = 0; i < cnt; ++i)
        if (!std::isfinite(rgb[i]))
            throw_invalid(fn, "finite lighting coefficients, got " + std::to_string(rgb[i]) +
                                  " at coefficient " + std::to_string(i / 3) + ", channel " +
                                  std::to_string(i % 3));
}

/// c(n) = pi a_l y_lm(n) for l < C, into c (C^2).
inline void lxh_cosine_vector(const LxhMatrix& m, double x, double y, double z, double* c) {
    sh::eval(m.cosine_bands, x, y, z, c);
    for (int l = 0; l < m.cosine_bands; ++l)
        for (int mm = -l; mm <= l; ++mm)
            c[sh::index(l, mm)] *= m.cosine[static_cast<std::size_t>(l)];
}

/// out (3 K^2) = P c, skipping the columns of vanishing a_l.
inline void lxh_apply(const LxhMatrix& m, const double* c, double* out) {
    const std::size_t e = m.column_size();
    std::fill(out, out + e, 0.0);
    for (int l = 0; l < m.cosine_bands; ++l) {
        if (m.cosine[static_cast<std::size_t>(l)] == 0) continue;
        for (int mm = -l; mm <= l; ++mm) {
            const int j = sh::index(l, mm);
            const double cj = c[j];
            const double* col = m.columns.data() + static_cast<std::size_t>(j) * e;
            for (std::size_t q = 0; q < e; ++q) out[q] += cj * col[q];
        }
    }
}

/// One orbit member: a texel and its symmetry relative to the orbit's representative:
/// texel direction = R^k Z^f (representative), R the +90 degree rotation about z.
struct LxhMember {
    std::size_t texel;
    int k, f;
};

/// Canonical image of a direction under {Z^f R^k}: z >= 0, (x, y) rotated into x > 0, y >= 0
/// (k = 0 at x = y = 0); returns (k, f) with d = R^k Z^f canonical.
inline void lxh_canonical(double& x, double& y, double& z, int& k, int& f) noexcept {
    f = z < 0 ? 1 : 0;
    if (f) z = -z;
    k = 0;
    // Rotate by -90 degrees, (x, y) -> (y, -x), until in the quadrant x > 0, y >= 0.
    while (!(x > 0 && y >= 0) && !(x == 0 && y == 0) && k < 4) {
        const double nx = y, ny = -x;
        x = nx;
        y = ny;
        ++k;
    }
    k &= 3;
}

}  // namespace detail

/// The product matrix of RGB lighting (lighting_bands N, 3 N^2 doubles interleaved: coefficient
/// i, channel c at rgb[3 i + c]) for visibility of K bands, with C = cosine_bands bands of H
/// (0: N + K - 1, exact). Cost: one pass over the Gaunt table (N, C, K), built and cached on first
/// use. Throws std::invalid_argument for bands outside 1..16, C outside 0..N+K-1, a null
/// pointer or a non-finite coefficient.
inline LxhMatrix lxh_matrix(int lighting_bands, const double* rgb, int visibility_bands,
                            int cosine_bands = 0) {
    const char* fn = "lxh_matrix";
    detail::check_lxh_bands(fn, lighting_bands, visibility_bands, cosine_bands);
    detail::check_lxh_lighting(fn, lighting_bands, rgb);
    LxhMatrix m;
    m.lighting_bands = lighting_bands;
    m.visibility_bands = visibility_bands;
    m.cosine_bands = cosine_bands > 0 ? cosine_bands : lighting_bands + visibility_bands - 1;
    const int nn = lighting_bands * lighting_bands;
    const int cc = m.cosine_bands * m.cosine_bands, kk = visibility_bands * visibility_bands;
    m.cosine.resize(static_cast<std::size_t>(m.cosine_bands));
    clamped_cosine_factors(m.cosine_bands, m.cosine.data());
    for (double& a : m.cosine) a *= constants::pi;
    m.columns.assign(static_cast<std::size_t>(cc) * m.column_size(), 0.0);
    const sh::TripleTable& t = sh::triple_table(lighting_bands, m.cosine_bands, visibility_bands);
    std::vector<double> ch(static_cast<std::size_t>(nn)), p(static_cast<std::size_t>(kk * cc));
    for (int c = 0; c < 3; ++c) {
        for (int i = 0; i < nn; ++i) ch[static_cast<std::size_t>(i)] = rgb[3 * i + c];
        sh::product_matrix(t, ch.data(), p.data());  // row k, column j
        for (int k = 0; k < kk; ++k)
            for (int j = 0; j < cc; ++j)
                m.columns[(static_cast<std::size_t>(j) * static_cast<std::size_t>(kk) +
                           static_cast<std::size_t>(k)) *
                              3 +
                          static_cast<std::size_t>(c)] = p[static_cast<std::size_t>(k * cc + j)];
    }
    return m;
}

/// (L x H)(n) at one unit normal, in double, by row scaling: out[3 k + c] for k < K^2.
inline void lxh_at(const LxhMatrix& m, double x, double y, double z, double* out) {
    std::vector<double> c(static_cast<std::size_t>(m.cosine_bands * m.cosine_bands));
    detail::lxh_cosine_vector(m, x, y, z, c.data());
    detail::lxh_apply(m, c.data(), out);
}

/// The reference's "direct per-texel product": (L x H)(n) by the sparse SH product of the
/// lighting with c(n), proj_K(L c(n)) per channel (sh::product with the Gaunt table (N, C, K)),
/// without the product matrix. Same result as lxh_at() up to rounding; the benchmark's baseline.
inline void lxh_direct(int lighting_bands, const double* rgb, int visibility_bands,
                       int cosine_bands, double x, double y, double z, double* out) {
    const char* fn = "lxh_direct";
    detail::check_lxh_bands(fn, lighting_bands, visibility_bands, cosine_bands);
    const int cb = cosine_bands > 0 ? cosine_bands : lighting_bands + visibility_bands - 1;
    const sh::TripleTable& t = sh::triple_table(lighting_bands, cb, visibility_bands);
    std::vector<double> a(static_cast<std::size_t>(cb));
    clamped_cosine_factors(cb, a.data());
    std::vector<double> c(static_cast<std::size_t>(cb * cb));
    sh::eval(cb, x, y, z, c.data());
    for (int l = 0; l < cb; ++l)
        for (int m = -l; m <= l; ++m)
            c[static_cast<std::size_t>(sh::index(l, m))] *=
                constants::pi * a[static_cast<std::size_t>(l)];
    const int nn = lighting_bands * lighting_bands, kk = visibility_bands * visibility_bands;
    std::vector<double> ch(static_cast<std::size_t>(nn)), r(static_cast<std::size_t>(kk));
    for (int ch_i = 0; ch_i < 3; ++ch_i) {
        for (int i = 0; i < nn; ++i) ch[static_cast<std::size_t>(i)] = rgb[3 * i + ch_i];
        sh::product(t, ch.data(), c.data(), r.data());
        for (int k = 0; k < kk; ++k) out[3 * k + ch_i] = r[static_cast<std::size_t>(k)];
    }
}

/// The bound of the header comment on the per-channel 2-norm of the error of (L x H)(n) with
/// C = cosine_bands bands of H against the exact projection, the largest over the channels
/// (0 when C >= N + K - 1). Throws as lxh_matrix().
inline double lxh_truncation_bound(int lighting_bands, const double* rgb, int visibility_bands,
                                   int cosine_bands) {
    const char* fn = "lxh_truncation_bound";
    detail::check_lxh_bands(fn, lighting_bands, visibility_bands, cosine_bands);
    const int full = lighting_bands + visibility_bands - 1;
    if (cosine_bands == 0 || cosine_bands >= full) return 0;
    const LxhMatrix m = lxh_matrix(lighting_bands, rgb, visibility_bands, full);
    double tail = 0;
    for (int l = cosine_bands; l < full; ++l) {
        const double a = m.cosine[static_cast<std::size_t>(l)];
        tail += a * a * (2 * l + 1) / (4 * constants::pi);
    }
    const std::size_t e = m.column_size();
    double worst = 0;
    for (int c = 0; c < 3; ++c) {
        double f = 0;
        for (int j = cosine_bands * cosine_bands; j < full * full; ++j)
            for (std::size_t q = static_cast<std::size_t>(c); q < e; q += 3) {
                const double v = m.columns[static_cast<std::size_t>(j) * e + q];
                f += v * v;
            }
        worst = std::max(worst, std::sqrt(f * tail));
    }
    return worst;
}

/// How build_lxh_table() constructs the table.
enum class LxhConstruction {
    plain,     ///< one SH evaluation and one pass over the columns per texel
    symmetric  ///< orbits under z negation and 90 degree z rotations share both (header comment)
};

/// The orbits of a parameterization's texels under z negation and 90 degree z rotations: what
/// the symmetric construction needs besides the lighting, so it is made once per
/// parameterization and reused for every lighting (make_lxh_orbits()).
struct LxhOrbits {
    std::size_t texels = 0;
    std::vector<std::size_t> begin;                ///< orbit o: members [begin[o], begin[o+1])
    std::vector<detail::LxhMember> members;        ///< relative to the orbit's first member
    std::vector<std::array<double, 3>> direction;  ///< the first member's unit direction
    std::size_t orbits() const noexcept { return direction.size(); }
};

namespace detail {
/// The unit direction (double) of texel `texel` (face-major, row-major index) of p.
template <class Param>
std::array<double, 3> lxh_texel_direction(const Param& p, std::size_t texel) {
    const std::size_t w = static_cast<std::size_t>(p.width());
    const std::size_t h = static_cast<std::size_t>(p.height());
    const auto d = p.texel_direction(static_cast<int>(texel / (w * h)), static_cast<int>(texel % w),
                                     static_cast<int>((texel / w) % h));
    const double x = static_cast<double>(d.x), y = static_cast<double>(d.y),
                 z = static_cast<double>(d.z);
    const double len = std::sqrt(x * x + y * y + z * z);
    return {x / len, y / len, z / len};
}

inline void check_lxh_matrix(const char* fn, const LxhMatrix& m) {
    check_lxh_bands(fn, m.lighting_bands, m.visibility_bands, m.cosine_bands);
    if (m.cosine_bands < 1 || m.cosine.size() != static_cast<std::size_t>(m.cosine_bands) ||
        m.columns.size() != static_cast<std::size_t>(m.cosine_bands) *
                                static_cast<std::size_t>(m.cosine_bands) * m.column_size())
        throw_invalid(fn, "an LxhMatrix made by lxh_matrix(), got an inconsistent one");
}

template <class Param>
void lxh_prepare(const char* fn, const Param& p, const LxhMatrix& m, LxhTable<Param>& tab) {
    check_lxh_matrix(fn, m);
    tab.param = p;
    tab.lighting_bands = m.lighting_bands;
    tab.visibility_bands = m.visibility_bands;
    tab.cosine_bands = m.cosine_bands;
    tab.stats = {};
    tab.stats.texels = p.texel_count();
    check_table_bytes(fn, 4.0 * double(p.texel_count()) * double(m.column_size()),
                      "an L x H table");
    tab.data.resize(p.texel_count() * m.column_size());  // every element is written
}

inline void lxh_write(float* dst, const double* v, std::size_t e) noexcept {
    for (std::size_t q = 0; q < e; ++q) dst[q] = static_cast<float>(v[q]);
}
}  // namespace detail

/// The orbits of p's texels (header comment: canonical images sorted, keys quantised to 2^-40,
/// or 2^-21 for a float parameterization). Cost O(T log T) for T texels, 64 bytes a texel.
template <class Param>
LxhOrbits make_lxh_orbits(const Param& p) {
    using DirT = decltype(p.texel_direction(0, 0, 0).x);
    const double quantum = std::ldexp(1.0, sizeof(DirT) >= sizeof(double) ? 40 : 21);
    struct Key {
        std::int64_t q[3];
        std::size_t texel;
        int k, f;
    };
    const std::size_t ntex = p.texel_count();
    std::vector<Key> keys(ntex);
    for (std::size_t t = 0; t < ntex; ++t) {
        auto d = detail::lxh_texel_direction(p, t);
        int k, f;
        detail::lxh_canonical(d[0], d[1], d[2], k, f);
        keys[t] = {{static_cast<std::int64_t>(std::llround(d[0] * quantum)),
                    static_cast<std::int64_t>(std::llround(d[1] * quantum)),
                    static_cast<std::int64_t>(std::llround(d[2] * quantum))},
                   t,
                   k,
                   f};
    }
    std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
        return std::tie(a.q[0], a.q[1], a.q[2], a.texel) <
               std::tie(b.q[0], b.q[1], b.q[2], b.texel);
    });
    LxhOrbits o;
    o.texels = ntex;
    o.members.reserve(ntex);
    std::size_t b = 0;
    while (b < ntex) {
        std::size_t end = b + 1;
        while (end < ntex && keys[end].q[0] == keys[b].q[0] && keys[end].q[1] == keys[b].q[1] &&
               keys[end].q[2] == keys[b].q[2])
            ++end;
        o.begin.push_back(o.members.size());
        o.direction.push_back(detail::lxh_texel_direction(p, keys[b].texel));
        // This texel = R^km Z^fm canonical, the first = R^k0 Z^f0 canonical.
        for (std::size_t i = b; i < end; ++i)
            o.members.push_back(
                {keys[i].texel, (keys[i].k - keys[b].k + 4) & 3, keys[i].f ^ keys[b].f});
        b = end;
    }
    o.begin.push_back(o.members.size());
    return o;
}

/// The L x H table of lighting matrix m over the texels of p by the symmetric construction with
/// p's orbits (make_lxh_orbits(p); throws std::invalid_argument if they have another texel
/// count). Writes into `out` reusing its storage (repeated builds for changing lighting
/// allocate nothing). Cost per orbit of up to 8 texels: one SH evaluation of C bands, 3 K^2
/// multiply-adds per nonzero m = 0 column and 4 (2 pairs) per nonzero m != 0 column pair, and
/// about 16 adds per texel and element for the DFT and the z sign.
template <class Param>
void build_lxh_table(const Param& p, const LxhMatrix& m, const LxhOrbits& orbits,
                     LxhTable<Param>& out) {
    const char* fn = "build_lxh_table";
    if (orbits.texels != p.texel_count() || orbits.begin.size() != orbits.orbits() + 1)
        detail::throw_invalid(fn, "the orbits of this parameterization (" +
                                      std::to_string(p.texel_count()) + " texels), got " +
                                      std::to_string(orbits.texels));
    detail::lxh_prepare(fn, p, m, out);
    const std::size_t e = m.column_size();
    std::vector<double> c(static_cast<std::size_t>(m.cosine_bands * m.cosine_bands)), res(e);
    std::vector<double> A(2 * e), G(2 * 4 * 2 * e);  // G[((p * 4 + r) * 2 + re/im) * e + q]
    std::vector<double> U(2 * 4 * e);                // U[(p * 4 + k) * e + q]
    auto gidx = [e](int p_, int r, int im) {
        return static_cast<std::size_t>((p_ * 4 + r) * 2 + im) * e;
    };
    out.stats.orbits = orbits.orbits();
    for (std::size_t o = 0; o < orbits.orbits(); ++o) {
        const auto& d = orbits.direction[o];
        detail::lxh_cosine_vector(m, d[0], d[1], d[2], c.data());
        const std::size_t b = orbits.begin[o], end = orbits.begin[o + 1];
        if (end - b == 1) {
            detail::lxh_apply(m, c.data(), res.data());
            detail::lxh_write(out.data.data() + orbits.members[b].texel * e, res.data(), e);
            continue;
        }
        // Columns grouped into A_p (m = 0) and G_rp (m > 0).
        std::fill(A.begin(), A.end(), 0.0);
        std::fill(G.begin(), G.end(), 0.0);
        for (int l = 0; l < m.cosine_bands; ++l) {
            if (m.cosine[static_cast<std::size_t>(l)] == 0) continue;
            {
                const double cj = c[static_cast<std::size_t>(sh::index(l, 0))];
                const double* col =
                    m.columns.data() + static_cast<std::size_t>(sh::index(l, 0)) * e;
                double* a = A.data() + static_cast<std::size_t>(l & 1) * e;
                for (std::size_t q = 0; q < e; ++q) a[q] += cj * col[q];
            }
            for (int mm = 1; mm <= l; ++mm) {
                const int par = (l + mm) & 1, r = mm & 3;
                const double cp = c[static_cast<std::size_t>(sh::index(l, mm))];
                const double cm = c[static_cast<std::size_t>(sh::index(l, -mm))];
                const double* pp =
                    m.columns.data() + static_cast<std::size_t>(sh::index(l, mm)) * e;
                const double* pm =
                    m.columns.data() + static_cast<std::size_t>(sh::index(l, -mm)) * e;
                double* gr = G.data() + gidx(par, r, 0);
                double* gi = G.data() + gidx(par, r, 1);
                // conj(Q) z = (P+ - i P-)(c+ + i c-): Re = P+ c+ + P- c-, Im = P+ c- - P- c+.
                for (std::size_t q = 0; q < e; ++q) {
                    gr[q] += pp[q] * cp + pm[q] * cm;
                    gi[q] += pp[q] * cm - pm[q] * cp;
                }
            }
        }
        // U_kp = A_p + Re sum_r i^(rk) G_rp by the 4-point DFT: E0 = G0 + G2, E1 = G0 - G2,
        // O0 = G1 + G3, O1 = G1 - G3; Re S0 = Re E0 + Re O0, Re S2 = Re E0 - Re O0,
        // Re S1 = Re E1 - Im O1, Re S3 = Re E1 + Im O1.
        for (int par = 0; par < 2; ++par) {
            const double* a = A.data() + static_cast<std::size_t>(par) * e;
            const double* g0 = G.data() + gidx(par, 0, 0);
            const double* g1 = G.data() + gidx(par, 1, 0);
            const double* g1i = G.data() + gidx(par, 1, 1);
            const double* g2 = G.data() + gidx(par, 2, 0);
            const double* g3 = G.data() + gidx(par, 3, 0);
            const double* g3i = G.data() + gidx(par, 3, 1);
            double* u0 = U.data() + static_cast<std::size_t>(par * 4 + 0) * e;
            double* u1 = U.data() + static_cast<std::size_t>(par * 4 + 1) * e;
            double* u2 = U.data() + static_cast<std::size_t>(par * 4 + 2) * e;
            double* u3 = U.data() + static_cast<std::size_t>(par * 4 + 3) * e;
            for (std::size_t q = 0; q < e; ++q) {
                const double e0 = a[q] + g0[q] + g2[q], e1 = a[q] + g0[q] - g2[q];
                const double o0 = g1[q] + g3[q], o1i = g1i[q] - g3i[q];
                u0[q] = e0 + o0;
                u2[q] = e0 - o0;
                u1[q] = e1 - o1i;
                u3[q] = e1 + o1i;
            }
        }
        // T(Z^f R^k n) = U_k0 + (-1)^f U_k1.
        for (std::size_t i = b; i < end; ++i) {
            const detail::LxhMember& mem = orbits.members[i];
            const double* ue = U.data() + static_cast<std::size_t>(mem.k) * e;
            const double* uo = U.data() + static_cast<std::size_t>(4 + mem.k) * e;
            float* dst = out.data.data() + mem.texel * e;
            if (mem.f)
                for (std::size_t q = 0; q < e; ++q) dst[q] = static_cast<float>(ue[q] - uo[q]);
            else
                for (std::size_t q = 0; q < e; ++q) dst[q] = static_cast<float>(ue[q] + uo[q]);
        }
    }
}

/// The L x H table of lighting matrix m over the texels of param p (any class of param/),
/// written into `out` reusing its storage. plain: per texel one SH evaluation of C bands and
/// 3 K^2 multiply-adds per nonzero column; symmetric: make_lxh_orbits(p) and then the build
/// above (keep the orbits and call that overload when building for many lightings).
/// Throws std::invalid_argument for an inconsistent m or an unknown construction.
template <class Param>
void build_lxh_table(const Param& p, const LxhMatrix& m, LxhConstruction how,
                     LxhTable<Param>& out) {
    const char* fn = "build_lxh_table";
    if (how != LxhConstruction::plain && how != LxhConstruction::symmetric)
        detail::throw_invalid(
            fn, "construction plain or symmetric, got " + std::to_string(static_cast<int>(how)));
    if (how == LxhConstruction::symmetric) {
        detail::check_lxh_matrix(fn, m);
        build_lxh_table(p, m, make_lxh_orbits(p), out);
        return;
    }
    detail::lxh_prepare(fn, p, m, out);
    const std::size_t e = m.column_size();
    std::vector<double> c(static_cast<std::size_t>(m.cosine_bands * m.cosine_bands)), res(e);
    for (std::size_t t = 0; t < out.stats.texels; ++t) {
        const auto d = detail::lxh_texel_direction(p, t);
        detail::lxh_cosine_vector(m, d[0], d[1], d[2], c.data());
        detail::lxh_apply(m, c.data(), res.data());
        detail::lxh_write(out.data.data() + t * e, res.data(), e);
    }
    out.stats.orbits = out.stats.texels;
}

/// build_lxh_table(p, m, how, out) into a new table.
template <class Param>
LxhTable<Param> build_lxh_table(const Param& p, const LxhMatrix& m,
                                LxhConstruction how = LxhConstruction::plain) {
    LxhTable<Param> tab{p, 0, 0, 0, {}, {}};
    build_lxh_table(p, m, how, tab);
    return tab;
}

/// build_lxh_table() from RGB lighting coefficients directly (lxh_matrix() then the table).
template <class Param>
LxhTable<Param> build_lxh_table(const Param& p, int lighting_bands, const double* rgb,
                                int visibility_bands, int cosine_bands = 0,
                                LxhConstruction how = LxhConstruction::plain) {
    return build_lxh_table(p, lxh_matrix(lighting_bands, rgb, visibility_bands, cosine_bands), how);
}

/// (1 - t) a + t b, element-wise: the table of the blended lighting (the tables are linear in
/// L). Throws std::invalid_argument unless a and b have the same bands and texel count, or for a
/// non-finite t.
template <class Param>
LxhTable<Param> blend_lxh_tables(const LxhTable<Param>& a, const LxhTable<Param>& b, double t) {
    const char* fn = "blend_lxh_tables";
    if (!std::isfinite(t)) detail::throw_invalid(fn, "a finite weight t, got " + std::to_string(t));
    if (a.lighting_bands != b.lighting_bands || a.visibility_bands != b.visibility_bands ||
        a.cosine_bands != b.cosine_bands || a.data.size() != b.data.size())
        detail::throw_invalid(fn, "two tables of the same bands and size, got " +
                                      std::to_string(a.data.size()) + " and " +
                                      std::to_string(b.data.size()) + " floats");
    LxhTable<Param> r = a;
    const float wa = static_cast<float>(1 - t), wb = static_cast<float>(t);
    for (std::size_t i = 0; i < r.data.size(); ++i) r.data[i] = wa * a.data[i] + wb * b.data[i];
    return r;
}

}  // namespace sphbasis
