// sphbasis CLI: `sphbasis project ENVMAP...` projects an environment map (RGB radiance) onto a
// basis and writes the coefficients as JSON, C++, GLSL, HLSL, or the layouts engines read
// (Unity's SphericalHarmonicsL2, three.js's SphericalHarmonics3, Filament cmgen's sh.txt).
// docs/project.md is the reference of the options, the formats and their conventions.
//
// Pipeline: read (OpenEXR, Radiance HDR, PNG/JPEG sRGB -> linear) -> refuse non-finite texels ->
// project (exact texel solid angles: sh::project_latlong for lat-long maps, exact for the
// piecewise-constant map; sh::project_cubemap for crosses and faces; other bases: least squares
// over the texels of their domain) -> --rotate -> --frame -> --window -> --irradiance -> format ->
// write all or none (support/output_file.hpp) or to standard output.
#include <CLI/CLI.hpp>
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <sphbasis/basis/registry.hpp>
#include <sphbasis/ops/sh_convolution.hpp>
#include <sphbasis/ops/sh_latlong.hpp>
#include <sphbasis/ops/sh_lights.hpp>
#include <sphbasis/ops/sh_rotation.hpp>
#include <sphbasis/ops/sh_windowing.hpp>
#include <sphbasis/param/cube_cross.hpp>
#include <sphbasis/param/cubemap.hpp>
#include <string>
#include <vector>

#include "../support/envmap.hpp"
#include "../support/json.hpp"
#include "../support/output_file.hpp"
#include "../support/progress.hpp"
#include "../support/stdout_check.hpp"
#include "cli.hpp"

namespace sphbasis::cli {

namespace {

/// An RGB texel / coefficient: the coefficient type of the projectors (C + C, C * double).
struct Rgb {
    double r = 0, g = 0, b = 0;
    Rgb operator+(const Rgb& o) const { return {r + o.r, g + o.g, b + o.b}; }
    Rgb operator*(double s) const { return {r * s, g * s, b * s}; }
};

struct ProjectOptions {
    std::vector<std::string> inputs;
    std::string layout = "equirect", basis = "sh", window = "none", rotate, format = "json", out;
    std::string frame;  // empty: the engine's frame for an engine format, else sphbasis
    long long bands = 0, coeffs = 0;
    bool irradiance = false;
    CLI::Option *bands_opt = nullptr, *coeffs_opt = nullptr, *basis_opt = nullptr,
                *frame_opt = nullptr;
    std::string command_line;
};

/// The map as the projectors see it: a lat-long image or six n x n faces.
struct EnvMap {
    bool cube = false;
    int width = 0, height = 0;  // lat-long size, or n x n for a cube
    // Lat-long: one image. Cube: the cross image (one) or six face images.
    std::vector<LinearRgbImage> images;
    param::CrossLayout cross = param::CrossLayout::horizontal;
    bool is_cross = false;
    long long negative = 0;  // texels with a negative channel (kept as they are)

    Rgb texel_latlong(int col, int row) const {
        const float* p =
            images[0].rgb.data() + 3 * (std::size_t(row) * std::size_t(width) + std::size_t(col));
        return {p[0], p[1], p[2]};
    }
    Rgb texel_cube(int face, int col, int row) const {
        const LinearRgbImage* img = &images[0];
        int x = col, y = row;
        if (is_cross)
            param::cross_pixel(cross, width, face, col, row, x, y);
        else
            img = &images[static_cast<std::size_t>(face)];
        const float* p =
            img->rgb.data() + 3 * (std::size_t(y) * std::size_t(img->width) + std::size_t(x));
        return {p[0], p[1], p[2]};
    }
};

const char* const face_names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

/// An engine's world frame as a signed permutation: world axis i = sign[i] * map axis axis[i],
/// one for lat-long maps and one for cube maps (crosses, faces), each read off the engine's
/// own code that samples such an image (docs/project.md, "Frames"), so that the coefficients
/// light the engine's world as its background shows the same image.
struct EngineFrame {
    const char* name;
    const char* words;
    int axis_equirect[3], sign_equirect[3], axis_cube[3], sign_cube[3];

