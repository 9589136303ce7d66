// sphbasis render tier: normal mapping with precomputed SH visibility (representations/
// family.hpp), Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed Visibility"
// (JGT 2009):
//   lxh-unc3, -unc4, -unc6    per-texel SH visibility of 3/4/6 bands (bake quantity visibility,
//                             world frame), shaded as V . (L x H)(n) at the mapped normal with an
//                             L x H cube-map table (ops/lxh_table.hpp; lxh_table_size texels a
//                             face edge, symmetric construction) of the rotated lighting on
//                             lxh_lighting_bands bands (0: the visibility's); sec. 3.
//   lxh-pcaM                  M = 4, 8, 12, 16, 24 listed (any 1..36 accepted): PCA (ops/
//                             compression.hpp) of the 6-band visibility of every point, per-texel
//                             weights, one RGB table per basis vector and the mean, T_j(n) =
//                             b_j . (L x H)(n) (eq. 5-6). M above the data's rank throws at
//                             prepare().
// Each reads the visibility bake (no bounces; per vertex on meshes without UVs). Only what a
// requested one reads is built: one table per distinct (visibility bands, lighting bands),
// shared (Context::shared(), kind "lxh-table"), one PCA per lxh-pca.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "../../core/constants.hpp"
#include "../../ops/compression.hpp"
#include "../../ops/lxh_table.hpp"
#include "../../param/cubemap.hpp"
#include "family.hpp"

namespace sphbasis::render::representations {

class Lxh : public Representation {
  public:
    static constexpr int pca_bands = 6;  // the visibility lxh-pca* compresses

    static void list(std::vector<std::string>& out) {
        out.insert(out.end(), {"lxh-unc3", "lxh-unc4", "lxh-unc6", "lxh-pca4", "lxh-pca8",
                               "lxh-pca12", "lxh-pca16", "lxh-pca24"});
    }
    static bool accepts(const std::string& name) {
        const int k = number_after(name, "lxh-unc"), m = number_after(name, "lxh-pca");
        return k == 3 || k == 4 || k == 6 || (m >= 1 && m <= pca_bands * pca_bands);
    }
    Lxh(const std::string& name, const Context& ctx) : Representation(name) {
        const int k = number_after(name, "lxh-unc"), m = number_after(name, "lxh-pca");
        if (k == 3 || k == 4 || k == 6) {
            vis_bands_ = k;
            bytes_per_element = std::size_t(k * k) * sizeof(float);
        } else if (m >= 1) {
            pca_ = true;
            vis_bands_ = pca_bands;
            vectors_ = m;
            bytes_per_element = std::size_t(m) * sizeof(float);
        } else {  // accepts() and this parser disagree
            sphbasis::detail::throw_invalid("render::Representations",
                                            "an lxh representation, got '" + name + "'");
        }
        element = "texel";
        cannot_show = "no interreflection; visibility beyond " + std::to_string(vis_bands_) +
                      " SH bands (sharp shadows), lighting " + "beyond " +
                      std::to_string(lighting_bands(ctx)) + " bands";
        if (pca_)
            cannot_show +=
                "; visibility beyond " + std::to_string(vectors_) + " principal components";
        for (const MeshView& mv : ctx.scene.meshes)
            if (!has_uvs(mv)) {
                element = "vertex";
                cannot_show += "; meshes without UVs store visibility per vertex";
                break;
            }
    }
    void plan(Context& ctx) override {
        mesh_bake =
            ctx.request_per_mesh(ctx.base_settings(Quantity::visibility, 0), true, vis_bands_);
    }
    /// The L x H table (shared by every lxh-* with the same bands) and, for lxh-pca, the PCA.
    void build(Context& ctx) override {
        const int nl = lighting_bands(ctx);
        table_ = ctx.shared<LxhTable<Param>>(
            "lxh-table", std::to_string(vis_bands_) + " " + std::to_string(nl),
            [&] {
                const std::vector<double> L = lighting(ctx, nl);
                const Param p(ctx.settings.lxh_table_size);
                return build_lxh_table(p, lxh_matrix(nl, L.data(), vis_bands_),
                                       LxhConstruction::symmetric);
            },
            &build_seconds);
        if (pca_) build_pca(ctx);
    }
    RGB shade(const Context& ctx, const Hit& hit, const vec3<double>&, double) const override {
        return pca_ ? shade_pca(hit) : shade_unc(ctx, hit);
    }
    int compressed_rank() const override { return pca_built_ ? rank_ : 0; }
    std::size_t compressions() const override { return pca_built_ ? 1 : 0; }

  private:
    using Param = param::CubeMap<float>;

    int lighting_bands(const Context& ctx) const {
        return ctx.settings.lxh_lighting_bands > 0 ? ctx.settings.lxh_lighting_bands : vis_bands_;
    }
    /// The SH of the distant lighting on `bands` bands, rotated by lighting_rotation,
    /// interleaved (coefficient i, channel c at [3 i + c]) as lxh_matrix() reads it.
    static std::vector<double> lighting(const Context& ctx, int bands) {
        const std::vector<RGB> L = ctx.distant_sh(bands);
        const std::size_t n = std::size_t(bands) * std::size_t(bands);
        std::vector<double> out(3 * n), ch(n), rot(n);
        for (std::size_t c = 0; c < 3; ++c) {
            for (std::size_t k = 0; k < n; ++k) ch[k] = L[k][c];
            sh::rotate(bands, ctx.settings.lighting_rotation, ch, rot);
            for (std::size_t k = 0; k < n; ++k) out[3 * k + c] = rot[k];
        }
        return out;
    }

