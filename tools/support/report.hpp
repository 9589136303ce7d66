// sphbasis CLI support: the comparison report of `sphbasis render` (report.json, report.md,
// report.html).
//
// The data are filled by tools/cli/render.cpp and written by three pure functions (strings,
// so that the caller writes them with the images all or none). report.html is self-contained:
// inline CSS, a small inline script that sorts the table by the column clicked, an inline SVG
// plot of the error against the shading time (log axes), the images linked by relative file names
// (the PNGs beside it), so the directory can be copied and viewed offline; it reads nothing from
// the network.
//
// Metrics (render/image_metrics.hpp has the definitions): flip (mean LDR-FLIP of the tone-mapped
// images over the covered pixels), rel_mse_floored and smape_floored (over the pixels where the
// reference's own noise allows a verdict, render::compare(): "judged"), outside_3_stderr (over
// the covered pixels), and the earlier rmse, rel_mse and smape (judged pixels; rel_mse's floor is
// so small that the darkest pixels dominate it). The rows are ranked by flip (ranked_by): it
// measures the difference a viewer sees in the picture the report shows, is bounded in [0, 1],
// is dominated neither by dark pixels nor by a few outliers, and sees edges and aliasing (the
// specular comparison) that per-pixel ratios miss; rel_mse_floored is the check in linear
// radiance beside it.
//
// Sampling (sampling_rule()): every image is made by render::ImageLoop, and a representation is
// rendered with the sample positions, box filter and sample count of the reference it is
// compared with. Times: each row's shade_ns is the representation's own shading per pixel
// sample; the camera rays and hit records the representations share are measured once
// (camera_ns_per_sample) and shown apart. render_ms_* are whole frames at one sample per pixel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "json.hpp"

namespace sphbasis::cli {

/// One step of the plan: what runs and why.
struct PlanStep {
    std::string what, reason;
};

/// One planned bake and what became of it.
struct PlannedBake {
    std::string where;       // "vertex", "texel", "probes"
    std::string mesh;        // mesh name ("" for probes)
    std::string quantities;  // "ao,transfer"
    std::string details;     // "bands 3, rays 256, bounces 1, lightmap 128"
    std::string key;         // 16 hex digits
    bool lighting_dependent = false;
    std::vector<std::string> read_by;  // representation names
    std::string status;                // "baked", "from cache" ("" before prepare)
};

/// One representation's row of the table.
struct ReportRow {
    std::string name;
    std::string against;  // "path tracer" or "specular reference"
    double rmse = 0, rel_mse = 0, smape = 0;
    double rel_mse_floored = 0, smape_floored = 0, outside_3_stderr = 0, flip = 0;
    int rank = 0;                       // 1 = the lowest flip (rank_rows())
    std::size_t judged = 0, total = 0;  // pixels
    double bake_seconds = 0;
    std::uint64_t bake_rays = 0;
    bool cached = false;
    double render_ms_1 = 0, render_ms_all = 0;  // per frame, one thread and all threads
    int spp = 0;          // samples per pixel of its image (the compared reference's)
    double shade_ns = 0;  // its own shading per pixel sample, thread-nanoseconds (no camera ray)
    std::string element;  // "texel", "vertex", "probe", "none"
    std::size_t bytes_per_element = 0, elements = 0;
    std::string cannot_show;
    std::string image, error_image, flip_image, exr;  // file names relative to the report
};

struct Report {
    std::string scene, command;
    int width = 0, height = 0, threads = 0;
    std::string tonemap;
    double exposure = 1;
    bool auto_exposure = false;
    double noise_limit = 0.05;
    double flip_ppd = 0;                        // FLIP's pixels per degree
    std::vector<double> lighting_rotation_deg;  // x, y, z (empty: none)
    // The reference.
    int bounces = 1;
    std::vector<std::string> effects;
    int spp = 0;
    double relative_noise = 0, reference_seconds = 0;
    std::uint64_t camera_rays = 0, shadow_rays = 0, bounce_rays = 0, normal_map_lookups = 0,
                  specular_evaluations = 0, environment_samples = 0, light_samples = 0;
    double rays_per_second = 0;
    bool specular_reference = false;
    int specular_ss = 0;
    double specular_reference_seconds = 0;
    // The sampling rule (sampling_rule()): the representations' samples per pixel (the
    // reference's final count; the specular ones: specular_ss^2) and the shared camera rays'
    // cost (generation, tracing, hit records) per pixel sample, thread-nanoseconds.
    int representation_spp = 0, specular_spp = 0;
    double camera_ns_per_sample = 0;
    // The plan and the bakes.
    std::vector<PlanStep> plan;
    std::vector<PlannedBake> bakes;
    std::size_t bakes_run = 0, bakes_loaded = 0;
    std::vector<std::string> warnings;
    std::vector<ReportRow> rows;
    double total_seconds = 0;
    // Files (relative names).
    std::string reference_image, reference_exr, reference_stderr_exr, specular_reference_image;
};

/// The rule by which the compared images are sampled (report.json's "sampling.rule", the
/// reports' text): one loop, the same positions, filter and counts.
std::string sampling_rule(const Report& r);

/// Sets each row's rank: 1 for the lowest flip, ties in the order of the rows.
void rank_rows(Report& r);

/// The plan as printed on stderr (one step per line, indented), before any work.
std::string plan_text(const Report& r);
Json report_json(const Report& r);
std::string report_markdown(const Report& r);
std::string report_html(const Report& r);

/// Text for HTML element content and attribute values.
std::string html_escape(const std::string& s);

}  // namespace sphbasis::cli
