// sphbasis render tier: irradiance volumes stored in the engine bases (representations/
// family.hpp):
//   volume-ambient-cube, volume-ambient-dice, volume-ambient-dice-bezier
//                             probes storing the irradiance in the ambient cube (6 values per
//                             channel; McTaggart 2004), Ambient Dice (12; Iwanicki and Sloan
//                             2017) or its Bezier variant over the icosahedron's faces (36: the
//                             whole sphere), least-squares fits over the sphere
//                             (basis/registry.hpp);
//   volume-sg9                probes storing the irradiance in BakingLab's world-space set of 9
//                             spherical Gaussian lobes (sg::bakinglab_lobes(9,
//                             Distribution::sphere): the lobes cover the whole sphere), a
//                             least-squares fit over the sphere (Pettineo, "SG Series" part 5);
//   volume-sh-l1-nonlinear, volume-zh3-hallucinate, volume-zh3
//                             probes storing a fitted representation (4, 4 and 5 values per
//                             channel: L1 SH with the Geomerics reconstruction, ZH3 with its
//                             zonal coefficient hallucinated, ZH3; basis/registry.hpp's
//                             FittedBasisInfo), fitted from the irradiance's SH.
// Each reads the probes of `volume` (SH radiance, 3 bands, bounces, lighting-dependent), converts
// every probe's irradiance (the clamped-cosine convolution of its radiance) to the stored values
// once (build), interpolates the STORED values trilinearly at the hit as an engine does, and
// evaluates them at the normal-mapped normal.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "../../basis/registry.hpp"
#include "../../core/quadrature.hpp"
#include "../../ops/projection.hpp"
#include "../../ops/sg_fit.hpp"
#include "family.hpp"
#include "field.hpp"
#include "volume.hpp"

namespace sphbasis::render::representations {

class VolumeEngine : public Representation {
  public:
    static void list(std::vector<std::string>& out) {
        for (const char* n : names()) out.push_back(std::string("volume-") + n);
    }
    static bool accepts(const std::string& name) {
        for (const char* n : names())
            if (name == std::string("volume-") + n) return true;
        return false;
    }
    VolumeEngine(const std::string& name, const Context& ctx) : Representation(name) {
        const std::string b = name.substr(7);
        fitted_ = find_fitted_basis(b);
        if (b == "sg9") {
            // The world-space lobe set: unit-amplitude lobes on the whole sphere.
            const std::vector<sg::Lobe<double>> lobes =
                sg::bakinglab_lobes(9, sg::Distribution::sphere);
            linear_ = {9, [lobes](double x, double y, double z, double* out) {
                           for (std::size_t k = 0; k < lobes.size(); ++k)
                               out[k] = sg::eval(lobes[k], x, y, z);
                       }};
        } else if (fitted_ == nullptr) {
            const BasisInfo& info = find_basis(b);  // throws for a name accepts() does not know
            // The whole sphere's count.
            linear_ = info.functions(b == "ambient-cube" ? 6 : (b == "ambient-dice" ? 12 : 36));
        }
        n_ = fitted_ != nullptr ? fitted_->stored : linear_.n;
        element = "probe";
        bytes_per_element = 3 * std::size_t(n_) * sizeof(float);
        cannot_show =
            "static lighting (ignores the render-time rotation); shadows and occlusion "
            "finer than the probe spacing; light leaks where probes straddle walls; "
            "directional detail beyond " +
            std::to_string(n_) + " " + b + " values" +
            std::string(ctx.settings.bounces > 0 ? "" : "; no interreflection");
    }
    void plan(Context& ctx) override { probe_bake = plan_probe_radiance(ctx); }
    void build(Context& ctx) override {
        const Field& f = ctx.fields[std::size_t(probe_bake)];
        const std::size_t probes = f.probe_values.size() / 27, n = std::size_t(n_);
        Eigen::MatrixXd t;  // linear: stored = T e (n x 9), the least squares over the sphere
        if (linear_.n > 0) {
            const DirectionalRule rule = sphere_rule(40);
            const BasicLeastSquares<> ls(linear_, false, rule);
            t = ls.conversion(evaluation_matrix(evaluator<SH>(9), rule));
        }
        stored_.assign(probes * 3 * n, 0.0);
        for (std::size_t p = 0; p < probes; ++p)
            for (std::size_t c = 0; c < 3; ++c) {
                Eigen::VectorXd e(9);
                for (std::size_t k = 0; k < 9; ++k)
                    e(Eigen::Index(k)) = ctx.sh.cosine9[k] * f.probe_values[27 * p + 9 * c + k];
                double* out = stored_.data() + (p * 3 + c) * n;
                if (linear_.n > 0) {
                    const Eigen::VectorXd s = t * e;
                    for (std::size_t k = 0; k < n; ++k) out[k] = s(Eigen::Index(k));
                } else {
                    fitted_->fit(e.data(), out);
                }
            }
    }
    RGB shade(const Context& ctx, const Hit& hit, const vec3<double>&, double) const override {
        const Field& f = ctx.fields[std::size_t(probe_bake)];
        const std::size_t n = std::size_t(n_);
        std::array<double, 3 * max_values> v;
        f.grid.interpolate_valid(stored_.data(), 3 * n, f.inside.data(), hit.position, v.data());
        const vec3<double> nm = Scene::normal_mapped(hit);
        std::array<double, max_values> y;
        if (linear_.n > 0) linear_.eval(nm.x, nm.y, nm.z, y.data());
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c) {
            double s = 0;
            if (linear_.n > 0) {
                for (std::size_t k = 0; k < n; ++k) s += v[c * n + k] * y[k];
            } else {
                s = fitted_->eval_d(v.data() + c * n, nm.x, nm.y, nm.z);
            }
            out[c] = hit.albedo[c] * s;
        }
        return out;
    }

  private:
    static constexpr int max_values = 36;  // values per channel at most (ambient-dice-bezier)
    static const std::vector<const char*>& names() {
        static const std::vector<const char*> n{"ambient-cube",
                                                "ambient-dice",
                                                "ambient-dice-bezier",
                                                "sh-l1-nonlinear",
                                                "zh3-hallucinate",
                                                "zh3",
                                                "sg9"};
        return n;
    }
    BasisFunctions linear_;  // the linear stored functions (n = 0: fitted_)
    const FittedBasisInfo* fitted_ = nullptr;
    int n_ = 0;
    std::vector<double> stored_;  // probes x 3 x n
};

}  // namespace sphbasis::render::representations