    RGB shade_unc(const Context& ctx, const Hit& hit) const {
        const int b = mesh_bake[hit.mesh];
        if (b < 0) return {0, 0, 0};
        std::array<double, 64> v;
        lookup(ctx.fields[std::size_t(b)], hit, v.data());
        const vec3<double> n = Scene::normal_mapped(hit);
        std::array<float, 3 * 64> t;
        table_->lookup(float(n.x), float(n.y), float(n.z), t.data());
        const std::size_t kk = std::size_t(vis_bands_ * vis_bands_);
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c) {
            double e = 0;
            for (std::size_t k = 0; k < kk; ++k) e += v[k] * double(t[3 * k + c]);
            out[c] = hit.albedo[c] * e * constants::inv_pi;
        }
        return out;
    }
    RGB shade_pca(const Hit& hit) const {
        const int f = mesh_field_[hit.mesh];
        if (f < 0) return {0, 0, 0};
        std::array<double, 64> w;
        lookup(fields_[std::size_t(f)], hit, w.data());
        const vec3<double> n = Scene::normal_mapped(hit);
        const std::size_t m = std::size_t(vectors_);
        std::array<float, 3 * 65> t;
        param::lookup(table_->param, tables_.data(), 3 * (m + 1), float(n.x), float(n.y),
                      float(n.z), t.data());
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c) {
            double e = t[c];
            for (std::size_t j = 0; j < m; ++j) e += w[j] * double(t[3 * (j + 1) + c]);
            out[c] = hit.albedo[c] * e * constants::inv_pi;
        }
        return out;
    }

    /// PCA (mean + M vectors, compress::pca) of the visibility of every point it reads (one
    /// basis for all meshes), its weights as fields, and the per-vector RGB tables
    /// T_j(n) = b_j . (L x H)(n) (Iwanicki and Sloan, eq. 6).
    void build_pca(const Context& ctx) {
        pca_built_ = false;
        const auto t0 = std::chrono::steady_clock::now();
        const std::size_t kk = std::size_t(vis_bands_ * vis_bands_);
        std::vector<std::size_t> offset(ctx.data.size(), 0);
        std::size_t rows = 0;
        for (std::size_t b : reads()) {
            offset[b] = rows;
            rows += ctx.data[b].results.size();
        }
        compress::MatrixX<double> x(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(kk));
        for (std::size_t b : reads())
            for (std::size_t i = 0; i < ctx.data[b].results.size(); ++i) {
                const std::vector<double>& v = ctx.data[b].results[i].visibility;
                for (std::size_t k = 0; k < kk; ++k)
                    x(Eigen::Index(offset[b] + i), Eigen::Index(k)) = k < v.size() ? v[k] : 0.0;
            }
        compress::Pca<double> model;
        try {
            model = compress::pca(x, vectors_);
        } catch (const std::invalid_argument& e) {
            sphbasis::detail::throw_invalid("render::Representations::prepare",
                                            "no more PCA vectors for '" + name +
                                                "' than the baked visibility supports (" +
                                                e.what() + ")");
        }
        rank_ = model.rank;
        fields_.clear();
        mesh_field_.assign(ctx.scene.meshes.size(), -1);
        const std::size_t m = std::size_t(vectors_);
        for (std::size_t mesh = 0; mesh < ctx.scene.meshes.size(); ++mesh) {
            const int b = mesh_bake[mesh];
            if (b < 0) continue;
            const std::size_t off = offset[std::size_t(b)];
            fields_.push_back(
                make_field(ctx.data[std::size_t(b)], vectors_, [&](std::size_t i, float* out) {
                    for (std::size_t j = 0; j < m; ++j)
                        out[j] = float(model.weights(Eigen::Index(off + i), Eigen::Index(j)));
                }));
            mesh_field_[mesh] = int(fields_.size() - 1);
        }
        const LxhTable<Param>& tab = *table_;
        const std::size_t texels = tab.param.texel_count(), e = 3 * kk, o = 3 * (m + 1);
        tables_.assign(texels * o, 0.f);
        for (std::size_t t = 0; t < texels; ++t) {
            const float* src = tab.data.data() + t * e;
            float* dst = tables_.data() + t * o;
            for (std::size_t c = 0; c < 3; ++c) {
                double s = 0;
                for (std::size_t k = 0; k < kk; ++k)
                    s += model.mean(Eigen::Index(k)) * double(src[3 * k + c]);
                dst[c] = float(s);
                for (std::size_t j = 0; j < m; ++j) {
                    double sj = 0;
                    for (std::size_t k = 0; k < kk; ++k)
                        sj +=
                            model.basis(Eigen::Index(k), Eigen::Index(j)) * double(src[3 * k + c]);
                    dst[3 * (j + 1) + c] = float(sj);
                }
            }
        }
        build_seconds += seconds_since(t0);
        pca_built_ = true;
    }

    bool pca_ = false;
    int vis_bands_ = 0, vectors_ = 0;  // visibility bands, PCA vectors
    std::shared_ptr<const LxhTable<Param>> table_;
    // lxh-pca*, after prepare():
    bool pca_built_ = false;
    int rank_ = 0;
    std::vector<int> mesh_field_;  // per mesh: index into fields_, -1: none
    std::vector<Field> fields_;    // the PCA weights
    std::vector<float> tables_;    // texel x (M + 1) x 3: mean, then basis vector j
};

}  // namespace sphbasis::render::representations