    /// The row-major matrix M with world = M map for the layout (det +-1).
    Mat3<double> matrix(bool cube) const {
        Mat3<double> m{};
        for (int i = 0; i < 3; ++i)
            m[std::size_t(3 * i + (cube ? axis_cube : axis_equirect)[i])] =
                (cube ? sign_cube : sign_equirect)[i];
        return m;
    }
};

const EngineFrame frames[] = {
    {"sphbasis",
     "the map's own frame (lat-long: +z up; cube: the faces' axes)",
     {0, 1, 2},
     {1, 1, 1},
     {0, 1, 2},
     {1, 1, 1}},
    // equirectUv(): u = atan(z, x)/2pi + 1/2, v = asin(y)/pi + 1/2; cube: flipEnvMap (x -> -x).
    {"threejs", "three.js (y up, right-handed)", {0, 2, 1}, {-1, 1, -1}, {0, 1, 2}, {-1, 1, 1}},
    // cmgen equirectangularToCubemap(): u = atan2(x, z)/2pi + 1/2, then mirrorCubemap (x -> -x).
    {"filament", "Filament (y up, right-handed)", {1, 2, 0}, {1, 1, -1}, {0, 1, 2}, {-1, 1, 1}},
    // Skybox-Panoramic ToRadialCoords(): u = 1/2 - atan2(z, x)/2pi, v = 1 - acos(y)/pi; cubes
    // are sampled with the world direction (the D3D faces, left-handed).
    {"unity", "Unity (y up, left-handed)", {0, 2, 1}, {-1, 1, 1}, {0, 1, 2}, {1, 1, 1}},
};

/// c <- D(M) c for a signed permutation M. When M keeps the z axis (every cube frame) it is
/// Rz(k quarter turns) diag(sx, 1, sz), applied exactly by sh::reflect and sh::rotate_z90 (each
/// coefficient kept, moved or negated); otherwise (the lat-long frames take +z to +y) by
/// sh::rotate, whose bands 0 and 1 come out exact and bands >= 2 within an ulp of D c (their
/// weights, such as -1/2 and sqrt(3)/2, are not representable).
void apply_frame(int bands, const Mat3<double>& m, double* c) {
    if (std::fabs(m[8]) == 1) {
        const double cs[4] = {1, 0, -1, 0}, sn[4] = {0, 1, 0, -1};
        for (int k = 0; k < 4; ++k)
            for (int fx = 0; fx < 2; ++fx) {
                const double sx = fx ? -1 : 1;
                if (m[0] != cs[k] * sx || m[1] != -sn[k] || m[3] != sn[k] * sx || m[4] != cs[k])
                    continue;
                if (fx) sh::reflect(bands, 0, c, c);
                if (m[8] < 0) sh::reflect(bands, 2, c, c);
                sh::rotate_z90(bands, k, c, c);
                return;
            }
    }
    sh::rotate(bands, m, c, c);
}

const EngineFrame& find_frame(const std::string& name) {
    for (const EngineFrame& f : frames)
        if (name == f.name) return f;
    throw UsageError("--frame: expected sphbasis, threejs, filament or unity, got '" +
                     quote_input(name) + "'");
}

EnvMap read_map(const ProjectOptions& o) {
    EnvMap m;
    const std::size_t want = o.layout == "faces" ? 6 : 1;
    if (o.inputs.size() != want)
        throw UsageError("--layout " + o.layout + ": expected " +
                         (want == 6 ? std::string("six face files in the order +X -X +Y -Y +Z -Z")
                                    : std::string("one ENVMAP file")) +
                         ", got " + std::to_string(o.inputs.size()));
    for (const std::string& path : o.inputs) {
        m.images.push_back(load_linear_rgb(path));
        const LinearRgbImage& img = m.images.back();
        const std::string bad = first_non_finite(img);
        if (!bad.empty())
            throw std::runtime_error("'" + path + "': " + bad +
                                     "; expected finite radiance in every texel");
        for (std::size_t i = 0; i < img.rgb.size(); i += 3)
            if (img.rgb[i] < 0 || img.rgb[i + 1] < 0 || img.rgb[i + 2] < 0) ++m.negative;
    }
    const LinearRgbImage& first = m.images[0];
    if (o.layout == "equirect") {
        m.width = first.width;
        m.height = first.height;
    } else if (o.layout == "cross") {
        m.cube = m.is_cross = true;
        int n = 0;
        try {
            m.cross = param::cross_layout_of(first.width, first.height, n);
        } catch (const std::invalid_argument&) {
            throw std::runtime_error(
                "'" + o.inputs[0] +
                "': --layout cross expects 4:3 (4n x 3n) or 3:4 (3n x 4n) pixels, got " +
                std::to_string(first.width) + " x " + std::to_string(first.height));
        }
        m.width = m.height = n;
    } else {
        m.cube = true;
        for (std::size_t f = 0; f < 6; ++f) {
            const LinearRgbImage& img = m.images[f];
            if (img.width != img.height || img.width != first.width)
                throw std::runtime_error(
                    "--layout faces expects six square faces of one size; face " +
                    std::string(face_names[f]) + " '" + o.inputs[f] + "' is " +
                    std::to_string(img.width) + " x " + std::to_string(img.height) + ", face +X " +
                    std::to_string(first.width) + " x " + std::to_string(first.height));
        }
        m.width = m.height = first.width;
    }
    return m;
}

/// SH projection, RGB, exact texel solid angles; a progress bar by rows.
std::vector<Rgb> project_sh(const EnvMap& m, int bands) {
    std::vector<Rgb> c(static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands));
    if (!m.cube) {
        Progress bar("project", m.height);
        sh::project_latlong_fn(
            bands, m.width, m.height,
            [&](int col, int row) {
                if (col == 0) bar.update();
                return m.texel_latlong(col, row);
            },
            c.data());
        bar.done();
    } else {
        Progress bar("project", 6LL * m.width);
        sh::project_cubemap_fn(
            bands, m.width,
            [&](int face, int col, int row) {
                if (col == 0) bar.update();
                return m.texel_cube(face, col, row);
            },
            c.data());
        bar.done();
    }
    return c;
}

/// Any basis: least squares over the texels in the basis's domain (the sphere, or z > 0 for the
/// hemispherical bases, by texel centre), weighted by the exact texel solid angles: the normal
/// equations G c = b with G = sum w B B^T, b = sum w L B, solved by LDLT.
std::vector<Rgb> project_fit(const EnvMap& m, const BasisInfo& basis, int count) {
    const Eigen::Index n = count;
    Eigen::MatrixXd g = Eigen::MatrixXd::Zero(n, n), b = Eigen::MatrixXd::Zero(n, 3);
    Eigen::VectorXd y(n);
    const bool hemi = basis.domain == Domain::hemisphere;
    auto add = [&](const vec3<double>& d, double w, const Rgb& v) {
        if (hemi && !(d.z > 0)) return;
        basis.eval_d(count, d.x, d.y, d.z, y.data());
        g.selfadjointView<Eigen::Lower>().rankUpdate(y, w);
        b.col(0) += (w * v.r) * y;
        b.col(1) += (w * v.g) * y;
        b.col(2) += (w * v.b) * y;
    };
    if (!m.cube) {
        Progress bar("project", m.height);
        for (int r = 0; r < m.height; ++r) {
            const double w = param::latlong_texel_solid_angle(m.width, m.height, r);
            const double th = constants::pi * (r + 0.5) / m.height;
            for (int c = 0; c < m.width; ++c) {
                const double ph = constants::two_pi * (c + 0.5) / m.width;
                add({std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)}, w,
                    m.texel_latlong(c, r));
            }
            bar.update();
        }
        bar.done();
    } else {
        Progress bar("project", 6LL * m.width);
        const int s = m.width;
        for (int f = 0; f < 6; ++f)
            for (int r = 0; r < s; ++r) {
                for (int c = 0; c < s; ++c)
                    add(param::square_to_cube(f, (c + 0.5) / s, (r + 0.5) / s),
                        param::cube_texel_solid_angle(s, c, r), m.texel_cube(f, c, r));
                bar.update();
            }
        bar.done();
    }
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(g.selfadjointView<Eigen::Lower>());
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0))
        throw std::runtime_error("the map has too few texels in the domain of basis '" +
                                 std::string(basis.name) + "' to fit " + std::to_string(count) +
                                 " functions; use a larger map or fewer --coeffs");
    const Eigen::MatrixXd x = ldlt.solve(b);
    std::vector<Rgb> out(static_cast<std::size_t>(count));
    for (Eigen::Index k = 0; k < n; ++k)
        out[static_cast<std::size_t>(k)] = {x(k, 0), x(k, 1), x(k, 2)};
    return out;
}

