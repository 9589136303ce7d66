// sphbasis shader twins of the renderer's shading (include/sphbasis/render/representations/),
// GLSL 4.50 (also GLSL ES 3.10). Hand-written (the code is plain; the only constants are the
// clamped-cosine factors and pi, each the correctly rounded float). No #version line: include it
// after sphbasis.glsl (it calls sphbasis_sh_eval3 and sphbasis_cube_to_square).
// The HLSL twin is sphbasis_render.hlsl (same functions, same operation order).
//
// Each function mirrors one step of a representation's shade() in the C++ renderer, which
// computes in double from float tables: the shader computes in float, and the harness
// (tests/shaders/twins_test.cpp) states the ulp bound of each against the C++.
// Layouts are those of the C++ (docs/shaders.md lists them):
//   L x H table  table[(texel * K^2 + k) * 3 + channel], texel = (face * n + row) * n + col
//   PCA tables   texel * (M + 1) * 3: the mean's table, then vector j's (lxh-pca)
//   CPCA         exit values per cluster (M + 1) x 3: mean . l, then basis_j . l (prt-cpca)
//   probes       probe (i, j, k) at i + nx (j + ny k), 27 floats a probe: channel c, coeff. k at 9c + k
#ifndef SPHBASIS_RENDER_GLSL
#define SPHBASIS_RENDER_GLSL

#ifndef SPHBASIS_MAX_VECTORS
/// The largest PCA / CPCA vector count the functions below take (the renderer's limit).
#define SPHBASIS_MAX_VECTORS 64
#endif

const float sphbasis_inv_pi = 0.318309873;  // 1/pi
const float sphbasis_pi = 3.14159274;  // pi

// ---------------------------------------------------------------------------------------------
// Cube-map lookup: param::CubeMap<float>(n) with its default DX10 seamless filter.

/// The point of face `face` at cube coordinates (sc, tc) in [-1, 1]^2 (not normalised), as
/// param::detail::cube_face_point.
vec3 sphbasis_cube_face_point(int face, float sc, float tc)
{
    if (face == 0) return vec3(1.0, -tc, -sc);
    if (face == 1) return vec3(-1.0, -tc, sc);
    if (face == 2) return vec3(sc, 1.0, tc);
    if (face == 3) return vec3(sc, -1.0, -tc);
    if (face == 4) return vec3(sc, -tc, 1.0);
    return vec3(-sc, -tc, -1.0);
}

/// The texel (face-major, row-major index) beyond an edge of `face` of an n x n cube map: (col,
/// row) = (i, j) with exactly one of them -1 or n, folded onto the neighbouring face, as the
/// seam table of param::CubeMap (build_seams).
int sphbasis_cube_seam_texel(int face, int i, int j, int n)
{
    float fn = float(n);
    float sc = 2.0 * (float(i) + 0.5) / fn - 1.0;
    float tc = 2.0 * (float(j) + 0.5) / fn - 1.0;
    vec3 p = sphbasis_cube_face_point(face, sc, tc);
    int major = face / 2;
    for (int a = 0; a < 3; ++a) {
        if (a == major || abs(p[a]) <= 1.0) continue;
        float over = abs(p[a]) - 1.0;
        p[a] = p[a] < 0.0 ? -1.0 : 1.0;
        p[major] = p[major] < 0.0 ? -(1.0 - over) : 1.0 - over;
    }
    int q;
    vec2 uv = sphbasis_cube_to_square(p, q);
    // cube_to_square's (u, v) = ((sc + 1)/2, (tc + 1)/2): the texel whose centre it is.
    int col = clamp(int(floor(uv.x * fn)), 0, n - 1);  // round(u n - 1/2)
    int row = clamp(int(floor(uv.y * fn)), 0, n - 1);
    return (q * n + row) * n + col;
}

/// The bilinear footprint of the unit direction d in an n x n cube map, as
/// param::CubeMap<float>(n).footprint (DX10 seamless: taps past an edge read the neighbouring
/// face; at a cube corner the missing fourth tap's weight is shared by the other three).
void sphbasis_cube_footprint(vec3 d, int n, out int index[4], out float weight[4])
{
    int face;
    vec2 uv = sphbasis_cube_to_square(d, face);
    float fn = float(n);
    float cx = clamp(uv.x, 0.0, 1.0) * fn - 0.5;
    float cy = clamp(uv.y, 0.0, 1.0) * fn - 0.5;
    float flx = floor(cx); float fly = floor(cy);
    float fx = cx - flx; float fy = cy - fly;
    int i0 = int(flx); int j0 = int(fly);
    weight[0] = (1.0 - fx) * (1.0 - fy);
    weight[1] = fx * (1.0 - fy);
    weight[2] = (1.0 - fx) * fy;
    weight[3] = fx * fy;
    int missing = -1;
    for (int k = 0; k < 4; ++k) {
        int i = i0 + k % 2; int j = j0 + k / 2;
        bool in_i = i >= 0 && i < n; bool in_j = j >= 0 && j < n;
        index[k] = 0;
        if (in_i && in_j) index[k] = (face * n + j) * n + i;
        else if (in_i || in_j) index[k] = sphbasis_cube_seam_texel(face, i, j, n);
        else missing = k;
    }
    if (missing >= 0) {
        float share = weight[missing] / 3.0;
        for (int k = 0; k < 4; ++k) weight[k] += share;
        weight[missing] = 0.0;
        index[missing] = index[3 - missing];
    }
}

