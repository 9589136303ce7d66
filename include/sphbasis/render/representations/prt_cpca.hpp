// sphbasis render tier: compressed precomputed radiance transfer (representations/family.hpp):
//   prt-cpca-C-M              4-2, 8-4, 16-4 listed (any C <= 4096, M <= 64 accepted): iterative
//                             CPCA (ops/compression.hpp) of the PRT transfer (3 prt_bands^2
//                             numbers a point), the cluster and weights read from the nearest
//                             texel (clusters cannot be filtered), per-cluster exit values
//                             computed once for the lighting. Sloan, Hall, Hart and Snyder,
//                             "Clustered Principal Components for Precomputed Radiance Transfer"
//                             (SIGGRAPH 2003).
// Reads the transfer bake of prt-texel (per vertex on meshes without UVs). C or M beyond what
// the baked transfer supports throws at prepare().
#pragma once

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "../../ops/compression.hpp"
#include "family.hpp"

namespace sphbasis::render::representations {

class PrtCpca : public Representation {
  public:
    static void list(std::vector<std::string>& out) {
        out.insert(out.end(), {"prt-cpca-4-2", "prt-cpca-8-4", "prt-cpca-16-4"});
    }
    static bool accepts(const std::string& name) {
        int c = 0, m = 0;
        return parse_name(name, c, m);
    }
    PrtCpca(const std::string& name, const Context& ctx) : Representation(name) {
        if (!parse_name(name, clusters_, vectors_))
            sphbasis::detail::throw_invalid("render::Representations",
                                            "prt-cpca-C-M, got '" + name + "'");
        element = texel_or_vertex(ctx);
        bytes_per_element = std::size_t(vectors_) * sizeof(float) + 2;  // + cluster index
        cannot_show = "lighting above " + std::to_string(ctx.settings.prt_bands) +
                      " SH bands; no normal-map detail; transfer beyond " +
                      std::to_string(vectors_) + " vectors in each of " +
                      std::to_string(clusters_) +
                      " clusters (read nearest: clusters cannot be filtered)" +
                      std::string(ctx.settings.bounces > 0 ? "" : "; no interreflection");
    }
    void plan(Context& ctx) override {
        ctx.needs_sh = true;
        mesh_bake =
            ctx.request_per_mesh(ctx.base_settings(Quantity::transfer, ctx.settings.bounces), true,
                                 ctx.settings.prt_bands);
    }
    /// Iterative CPCA (compress::cpca_iterative) of the transfer of every point read (3 N^2
    /// numbers, RGB), fields of (cluster, M weights), and the per-cluster exit values
    /// mu_c . l and b_cj . l for the current lighting (the course's CPCA rendering).
    void build(Context& ctx) override {
        const std::size_t n = std::size_t(ctx.settings.prt_bands * ctx.settings.prt_bands);
        const auto t0 = std::chrono::steady_clock::now();
        std::vector<std::size_t> offset(ctx.data.size(), 0);
        std::size_t rows = 0;
        for (std::size_t b : reads()) {
            offset[b] = rows;
            rows += ctx.data[b].results.size();
        }
        compress::MatrixX<double> x(static_cast<Eigen::Index>(rows),
                                    static_cast<Eigen::Index>(3 * n));
        for (std::size_t b : reads())
            for (std::size_t i = 0; i < ctx.data[b].results.size(); ++i)
                for (std::size_t c = 0; c < 3; ++c)
                    for (std::size_t k = 0; k < n; ++k) {
                        const auto& t = ctx.data[b].results[i].transfer[c];
                        x(Eigen::Index(offset[b] + i), Eigen::Index(c * n + k)) =
                            k < t.size() ? t[k] : 0.0;
                    }
        compress::CpcaSettings cs;
        cs.clusters = clusters_;
        cs.vectors = vectors_;
        cs.seed = ctx.settings.seed + 1;
        compress::Cpca<double> model;
        try {
            model = compress::cpca_iterative(x, cs);
        } catch (const std::invalid_argument& e) {
            sphbasis::detail::throw_invalid(
                "render::Representations::prepare",
                "clusters and vectors the baked transfer supports for '" + name + "' (" + e.what() +
                    ")");
        }
        const std::size_t m = std::size_t(vectors_);
        fields_.clear();
        mesh_field_.assign(ctx.scene.meshes.size(), -1);
        for (std::size_t mesh = 0; mesh < ctx.scene.meshes.size(); ++mesh) {
            const int b = mesh_bake[mesh];
            if (b < 0) continue;
            const std::size_t off = offset[std::size_t(b)];
            fields_.push_back(
                make_field(ctx.data[std::size_t(b)], int(m + 1), [&](std::size_t i, float* out) {
                    out[0] = float(model.cluster[off + i]);
                    for (std::size_t j = 0; j < m; ++j)
                        out[j + 1] = float(model.weights(Eigen::Index(off + i), Eigen::Index(j)));
                }));
            mesh_field_[mesh] = int(fields_.size() - 1);
        }
        // Exit values: the lighting matrix (3 N^2 x 3), channel c's lighting in rows c N^2..
        compress::MatrixX<double> light = compress::MatrixX<double>::Zero(Eigen::Index(3 * n), 3);
        for (std::size_t c = 0; c < 3; ++c)
            for (std::size_t k = 0; k < n; ++k)
                light(Eigen::Index(c * n + k), Eigen::Index(c)) = ctx.sh.prt[c][k];
        const compress::ExitValues<double> ev = compress::exit_values(model, light);
        exit_.assign(std::size_t(clusters_) * (m + 1) * 3, 0.0);
        for (std::size_t cl = 0; cl < std::size_t(model.clusters()); ++cl)
            for (std::size_t c = 0; c < 3; ++c) {
                double* e = exit_.data() + cl * (m + 1) * 3;
                e[c] = ev.mean(Eigen::Index(cl), Eigen::Index(c));
                for (std::size_t j = 0; j < m; ++j)
                    e[3 * (j + 1) + c] = ev.basis[cl](Eigen::Index(j), Eigen::Index(c));
            }
        build_seconds = seconds_since(t0);
    }
    RGB shade(const Context&, const Hit& hit, const vec3<double>&, double) const override {
        const int fi = mesh_field_[hit.mesh];
        if (fi < 0) return {0, 0, 0};
        std::array<double, 65> w;
        lookup_nearest(fields_[std::size_t(fi)], hit, w.data());
        const std::size_t m = std::size_t(vectors_);
        const std::size_t cl = std::size_t(std::clamp(w[0], 0.0, double(clusters_ - 1)));
        const double* e = exit_.data() + cl * (m + 1) * 3;
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c) {
            double s = e[c];
            for (std::size_t j = 0; j < m; ++j) s += w[j + 1] * e[3 * (j + 1) + c];
            out[c] = hit.albedo[c] * s;
        }
        return out;
    }

  private:
    /// prt-cpca-C-M: C clusters (1..4096) of M vectors (1..64).
    static bool parse_name(const std::string& name, int& c, int& m) {
        const std::string pre = "prt-cpca-";
        if (name.compare(0, pre.size(), pre) != 0) return false;
        const std::size_t dash = name.find('-', pre.size());
        if (dash == std::string::npos) return false;
        c = number_after(name.substr(0, dash), pre);
        m = number_after(name.substr(dash), "-");
        return c >= 1 && c <= 4096 && m >= 1 && m <= 64;
    }

    int clusters_ = 0, vectors_ = 0;
    // After prepare():
    std::vector<int> mesh_field_;  // per mesh: index into fields_, -1: none
    std::vector<Field> fields_;    // (cluster, M weights) per point
    std::vector<double> exit_;     // per cluster, (M + 1) x 3 exit values
};

}  // namespace sphbasis::render::representations