std::string fixed(double v, const char* fmt) {
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

/// The float literal of v for C++/GLSL/HLSL: 9 significant digits (round-trips a float).
std::string float_literal(double v, bool suffix) {
    std::string s = fixed(v, "%.9g");
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
    return suffix ? s + "f" : s;
}

/// (l, m) of ACN index k.
std::pair<int, int> lm_of(int k) {
    const int l = static_cast<int>(std::sqrt(static_cast<double>(k)));
    return {l, k - l * (l + 1)};
}

/// The constant factor K_k of y_k (l <= 2) as a polynomial in x, y, z, in the order of
/// the engines: 1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2 (no Condon-Shortley phase).
double engine_constant(int k) {
    const double sp = std::sqrt(constants::pi);
    switch (k) {
        case 0:
            return 0.5 / sp;  // 1/(2 sqrt(pi))
        case 1:
        case 2:
        case 3:
            return std::sqrt(3.0) / (2 * sp);
        case 6:
            return std::sqrt(5.0) / (4 * sp);
        case 8:
            return std::sqrt(15.0) / (4 * sp);
        default:
            return std::sqrt(15.0) / (2 * sp);  // 4, 5, 7
    }
}

int run_project(ProjectOptions& o) {
    // Options first, all before any file is read.
    if (o.layout != "equirect" && o.layout != "cross" && o.layout != "faces")
        throw UsageError("--layout: expected equirect, cross or faces, got '" +
                         quote_input(o.layout) + "'");
    static const char* const formats[] = {"json",  "cpp",     "glsl",    "hlsl",
                                          "unity", "threejs", "filament"};
    if (std::find_if(std::begin(formats), std::end(formats),
                     [&](const char* f) { return o.format == f; }) == std::end(formats))
        throw UsageError(
            "--format: expected json, cpp, glsl, hlsl, unity, threejs or filament, got '" +
            quote_input(o.format) + "'");
    const BasisInfo* basis = nullptr;
    try {
        basis = &find_basis(o.basis);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--basis: ") + e.what());
    }
    const bool is_sh = std::string(basis->name) == "sh";
    if (o.bands_opt->count() && o.coeffs_opt->count())
        throw UsageError("give --bands N or --coeffs N, not both");
    if (o.bands_opt->count() && !is_sh)
        throw UsageError("--bands: basis '" + std::string(basis->name) +
                         "' is sized by --coeffs N (" + basis->count_rule() + ")");
    int count = 9, bands = 3;
    if (o.coeffs_opt->count()) {
        if (o.coeffs < 1 || o.coeffs > 100000 || !basis->valid_count(static_cast<int>(o.coeffs)))
            throw UsageError(std::string("--coeffs: basis '") + basis->name + "' expects " +
                             basis->count_rule() + " functions, got " + std::to_string(o.coeffs));
        count = static_cast<int>(o.coeffs);
        bands = is_sh ? static_cast<int>(std::lround(std::sqrt(double(count)))) : 0;
    } else if (o.bands_opt->count()) {
        bands = static_cast<int>(o.bands);
        count = bands * bands;
    } else if (!is_sh) {
        throw UsageError("--basis " + std::string(basis->name) + ": give --coeffs N (" +
                         basis->count_rule() + ")");
    }
    if (!is_sh && (o.irradiance || o.window != "none" || !o.rotate.empty()))
        throw UsageError("--irradiance, --window and --rotate work on SH (--basis sh); basis '" +
                         std::string(basis->name) + "' takes none of them");
    const bool engine = o.format == "unity" || o.format == "threejs" || o.format == "filament";
    if (engine && !(is_sh && bands == 3))
        throw UsageError("--format " + o.format +
                         ": the engine holds 3 bands of SH (--bands 3), got " +
                         (is_sh ? std::to_string(bands) + " bands" : "basis " + o.basis));
    if (o.format == "threejs" && o.irradiance)
        throw UsageError(
            "--format threejs: SphericalHarmonics3 holds radiance (three.js applies the cosine "
            "in getIrradianceAt); drop --irradiance");
    // An engine format defaults to its engine's frame; every other format to the map's own.
    const EngineFrame& frame =
        find_frame(!o.frame.empty() ? o.frame : (engine ? o.format : std::string("sphbasis")));
    if (!is_sh && std::string(frame.name) != "sphbasis")
        throw UsageError("--frame " + o.frame + ": frames work on SH (--basis sh); basis '" +
                         std::string(basis->name) + "' stays in the map's frame");
    // Unity's and Filament's layouts hold the convolved light (irradiance / pi, pre-scaled).
    const bool convolve = o.irradiance || o.format == "unity" || o.format == "filament";

    std::vector<double> quat;
    if (!o.rotate.empty()) {
        quat = to_reals(o.rotate, "--rotate");
        if (quat.size() != 4)
            throw UsageError("--rotate: expected four numbers W,X,Y,Z, got " +
                             std::to_string(quat.size()));
        const double big = std::max(
            {std::fabs(quat[0]), std::fabs(quat[1]), std::fabs(quat[2]), std::fabs(quat[3])});
        if (!(big > 0)) throw UsageError("--rotate: expected a non-zero quaternion");
        for (double& q : quat) q /= big;
    }
    enum class Window { none, automatic, sloan } window = Window::none;
    double lambda = 0;
    if (o.window == "auto") {
        window = Window::automatic;
    } else if (o.window.rfind("sloan:", 0) == 0) {
        window = Window::sloan;
        lambda = to_real(o.window.substr(6), "--window sloan:X");
        if (!(lambda >= 0))
            throw UsageError("--window sloan:X: expected X >= 0, got " + o.window.substr(6));
    } else if (o.window != "none") {
        throw UsageError("--window: expected none, auto or sloan:X, got '" + quote_input(o.window) +
                         "'");
    }
    OutputFiles files;
    if (!o.out.empty()) {
        files.declare(o.out);
        files.prepare();
    }

    // Read and project.
    const Clock::time_point t0 = Clock::now();
    const EnvMap map = read_map(o);
    const double read_s = seconds_since(t0);
    const Clock::time_point t1 = Clock::now();
    std::vector<Rgb> c = is_sh ? project_sh(map, bands) : project_fit(map, *basis, count);
    const double project_s = seconds_since(t1);

    // Rotate, window, convolve: per channel in double.
    const std::size_t n2 = c.size();
    std::vector<double> ch(3 * n2);
    for (std::size_t k = 0; k < n2; ++k) {
        ch[k] = c[k].r;
        ch[n2 + k] = c[k].g;
        ch[2 * n2 + k] = c[k].b;
    }
    if (!quat.empty())
        for (int j = 0; j < 3; ++j)
            sh::rotate_quaternion(bands, quat[0], quat[1], quat[2], quat[3],
                                  ch.data() + std::size_t(j) * n2, ch.data() + std::size_t(j) * n2);
    // The engine's world: g(w) = f(M^T w) for the signed permutation M (det -1 included).
    const bool framed = std::string(frame.name) != "sphbasis";
    if (framed)
        for (int j = 0; j < 3; ++j)
            apply_frame(bands, frame.matrix(map.cube), ch.data() + std::size_t(j) * n2);
    const std::vector<double> kernel =
        is_sh ? sh::clamped_cosine_kernel(bands) : std::vector<double>{};
    Json window_json = {
        {"kind", o.window == "auto" ? "auto" : (window == Window::sloan ? "sloan" : "none")}};
    if (window != Window::none) {
        std::vector<double> w;
        if (window == Window::automatic) {
            const sh::RingingWindow<double> r =
                sh::ringing_window(bands, ch.data(), 3, convolve ? kernel.data() : nullptr, 0.0);
            w = r.window;
            lambda = r.lambda;
            window_json["certified_lower_bound"] = r.lower_bound;
            window_json["achieved"] = r.achieved;
            window_json["relative_l2_change"] = r.cost.relative_l2_change;
            window_json["of"] = convolve ? "irradiance" : "radiance";
        } else {
            w = sh::sloan_window(bands, lambda);
        }
        window_json["lambda"] = std::isinf(lambda) ? Json("inf") : Json(lambda);
        window_json["weights"] = w;
        for (int j = 0; j < 3; ++j)
            sh::apply_window(bands, w.data(), ch.data() + std::size_t(j) * n2,
                             ch.data() + std::size_t(j) * n2);
    }
    if (convolve)
        for (int j = 0; j < 3; ++j)
            sh::convolve(bands, kernel.data(), ch.data() + std::size_t(j) * n2,
                         ch.data() + std::size_t(j) * n2);
    auto at = [&](std::size_t k, int j) { return ch[static_cast<std::size_t>(j) * n2 + k]; };

    // Format.
    std::string text;
    const std::string quantity =
        o.format == "unity" || o.format == "filament"
            ? "irradiance / pi, pre-scaled by the basis constants"
            : (convolve ? "irradiance E(n) = integral of L(w) max(0, n.w) dw (not divided by pi)"
                        : "radiance L(w)");
    const std::string order =
        is_sh ? "ACN k = l(l+1)+m, real SH without the Condon-Shortley phase (y_1-1 ~ +y, "
                "y_10 ~ +z, y_11 ~ +x), orthonormal over the sphere"
              : std::string("the functions of basis '") + basis->name + "' in its own order";
    if (o.format == "json") {
        Json j;
        j["command"] = o.command_line;
        j["inputs"] = o.inputs;
        j["layout"] = o.layout;
        if (map.is_cross)
            j["cross"] = map.cross == param::CrossLayout::horizontal ? "horizontal" : "vertical";
        j["size"] = {map.cube ? 6 * map.width : map.width, map.height};
        j["basis"] = basis->name;
        if (is_sh) j["bands"] = bands;
        j["coeffs_per_channel"] = static_cast<int>(n2);
        j["quantity"] = quantity;
        j["order"] = order;
        j["rotate"] = quat.empty() ? Json(nullptr) : Json(quat);
        if (framed) j["frame"] = frame.name;
        j["window"] = window_json;
        j["negative_texels"] = map.negative;
        j["seconds"] = {{"read", read_s}, {"project", project_s}};
        j["channels"] = {"r", "g", "b"};
        Json cs = Json::array();
        for (std::size_t k = 0; k < n2; ++k) cs.push_back({at(k, 0), at(k, 1), at(k, 2)});
        j["coeffs"] = cs;
        text = dump_json(j, {{"coeffs", 2}}) + "\n";
    } else if (o.format == "cpp" || o.format == "glsl" || o.format == "hlsl") {
        const bool cpp = o.format == "cpp";
        const std::string cm = "// ";
        text = cm + "generated by: " + o.command_line + "\n" + cm + quantity + "\n" + cm + order +
               "\n" + (framed ? cm + "frame: " + frame.words + "\n" : std::string()) + cm +
               "coefficient k of channel c: sphbasis_coeffs[k]" + (cpp ? "[c]" : ".rgb[c]") +
               "; RGB linear\n";
        const std::string nn = std::to_string(n2);
        if (cpp)
            text += "const float sphbasis_coeffs[" + nn + "][3] = {\n";
        else if (o.format == "glsl")
            text += "const vec3 sphbasis_coeffs[" + nn + "] = vec3[" + nn + "](\n";
        else
            text += "static const float3 sphbasis_coeffs[" + nn + "] = {\n";
        for (std::size_t k = 0; k < n2; ++k) {
            const std::string v = float_literal(at(k, 0), cpp) + ", " +
                                  float_literal(at(k, 1), cpp) + ", " +
                                  float_literal(at(k, 2), cpp);
            const std::string open = cpp ? "{" : (o.format == "glsl" ? "vec3(" : "float3(");
            const std::string close = cpp ? "}" : ")";
            std::string line = "    " + open + v + close + (k + 1 < n2 ? "," : "");
            if (is_sh) {
                const auto [l, m] = lm_of(static_cast<int>(k));
                line += "  // l = " + std::to_string(l) + ", m = " + std::to_string(m);
            }
            text += line + "\n";
        }
        text += o.format == "glsl" ? ");\n" : "};\n";
    } else if (o.format == "threejs") {
        // SphericalHarmonics3.fromArray: coefficient-major, RGB inside (27 numbers).
        Json sh = Json::array();
        for (std::size_t k = 0; k < 9; ++k)
            for (int j = 0; j < 3; ++j) sh.push_back(at(k, j));
        Json doc = {{"generator", o.command_line},
                    {"convention",
                     "three.js SphericalHarmonics3 (radiance coefficients, ACN order, no "
                     "Condon-Shortley phase): new SphericalHarmonics3().fromArray(sh)"},
                    {"frame", frame.words},
                    {"sh", sh}};
        text = dump_json(doc, {{"sh", 2}}) + "\n";
    } else if (o.format == "unity") {
        text = "// generated by: " + o.command_line +
               "\n// UnityEngine.Rendering.SphericalHarmonicsL2, sh[channel, k]: irradiance / pi "
               "pre-scaled by the basis constants (k: 1, y, z, x, xy, yz, 3z^2-1, xz, x^2-y^2)\n"
               "// frame: " +
               frame.words +
               "\n"
               "var sh = new UnityEngine.Rendering.SphericalHarmonicsL2();\n";
        for (int j = 0; j < 3; ++j)
            for (std::size_t k = 0; k < 9; ++k)
                text += "sh[" + std::to_string(j) + ", " + std::to_string(k) + "] = " +
                        float_literal(
                            at(k, j) * engine_constant(static_cast<int>(k)) / constants::pi, true) +
                        ";\n";
    } else {  // filament: cmgen's sh.txt (--sh-shader / --deploy), one line per coefficient
        for (std::size_t k = 0; k < 9; ++k) {
            const double s = engine_constant(static_cast<int>(k)) / constants::pi;
            const auto [l, m] = lm_of(static_cast<int>(k));
            text += "(" + fixed(at(k, 0) * s, "%18.15f") + ", " + fixed(at(k, 1) * s, "%18.15f") +
                    ", " + fixed(at(k, 2) * s, "%18.15f") + "); // L" + std::to_string(l) +
                    std::to_string(m) + ", irradiance, pre-scaled base\n";
        }
    }

    if (o.out.empty()) {
        std::cout << text;
        check_stdout();
    } else {
        files.add(o.out, text);
        files.commit();
    }
    return 0;
}

}  // namespace