// ---------------------------------------------------------------------------------------------
// lxh-unc3/4/6 (representations/lxh.hpp): Iwanicki and Sloan, "Normal Mapping with
// Low-Frequency Precomputed Visibility" (JGT 2009), sec. 3: V . (L x H)(n).

/// The exit radiance albedo * V . (L x H)(n) / pi of a texel's SH visibility vis (count = K^2
/// coefficients, K = 3, 4 or 6) and the bilinearly filtered L x H table t at the mapped normal
/// (t[k] = RGB coefficient k; the caller blends the 4 taps of sphbasis_cube_footprint as
/// sum_q weight[q] table[index[q]]), as Lxh::shade_unc.
vec3 sphbasis_lxh_shade(float vis[36], vec3 t[36], int count, vec3 albedo)
{
    vec3 e = vec3(0.0);
    for (int k = 0; k < count; ++k) e += vis[k] * t[k];
    return albedo * e * sphbasis_inv_pi;
}

// ---------------------------------------------------------------------------------------------
// PCA (lxh-pcaM) and CPCA (prt-cpca-C-M): Sloan, Hall, Hart and Snyder, "Clustered Principal
// Components for Precomputed Radiance Transfer" (SIGGRAPH 2003): e = e_0 + sum_j w_j e_j.

/// e0 + sum_{j < m} w[j] e[j]: lxh-pca's filtered tables (e0 the mean's, e[j] vector j's; then
/// times albedo / pi, Lxh::shade_pca) or a CPCA cluster's exit values (e0 = mean . l,
/// e[j] = basis_j . l; then times albedo, PrtCpca::shade).
vec3 sphbasis_pca_exit(vec3 e0, vec3 e[SPHBASIS_MAX_VECTORS], float w[SPHBASIS_MAX_VECTORS], int m)
{
    vec3 s = e0;
    for (int j = 0; j < m; ++j) s += w[j] * e[j];
    return s;
}

/// The cluster of a CPCA texel, read nearest (clusters cannot be filtered) and stored as a
/// float: clamped to [0, clusters - 1] and truncated, as PrtCpca::shade.
int sphbasis_cpca_cluster(float stored, int clusters)
{
    return int(clamp(stored, 0.0, float(clusters - 1)));
}

// ---------------------------------------------------------------------------------------------
// prt-normalmap-svd4/6 (representations/prt_normalmap.hpp, ops/normal_basis.hpp): Sloan,
// Lehtinen and Kautz, "Precomputed Radiance Transfer: Theory and Practice" (SIGGRAPH 2005
// course), normal mapping for PRT: e(n) = (a(n)^T V_M) (G l), a(n) = pi a_l y_lm(n).

/// The mapped normal nm in the texel's tangent frame (s, t, n), its z clamped to >= 0 and
/// normalised ((0, 0, 1) for a zero vector), as PrtNormalMap::shade_svd.
vec3 sphbasis_normal_basis_tangent(vec3 nm, vec3 s, vec3 t, vec3 n)
{
    vec3 u = vec3(dot(nm, s), dot(nm, t), max(dot(nm, n), 0.0));
    float l = sqrt(dot(u, u));
    return l > 0.0 ? u * (1.0 / l) : vec3(0.0, 0.0, 1.0);
}

/// The M <= 6 normal-basis weights p_k = sum_i pi a_l(i) y_i(u) V[i][k] at the tangent-space
/// unit normal u, V the 9 x M matrix of normal_basis() (3 bands, unclamped, cosine-weighted:
/// NormalBasis::v) stored by columns, v[9 k + i].
void sphbasis_normal_basis_weights(vec3 u, float v[54], int m, out float p[6])
{
    float y[9];
    sphbasis_sh_eval3(u, y);
    float a[9];
    for (int i = 0; i < 9; ++i)
        a[i] = (i == 0 ? sphbasis_pi : (i < 4 ? 2.09439516 : 0.785398185)) * y[i];  // pi a_l
    for (int k = 0; k < 6; ++k) {
        p[k] = 0.0;
        if (k < m)
            for (int i = 0; i < 9; ++i) p[k] += a[i] * v[9 * k + i];
    }
}

