// sphbasis render tier: baking lighting representations at surface points and free points.
//
// CONTRACT (written by the lead; the engine helper implements it and may add members and
// functions, but keeps these names and meanings: the tool is written against them).
//
// Sources: Hill, "Hardware Accelerating Art Production" (Gamasutra 2004), eq. 1-5; Sloan,
// Lehtinen and Kautz, "Precomputed Radiance Transfer: Theory and Practice" (SIGGRAPH 2005
// course); Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed Visibility"
// (JGT 2009), section 3.1; Ishmukhametov, "Irradiance Normal Mapping" (thesis), section 1.9.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "../core/vec.hpp"
#include "lighting.hpp"
#include "mesh.hpp"

namespace sphbasis::render {

/// The quantities a bake can produce (bit flags).
enum Quantity : unsigned {
    ao = 1u << 0,
    bent = 1u << 1,
    visibility = 1u << 2,
    transfer = 1u << 3,
    irradiance = 1u << 4,
    radiance = 1u << 5,
};

struct BakeSettings {
    unsigned quantities = Quantity::ao;
    int bands = 3;                  // SH bands of visibility, transfer and radiance
    std::string basis = "sh";       // basis of `irradiance` (a name of find_basis())
    int coeffs = 9;                 // its coefficient count
    int rays = 256;                 // rays per point and pass
    int bounces = 0;                // at most this many interreflection bounces
    std::uint64_t seed = 0;
    double max_distance = std::numeric_limits<double>::infinity();  // ao: farther hits don't occlude
    double target_error = 1e-3;     // a bounce runs only while its bound is above this
    bool force_all_passes = false;  // run every pass the plan would skip (for tests)
};

/// A point to bake. A surface point has a normal (need not be unit; it is normalised), a free
/// point (radiance, probes) has normal {0, 0, 0}. `tangent` (unit, orthogonal to n, or zero
/// for tangent_frame(n)) orients the tangent space of `irradiance`. `id` seeds the point's
/// sample sequence: results depend only on (seed, id, settings), never on the thread count
/// or the order of points, which is what makes sharded bakes bit-identical to one run.
struct BakePoint {
    vec3<double> p{0, 0, 0}, n{0, 0, 0}, tangent{0, 0, 0};
    std::uint64_t id = 0;
};

/// What a bake gives per point; only the requested quantities are filled.
struct PointResult {
    double ao = 0, ao_stderr = 0;
    vec3<double> bent{0, 0, 0};
    std::vector<double> visibility, visibility_stderr;  // bands^2
    std::array<std::vector<double>, 3> transfer;        // R, G, B (bands^2 each)
    std::vector<double> transfer_stderr;                // bands^2 (max over channels)
    bool transfer_rgb = false;  // false: the three channels are equal (print one list)
    std::array<std::vector<double>, 3> irradiance;      // R, G, B (coeffs each)
    std::array<std::vector<double>, 3> radiance;        // R, G, B (bands^2 each)
    bool inside = false;        // the point is inside closed geometry (probes leak)
};

/// One pass of the plan: what runs, why, and what it cost.
struct Pass {
    std::string name, reason;
    std::uint64_t rays = 0;
    double seconds = 0;
};

struct SceneDesc {
    std::vector<MeshView> meshes;
    Environment environment;
    std::vector<Light> lights;
};

}  // namespace sphbasis::render

namespace sphbasis::render {

/// Bakes the requested quantities of a scene. The constructor validates the scene and the
/// settings (std::invalid_argument with a message), builds the Embree scene and derives the
/// pass plan; bake() runs exactly the planned passes, in parallel on oneTBB.
class Baker {
  public:
    Baker(const SceneDesc& scene, const BakeSettings& settings) : settings_(settings) {
        (void)scene;
        throw std::logic_error("sphbasis::render::Baker: not implemented yet");
    }
    /// The passes that will run (name, reason); after bake(), with rays and seconds.
    const std::vector<Pass>& plan() const noexcept { return plan_; }
    /// Results for each point (same order). `progress(k)` (optional) is called with the number
    /// of points finished since its last call, from any thread.
    template <class Progress = void (*)(std::size_t)>
    std::vector<PointResult> bake(const std::vector<BakePoint>& points,
                                  Progress&& progress = nullptr) {
        (void)points;
        (void)progress;
        return {};
    }
    /// Rays traced so far, all passes.
    std::uint64_t rays_traced() const noexcept { return 0; }

  private:
    BakeSettings settings_;
    std::vector<Pass> plan_;
};

}  // namespace sphbasis::render