Run setup_project(CLI::App& app) {
    auto o = std::make_shared<ProjectOptions>();
    app.add_option("ENVMAP", o->inputs,
                   "the map: one file (equirect, cross) or six (faces: +X -X +Y -Y +Z -Z); EXR, "
                   "HDR, PNG, JPEG")
        ->required();
    app.add_option("--layout", o->layout, "equirect (lat-long), cross (4:3 or 3:4) or faces")
        ->type_name("equirect|cross|faces")
        ->capture_default_str();
    o->bands_opt = add_integer(app, "--bands", o->bands, 1, 64, "SH bands N (N^2 coefficients)");
    o->bands_opt->default_str("3");
    o->basis_opt =
        app.add_option("--basis", o->basis, "the basis: sh, hsh, makhotkin, zernike, hbasis, ...")
            ->type_name("NAME")
            ->capture_default_str();
    o->coeffs_opt = add_integer(app, "--coeffs", o->coeffs, std::numeric_limits<long long>::min(),
                                std::numeric_limits<long long>::max(),
                                "the number of functions of --basis (a size the basis has)");
    o->coeffs_opt->default_str("");
    app.add_flag("--irradiance", o->irradiance,
                 "convolve with the clamped cosine: E(n), not divided by pi");
    app.add_option("--window", o->window,
                   "none, auto (the certified non-negative window) or sloan:X (lambda = X)")
        ->type_name("none|auto|sloan:X")
        ->capture_default_str();
    app.add_option("--rotate", o->rotate,
                   "rotate the coefficients by a quaternion (as `rotate --quat`)")
        ->type_name("W,X,Y,Z");
    o->frame_opt = app.add_option("--frame", o->frame,
                                  "the world the coefficients are for: sphbasis (the map's "
                                  "frame), threejs, filament or unity (default: the --format's "
                                  "engine, else sphbasis)")
                       ->type_name("sphbasis|threejs|filament|unity");
    app.add_option("--format", o->format, "json, cpp, glsl, hlsl, unity, threejs or filament")
        ->type_name("FORMAT")
        ->capture_default_str();
    add_path(app, "--out", o->out, "write to PATH (all or none) instead of standard output");
    app.footer(
        "Project an environment map onto a basis (docs/project.md). Texels are weighted by their\n"
        "exact solid angles; non-finite texels are refused. Lat-long: row 0 at +z, phi =\n"
        "atan2(y, x) from the left edge. Faces and crosses: the D3D/GL cube faces.");
    return [o] {
        // The command as given, for the header of the outputs (the option values, not argv).
        std::string& c = o->command_line;
        c = "sphbasis project";
        for (const auto& in : o->inputs) c += " " + in;
        c += " --layout " + o->layout;
        if (o->basis != "sh" || o->coeffs_opt->count()) c += " --basis " + o->basis;
        if (o->coeffs_opt->count()) c += " --coeffs " + std::to_string(o->coeffs);
        if (o->bands_opt->count()) c += " --bands " + std::to_string(o->bands);
        if (o->irradiance) c += " --irradiance";
        if (o->window != "none") c += " --window " + o->window;
        if (!o->rotate.empty()) c += " --rotate " + o->rotate;
        if (o->frame_opt->count()) c += " --frame " + o->frame;
        c += " --format " + o->format;
        return run_project(*o);
    };
}

}  // namespace sphbasis::cli