/// The exit radiance albedo * sum_k p_k (G_k l) / pi of prt-normalmap-svdM, gl[k] = G_k . l
/// per channel (the texel's M transfer rows applied to the lighting).
vec3 sphbasis_prt_normalmap_svd(float p[6], vec3 gl[6], int m, vec3 albedo)
{
    vec3 e = vec3(0.0);
    for (int k = 0; k < m; ++k) e += p[k] * gl[k];
    return albedo * e * sphbasis_inv_pi;
}

// ---------------------------------------------------------------------------------------------
// prt-ratio (representations/prt_normalmap.hpp) and the volume (representations/volume.hpp).

/// sum_k C[k] y_k(n) for 9 RGB coefficients C (the clamped-cosine factors a_l already folded
/// in: C = a_l L gives E/pi), as render's sh_shade without the albedo.
vec3 sphbasis_sh_shade(vec3 C[9], vec3 n)
{
    float y[9];
    sphbasis_sh_eval3(n, y);
    vec3 s = vec3(0.0);
    for (int k = 0; k < 9; ++k) s += C[k] * y[k];
    return s;
}

/// The ratio method: the unshadowed irradiance at the mapped normal nm times the ratio of the
/// shadowed (PRT transfer . lighting, per channel) to the unshadowed irradiance at the surface
/// normal ns, C = a_l L (9 RGB), as PrtNormalMap::shade_ratio (0 where the unshadowed value at
/// ns is <= 1e-12).
vec3 sphbasis_prt_ratio(vec3 shadowed, vec3 C[9], vec3 ns, vec3 nm, vec3 albedo)
{
    vec3 u0 = sphbasis_sh_shade(C, ns);
    vec3 um = albedo * sphbasis_sh_shade(C, nm);
    vec3 r = vec3(0.0);
    for (int c = 0; c < 3; ++c)
        r[c] = u0[c] > 1e-12 ? max(shadowed[c], 0.0) / u0[c] * um[c] : 0.0;
    return r;
}

/// The 8 probes of p's cell in a counts.x x counts.y x counts.z grid spanning [lo, hi] and their
/// trilinear weights, as render::ProbeGrid::weights: p clamped into the box, corner
/// c = dx + 2 dy + 4 dz, probe (i, j, k) at index i + nx (j + ny k); an axis with one probe
/// (or lo == hi) uses probe 0 with weight 1.
void sphbasis_probe_weights(vec3 p, vec3 lo, vec3 hi, ivec3 counts, out int index[8],
                            out float w[8])
{
    ivec3 base = ivec3(0);
    vec3 t = vec3(0.0);
    for (int a = 0; a < 3; ++a) {
        int n = counts[a];
        if (n < 2 || !(hi[a] > lo[a])) continue;
        float s = (clamp(p[a], lo[a], hi[a]) - lo[a]) / (hi[a] - lo[a]) * float(n - 1);
        int i = min(int(floor(s)), n - 2);
        base[a] = i;
        t[a] = clamp(s - float(i), 0.0, 1.0);
    }
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 ijk;
        float wc = 1.0;
        for (int a = 0; a < 3; ++a) {
            int dd = (corner >> a) & 1;
            ijk[a] = min(base[a] + dd, counts[a] - 1);
            wc *= dd != 0 ? t[a] : 1.0 - t[a];
        }
        index[corner] = ijk.x + counts.x * (ijk.y + counts.y * ijk.z);
        w[corner] = wc;
    }
}

/// Leaves out the corners whose probe lies inside geometry and renormalises the others, as
/// render::ProbeGrid::interpolate_valid. Returns false when no weight is left: the caller then
/// reads the nearest valid probe (ProbeGrid::nearest_valid, a search best done on the CPU).
bool sphbasis_probe_weights_valid(inout float w[8], bool inside[8])
{
    float total = 0.0;
    for (int k = 0; k < 8; ++k) {
        if (inside[k]) w[k] = 0.0;
        total += w[k];
    }
    if (!(total > 0.0)) return false;
    for (int k = 0; k < 8; ++k) w[k] /= total;
    return true;
}

/// The irradiance volume's shading (Greger, Shirley, Hubbard and Greenberg, "The Irradiance
/// Volume", IEEE CG&A 1998): the trilinearly interpolated radiance L (9 RGB SH coefficients,
/// 3 bands) convolved with the clamped cosine at the normal n, times the albedo: albedo *
/// sum_k a_l L_k y_k(n) (= albedo E/pi), as representations::Volume::shade.
vec3 sphbasis_volume_shade(vec3 L[9], vec3 n, vec3 albedo)
{
    vec3 C[9];
    for (int k = 0; k < 9; ++k)
        C[k] = (k == 0 ? 1.0 : (k < 4 ? 0.666666687 : 0.25)) * L[k];  // a_0, a_1 = 2/3, a_2 = 1/4
    return albedo * sphbasis_sh_shade(C, n);
}

#endif  // SPHBASIS_RENDER_GLSL
