// Shared pieces of the render tests: image comparisons, lat-long environments, and the World
// (meshes, scene description, Embree scene) that the representation tests bake and shade.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

#include "render_shapes_for_tests.hpp"
#include "sphbasis/render/bake.hpp"
#include "sphbasis/render/image.hpp"
#include "sphbasis/render/lighting.hpp"
#include "sphbasis/render/scene.hpp"
#include "sphbasis/render/shapes.hpp"

namespace sphbasis_test {

/// A w x h RGB image of one colour.
inline sphbasis::render::Image constant_image(int w, int h, float r, float g, float b) {
    sphbasis::render::Image im(w, h, 3);
    for (std::size_t i = 0; i < std::size_t(w) * std::size_t(h); ++i) {
        im.data[3 * i] = r;
        im.data[3 * i + 1] = g;
        im.data[3 * i + 2] = b;
    }
    return im;
}

using sphbasis::render::Image;

/// v / |v|.
inline sphbasis::vec3<double> unit(sphbasis::vec3<double> v) {
    const double l = std::sqrt(sphbasis::dot(v, v));
    return {v.x / l, v.y / l, v.z / l};
}

/// Largest |a - b| over all pixels and channels (same sizes).
inline double max_abs_diff(const Image& a, const Image& b) {
    double d = 0;
    for (std::size_t i = 0; i < a.data.size(); ++i)
        d = std::max(d, std::fabs(double(a.data[i]) - double(b.data[i])));
    return d;
}
/// Largest |a| over all pixels and channels.
inline double max_abs(const Image& a) {
    double d = 0;
    for (float v : a.data) d = std::max(d, std::fabs(double(v)));
    return d;
}
/// Root mean square of a - ref over all pixels and channels (same sizes).
inline double rmse(const Image& a, const Image& ref) {
    double e = 0;
    for (std::size_t i = 0; i < a.data.size(); ++i)
        e += (double(a.data[i]) - ref.data[i]) * (double(a.data[i]) - ref.data[i]);
    return std::sqrt(e / double(a.data.size()));
}

/// w x h RGB texels, row by row: fill(i, j, p) sets the 3 floats p of column i, row j.
template <class Fill>
std::vector<float> rgb_texels(int w, int h, Fill&& fill) {
    std::vector<float> t(std::size_t(w) * std::size_t(h) * 3);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            fill(i, j, &t[3 * (std::size_t(j) * std::size_t(w) + std::size_t(i))]);
    return t;
}

/// A constant environment of radiance `radiance`.
inline sphbasis::render::Environment constant_environment(sphbasis::render::RGB radiance) {
    sphbasis::render::Environment e;
    e.kind = sphbasis::render::Environment::Kind::constant;
    e.constant = radiance;
    return e;
}
/// A lat-long environment over w x h RGB texels (borrowed: `texels` must outlive it).
inline sphbasis::render::Environment latlong_environment(const std::vector<float>& texels, int w,
                                                         int h) {
    sphbasis::render::Environment e;
    e.kind = sphbasis::render::Environment::Kind::latlong;
    e.texels = texels.data();
    e.width = w;
    e.height = h;
    return e;
}

/// A directional light towards unit `direction` with irradiance `color` (normal incidence).
inline sphbasis::render::Light directional_light(sphbasis::vec3<double> direction,
                                                 sphbasis::render::RGB color) {
    sphbasis::render::Light l;
    l.type = sphbasis::render::Light::Type::directional;
    l.direction = direction;
    l.color = color;
    return l;
}
/// A sphere light of `radius` at `position` with radiance `color`.
inline sphbasis::render::Light sphere_light(sphbasis::vec3<double> position, double radius,
                                            sphbasis::render::RGB color) {
    sphbasis::render::Light l;
    l.type = sphbasis::render::Light::Type::sphere;
    l.position = position;
    l.radius = radius;
    l.color = color;
    return l;
}

/// The value at +z of the least-squares fit of (1 + z)/2 in `basis` with `coeffs` functions on
/// `rule` (render::IrradianceFit): per unit pi L, a constant sky's irradiance over a tangent
/// hemisphere (the bake's rule hemisphere_rule_sqrt(32, 32)) or a probe's over the sphere.
inline double fit_at_z(const char* basis, int coeffs, const sphbasis::DirectionalRule& rule) {
    const sphbasis::render::IrradianceFit fit(basis, coeffs, rule);
    std::vector<double> c(std::size_t(3 * coeffs));
    fit.fit_function([](double, double, double z) { return 0.5 * (1 + z); }, c.data(),
                     c.data() + coeffs, c.data() + 2 * coeffs);
    return fit.evaluate(c.data(), 0, 0, 1);
}

/// Meshes, the scene description over them and the Embree scene; build() after the meshes and
/// the description's lighting are set (the views point into `meshes`, so do not copy a World
/// after build()).
struct World {
    std::vector<sphbasis::render::Mesh> meshes;
    std::vector<float> env_texels;  // the lat-long sky's texels, when the test sets one
    sphbasis::render::SceneDesc desc;
    std::unique_ptr<sphbasis::render::Scene> rt;
    void build() {
        desc.meshes.clear();
        for (const auto& m : meshes) desc.meshes.push_back(m.view());
        rt = std::make_unique<sphbasis::render::Scene>(desc.meshes);
    }
};

/// A ball (radius 0.5, centre 0.6 above the plane, albedo 0.7, 0.6, 0.5) over a 3 x 3 plane
/// (4 x 4 cells, albedo 0.5), both with UVs; not built.
inline World sphere_on_plane_meshes() {
    World w;
    w.meshes.push_back(sphbasis::render::shapes::sphere({0, 0, 0.6}, 0.5, 8, 16));
    w.meshes.push_back(quad_grid(-1.5, 1.5, -1.5, 1.5, 0, 4));
    w.meshes[0].albedo = {0.7f, 0.6f, 0.5f};
    w.meshes[1].albedo = {0.5f, 0.5f, 0.5f};
    return w;
}

/// The closed-form bake scene: a sphere (radius r = 1, centre height h = 2, stacks x slices
/// facets) over a 200 x 200 plane. meshes(): a scene of the two, unlit; desc(): under a constant
/// sky of 1.
struct SphereOverPlane {
    double h = 2, r = 1;
    sphbasis::render::Mesh plane, ball;
    explicit SphereOverPlane(int stacks = 64, int slices = 128)
        : plane(quad_grid(-100, 100, -100, 100, 0, 1)),
          ball(uv_sphere(0, 0, 2, 1, stacks, slices)) {}
    sphbasis::render::SceneDesc meshes() const {
        sphbasis::render::SceneDesc d;
        d.meshes = {plane.view(), ball.view()};
        return d;
    }
    sphbasis::render::SceneDesc desc() const {
        sphbasis::render::SceneDesc d = meshes();
        d.environment = constant_environment({1, 1, 1});
        return d;
    }
};

}  // namespace sphbasis_test
