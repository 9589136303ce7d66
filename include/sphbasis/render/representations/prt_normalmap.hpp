// sphbasis render tier: normal mapping with precomputed radiance transfer (representations/
// family.hpp):
//   prt-normalmap             the incident-transfer matrix M (bake quantity transfer_matrix:
//                             9 x prt_bands^2 RGB per texel) shaded as e(n) = y(n)^T C M l at the
//                             mapped normal in world frame (R = I there); Sloan, Lehtinen and
//                             Kautz, "Precomputed Radiance Transfer: Theory and Practice"
//                             (SIGGRAPH 2005 course), normal mapping for PRT.
//   prt-normalmap-svd4, -svd6 the same through the normal basis (ops/normal_basis.hpp, unclamped,
//                             cosine-weighted): per texel G = V_k^T R M (R: world to the texel's
//                             tangent frame), e(n) = (a(n)^T V_k) G l with a(n) = pi a_l y(n).
//   prt-ratio                 unshadowed irradiance at the mapped normal times the ratio of the
//                             shadowed (PRT transfer) to the unshadowed irradiance at the
//                             surface normal; reads prt-texel's bake.
// Each reads a texel bake (per vertex on meshes without UVs) with prt_bands bands and the
// scene's bounces; the lighting may be rotated at render time as for prt-*.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../../core/constants.hpp"
#include "../../core/frame.hpp"
#include "../../ops/normal_basis.hpp"
#include "bake_points.hpp"
#include "family.hpp"
#include "prt.hpp"

namespace sphbasis::render::representations {

class PrtNormalMap : public Representation {
  public:
    static void list(std::vector<std::string>& out) {
        out.insert(out.end(),
                   {"prt-normalmap", "prt-normalmap-svd4", "prt-normalmap-svd6", "prt-ratio"});
    }
    static bool accepts(const std::string& name) {
        return name == "prt-normalmap" || name == "prt-normalmap-svd4" ||
               name == "prt-normalmap-svd6" || name == "prt-ratio";
    }
    PrtNormalMap(const std::string& name, const Context& ctx)
        : Representation(name), ratio_(name == "prt-ratio") {
        const char* no_bounce = ctx.settings.bounces > 0 ? "" : "; no interreflection";
        element = texel_or_vertex(ctx);
        if (ratio_) {
            cannot_show =
                "shadowing of the tilted normal taken from the surface normal's "
                "(one ratio per texel)" +
                std::string(no_bounce);
            return;
        }
        const int nb = ctx.settings.prt_bands;
        if (name != "prt-normalmap") {
            svd_vectors_ = name == "prt-normalmap-svd4" ? 4 : 6;
            bytes_per_element = 3 * std::size_t(svd_vectors_ * nb * nb) * sizeof(float);
        } else {
            bytes_per_element = 3 * std::size_t(9 * nb * nb) * sizeof(float);
        }
        cannot_show = "lighting above " + std::to_string(nb) +
                      " SH bands; incident light above 3 bands" + std::string(no_bounce);
        if (svd_vectors_ > 0)
            cannot_show += "; normal variation beyond " + std::to_string(svd_vectors_) +
                           " normal-basis functions";
    }
    void plan(Context& ctx) override {
        ctx.needs_sh = true;
        mesh_bake = ctx.request_per_mesh(
            ctx.base_settings(ratio_ ? Quantity::transfer : Quantity::transfer_matrix,
                              ctx.settings.bounces),
            true, ctx.settings.prt_bands);
    }
    void build(Context& ctx) override {
        if (svd_vectors_ > 0) build_svd(ctx);
    }
    RGB shade(const Context& ctx, const Hit& hit, const vec3<double>&, double) const override {
        if (ratio_) return shade_ratio(ctx, hit);
        return svd_vectors_ > 0 ? shade_svd(ctx, hit) : shade_normalmap(ctx, hit);
    }
    void stats(const Context& ctx, RepresentationStats& s) const override {
        if (ratio_) s.bytes_per_element = transfer_bytes(ctx, *this);
    }

  private:
    RGB shade_ratio(const Context& ctx, const Hit& hit) const {
        const int b = mesh_bake[hit.mesh];
        if (b < 0) return {0, 0, 0};
        std::array<double, 3 * 64> t;
        lookup(ctx.fields[std::size_t(b)], hit, t.data());
        const std::size_t n = std::size_t(ctx.settings.prt_bands * ctx.settings.prt_bands);
        const RGB u0 = sh_shade(ctx.sh.irr, hit.shading_normal, {1, 1, 1});
        const RGB um = sh_shade(ctx.sh.irr, Scene::normal_mapped(hit), hit.albedo);
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c) {
            const double sh = transfer_dot(t.data() + c * n, ctx.sh.prt[c], n);
            out[c] = u0[c] > 1e-12 ? std::max(sh, 0.0) / u0[c] * um[c] : 0.0;
        }
        return out;
    }
    /// prt-normalmap: L_in = M l (3 bands, world frame) per channel, shaded at the mapped
    /// normal: e(n) = y(n)^T C M l (the tangent rotation R is the identity in world frame).
    RGB shade_normalmap(const Context& ctx, const Hit& hit) const {
        const int b = mesh_bake[hit.mesh];
        if (b < 0) return {0, 0, 0};
        const std::size_t n = std::size_t(ctx.settings.prt_bands * ctx.settings.prt_bands);
        std::array<double, 27 * 64> m;
        lookup(ctx.fields[std::size_t(b)], hit, m.data());
        const vec3<double> nm = Scene::normal_mapped(hit);
        double y[9];
        sh::eval_unit(3, nm.x, nm.y, nm.z, y);
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c) {
            double e = 0;
            for (std::size_t i = 0; i < 9; ++i) {
                const double li = transfer_dot(m.data() + c * 9 * n + i * n, ctx.sh.prt[c], n);
                e += ctx.sh.cosine9[i] * li * y[i];
            }
            out[c] = hit.albedo[c] * e;
        }
        return out;
    }
    /// The tangent frame a hit reads a prt-normalmap-svd field in: the texel's (tangent,
    /// bitangent, normal) as the lightmaps, Frame(normal) for per-vertex fields.
    static Frame<double> svd_frame(const Field& f, const Hit& hit) {
        using namespace detail::rt;
        const V3 ns = hit.shading_normal;
        if (f.where == BakeRequest::Where::vertex || !(length(hit.tangent) > 0.5))
            return Frame<double>(ns);
        return Frame<double>(hit.tangent, cross(ns, hit.tangent) * hit.bitangent_sign, ns);
    }
    /// prt-normalmap-svdM: per texel G = V_M^T R M (M x N^2 per channel), e(n) =
    /// (a(n)^T V_M) (G l) with a(n) = pi a_l y_lm(n) in the tangent frame.
    RGB shade_svd(const Context& ctx, const Hit& hit) const {
        const int fi = mesh_field_[hit.mesh];
        if (fi < 0) return {0, 0, 0};
        const Field& f = fields_[std::size_t(fi)];
        const std::size_t n = std::size_t(ctx.settings.prt_bands * ctx.settings.prt_bands);
        const std::size_t mv = std::size_t(svd_vectors_);
        std::array<double, 3 * 6 * 64> g;
        lookup(f, hit, g.data());
        const Frame<double> fr = svd_frame(f, hit);
        using namespace detail::rt;
        const V3 nm = Scene::normal_mapped(hit);
        V3 u{dot(nm, fr.s), dot(nm, fr.t), std::max(dot(nm, fr.n), 0.0)};
        u = normalized(u, {0, 0, 1});
        double y[9], p[9];
        sh::eval_unit(3, u.x, u.y, u.z, y);
        const Eigen::MatrixXd& v = *normal_v_;
        for (std::size_t k = 0; k < mv; ++k) {
            p[k] = 0;
            for (std::size_t i = 0; i < 9; ++i)
                p[k] +=
                    constants::pi * ctx.sh.cosine9[i] * y[i] * v(Eigen::Index(i), Eigen::Index(k));
        }
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c) {
            double e = 0;
            for (std::size_t k = 0; k < mv; ++k) {
                e += p[k] * transfer_dot(g.data() + (c * mv + k) * n, ctx.sh.prt[c], n);
            }
            out[c] = hit.albedo[c] * e * constants::inv_pi;
        }
        return out;
    }
    /// The fields of prt-normalmap-svd*: G = V_M^T R M per point, R the SH rotation of
    /// 3 bands from world to the point's tangent frame (by least squares on 25 directions:
    /// exact for 3-band functions, mirrored frames included).
    void build_svd(Context& ctx) {
        build_seconds = 0;
        normal_v_ = ctx.shared<Eigen::MatrixXd>("normal-basis", "3 unclamped cosine", [] {
            NormalBasisSettings nbs;
            nbs.bands = 3;
            nbs.clamped = false;
            nbs.weighting = NormalWeighting::cosine;
            return normal_basis(nbs).v;
        });
        constexpr int S = 25;
        std::array<vec3<double>, S> u;
        Eigen::MatrixXd yl(S, 9);
        for (int s = 0; s < S; ++s) {
            const double z = 1 - (2 * s + 1) / double(S), rr = std::sqrt(1 - z * z);
            const double ph = 2.399963229728653 * s;  // the golden angle
            u[std::size_t(s)] = {rr * std::cos(ph), rr * std::sin(ph), z};
            double y[9];
            sh::eval_unit(3, u[std::size_t(s)].x, u[std::size_t(s)].y, u[std::size_t(s)].z, y);
            for (int i = 0; i < 9; ++i) yl(s, i) = y[i];
        }
        const Eigen::MatrixXd pinv = (yl.transpose() * yl).inverse() * yl.transpose();
        const std::size_t n = std::size_t(ctx.settings.prt_bands * ctx.settings.prt_bands);
        const std::size_t mv = std::size_t(svd_vectors_);
        const Eigen::MatrixXd vt = normal_v_->leftCols(Eigen::Index(mv)).transpose();
        fields_.clear();
        mesh_field_.assign(ctx.scene.meshes.size(), -1);
        for (std::size_t mesh = 0; mesh < ctx.scene.meshes.size(); ++mesh) {
            const int b = mesh_bake[mesh];
            if (b < 0) continue;
            const BakeData& d = ctx.data[std::size_t(b)];
            std::vector<double> vn;
            if (d.request.where == BakeRequest::Where::vertex)
                vn = vertex_normals(ctx.scene.meshes[mesh]);
            const auto t0 = std::chrono::steady_clock::now();
            fields_.push_back(make_field(d, int(3 * mv * n), [&](std::size_t i, float* out) {
                using namespace detail::rt;
                Frame<double> fr;
                if (d.request.where == BakeRequest::Where::vertex) {
                    fr = Frame<double>(
                        normalized(V3{vn[3 * i], vn[3 * i + 1], vn[3 * i + 2]}, {0, 0, 1}));
                } else {
                    const BakePoint& bp = d.layout.samples[i].point;
                    const V3 nn = normalized(bp.n, {0, 0, 1});
                    fr = length(bp.tangent) > 0.5
                             ? Frame<double>(bp.tangent, cross(nn, bp.tangent) * bp.bitangent_sign,
                                             nn)
                             : Frame<double>(nn);
                }
                Eigen::MatrixXd yw(S, 9);
                for (int s2 = 0; s2 < S; ++s2) {
                    const vec3<double>& q = u[std::size_t(s2)];
                    const V3 w = fr.s * q.x + fr.t * q.y + fr.n * q.z;
                    double y[9];
                    sh::eval_unit(3, w.x, w.y, w.z, y);
                    for (int k = 0; k < 9; ++k) yw(s2, k) = y[k];
                }
                const Eigen::MatrixXd vr = vt * (pinv * yw);  // mv x 9
                const PointResult& pr = d.results[i];
                for (std::size_t c = 0; c < 3; ++c)
                    for (std::size_t k = 0; k < mv; ++k)
                        for (std::size_t j = 0; j < n; ++j) {
                            double v = 0;
                            for (std::size_t q = 0; q < 9; ++q)
                                if (q * n + j < pr.transfer_matrix[c].size())
                                    v += vr(Eigen::Index(k), Eigen::Index(q)) *
                                         pr.transfer_matrix[c][q * n + j];
                            out[(c * mv + k) * n + j] = float(v);
                        }
            }));
            mesh_field_[mesh] = int(fields_.size() - 1);
            build_seconds += seconds_since(t0);
        }
    }

    bool ratio_ = false;
    int svd_vectors_ = 0;  // prt-normalmap-svd*: normal-basis functions kept
    // prt-normalmap-svd*, after prepare():
    std::shared_ptr<const Eigen::MatrixXd> normal_v_;  // V of the normal basis (9 x 9)
    std::vector<int> mesh_field_;                      // per mesh: index into fields_
    std::vector<Field> fields_;
};

}  // namespace sphbasis::render::representations
