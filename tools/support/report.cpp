// sphbasis CLI support: the render report (see report.hpp).
#include "report.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>

namespace sphbasis::cli {

namespace {

std::string g3(double v) {
    if (!std::isfinite(v)) return "n/a";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

std::string fixed(double v, int digits) {
    if (!std::isfinite(v)) return "n/a";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

std::string percent(std::size_t part, std::size_t whole) {
    if (whole == 0) return "n/a";
    return fixed(100.0 * double(part) / double(whole), 1) + "%";
}

std::string bytes_text(const ReportRow& row) {
    if (row.element.empty() || row.element == "none" || row.bytes_per_element == 0) return "none";
    return std::to_string(row.bytes_per_element) + " B/" + row.element + " x " +
           std::to_string(row.elements);
}

std::string bake_text(const ReportRow& row) {
    if (row.bake_rays == 0 && row.bake_seconds == 0 && !row.cached) return "none";
    return g3(row.bake_seconds) + (row.cached ? " (cached)" : "");
}

/// Markdown table cells must not contain '|' or line breaks.
std::string md_cell(const std::string& s) {
    std::string o;
    for (char c : s) {
        if (c == '|')
            o += "\\|";
        else if (c == '\n')
            o += ' ';
        else
            o += c;
    }
    return o;
}

/// Full precision for the html sort keys.
std::string g17(double v) {
    if (!std::isfinite(v)) return "0";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

/// The rows' indices in rank order.
std::vector<std::size_t> by_rank(const Report& r) {
    std::vector<std::size_t> order(r.rows.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&r](std::size_t a, std::size_t b) {
        return r.rows[a].rank < r.rows[b].rank;
    });
    return order;
}

const char* const ranking_reason =
    "Ranked by mean FLIP (lower is better): it measures the difference a viewer sees in the "
    "pictures this report shows (both images tone-mapped alike), is bounded in [0, 1], is "
    "dominated neither by dark pixels nor by a few outliers, and sees edges and aliasing that "
    "per-pixel ratios miss. The floored relative MSE is the check in linear radiance beside it.";

/// Each metric's definition, for report.json and the reports' legends.
std::vector<std::pair<std::string, std::string>> metric_definitions(const Report& r) {
    return {
        {"flip",
         "mean LDR-FLIP (Andersson et al., 'FLIP: A Difference Evaluator for Alternating "
         "Images', 2020) over the covered pixels, of the two images tone-mapped as the PNGs "
         "(exposure, operator), " +
             g3(r.flip_ppd) + " pixels per degree; 0 = identical, 1 = green against blue"},
        {"rel_mse_floored",
         "mean over judged pixels and channels of (t - r)^2 / (r^2 + 1e-2 m^2), m the mean "
         "reference value (Rousselle, Knaus and Zwicker 2011)"},
        {"smape_floored",
         "mean over judged pixels and channels of 2 |t - r| / (|t| + |r| + 1e-2 m), in [0, 2)"},
        {"outside_3_stderr",
         "fraction of covered pixels where some channel differs by more than 3 standard errors "
         "of the reference (a zero standard error floored at 1e-4 m; about 0.3-0.8% for an exact "
         "image against a noisy reference, more against a noise-free one)"},
        {"rmse", "root mean square error over judged pixels and channels"},
        {"rel_mse",
         "mean over judged pixels of sum_c (t - r)^2 / (sum_c r^2 + (1e-3 mean luminance)^2); "
         "the darkest pixels dominate it: prefer rel_mse_floored"},
        {"smape",
         "mean over judged pixels of sum_c |t - r| / sum_c (|t| + |r| + 1e-3 mean luminance)"}};
}

Json rows_json(const Report& r) {
    Json rows = Json::array();
    for (const ReportRow& x : r.rows) {
        rows.push_back({{"name", x.name},
                        {"against", x.against},
                        {"rmse", x.rmse},
                        {"rel_mse", x.rel_mse},
                        {"smape", x.smape},
                        {"rel_mse_floored", x.rel_mse_floored},
                        {"smape_floored", x.smape_floored},
                        {"outside_3_stderr", x.outside_3_stderr},
                        {"flip", x.flip},
                        {"rank", x.rank},
                        {"judged_pixels", x.judged},
                        {"pixels", x.total},
                        {"judged_fraction", x.total > 0 ? double(x.judged) / double(x.total) : 0.0},
                        {"bake_seconds", x.bake_seconds},
                        {"bake_rays", x.bake_rays},
                        {"bakes_cached", x.cached},
                        {"render_ms_1_thread", x.render_ms_1},
                        {"render_ms_all_threads", x.render_ms_all},
                        {"spp", x.spp},
                        {"shade_ns_per_sample", x.shade_ns},
                        {"element", x.element},
                        {"bytes_per_element", x.bytes_per_element},
                        {"elements", x.elements},
                        {"cannot_show", x.cannot_show},
                        {"image", x.image},
                        {"error_image", x.error_image},
                        {"flip_image", x.flip_image},
                        {"exr", x.exr}});
    }
    return rows;
}

}  // namespace

std::string html_escape(const std::string& s) {
    std::string o;
    o.reserve(s.size());
    for (char c : s) {
        switch (c) {
            case '&':
                o += "&amp;";
                break;
            case '<':
                o += "&lt;";
                break;
            case '>':
                o += "&gt;";
                break;
            case '"':
                o += "&quot;";
                break;
            case '\'':
                o += "&#39;";
                break;
            default:
                o += c;
        }
    }
    return o;
}

std::string sampling_rule(const Report& r) {
    std::ostringstream o;
    o << "Sampling: every image comes from one loop (render::ImageLoop): sample i of a pixel lies "
         "at R2 point i rotated by an offset hashed from (seed, pixel) (the pixel centre when an "
         "image has one sample), every sample of a pixel weighs the same (box filter). A "
         "representation is rendered with the seed and the sample count of the image it is "
         "compared with, so the two share every sample position: "
      << r.representation_spp << " spp against the path tracer";
    if (r.specular_reference)
        o << ", " << r.specular_spp << " (" << r.specular_ss << "x" << r.specular_ss
          << ") against the specular reference, each sample reading the mip level of the whole "
             "pixel's footprint";
    o << ". Shading ns/pixel is a representation's own shading per pixel sample on one thread; "
         "the camera rays and hit records the representations share cost "
      << g3(r.camera_ns_per_sample) << " ns per pixel sample, shown once.";
    return o.str();
}

void rank_rows(Report& r) {
    std::vector<std::size_t> order(r.rows.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&r](std::size_t a, std::size_t b) {
        return r.rows[a].flip < r.rows[b].flip;
    });
    for (std::size_t k = 0; k < order.size(); ++k) r.rows[order[k]].rank = int(k + 1);
}

std::string plan_text(const Report& r) {
    std::ostringstream o;
    o << "plan for " << r.scene << " (" << r.width << "x" << r.height << "):\n";
    for (const PlanStep& p : r.plan) o << "  " << p.what << ": " << p.reason << "\n";
    o << "  reference: path tracer, bounces "
      << (r.bounces < 0 ? std::string("unbounded (Russian roulette)") : std::to_string(r.bounces))
      << "\n";
    for (const std::string& e : r.effects) o << "    " << e << "\n";
    if (r.specular_reference)
        o << "  specular reference: " << r.specular_ss << "x" << r.specular_ss
          << " supersampled (for specular-*)\n";
    if (r.bakes.empty()) o << "  bakes: none (no requested representation reads one)\n";
    for (std::size_t i = 0; i < r.bakes.size(); ++i) {
        const PlannedBake& b = r.bakes[i];
        o << "  bake " << i + 1 << ": " << b.quantities << " per " << b.where
          << (b.mesh.empty() ? std::string() : " of '" + b.mesh + "'") << " (" << b.details
          << (b.lighting_dependent ? ", lighting-dependent" : "") << "), key " << b.key;
        if (!b.read_by.empty()) {
            o << ", read by";
            for (std::size_t k = 0; k < b.read_by.size(); ++k)
                o << (k ? ", " : " ") << b.read_by[k];
        }
        if (!b.status.empty()) o << " [" << b.status << "]";
        o << "\n";
    }
    return o.str();
}

Json report_json(const Report& r) {
    Json plan = Json::array();
    for (const PlanStep& p : r.plan) plan.push_back({{"what", p.what}, {"reason", p.reason}});
    Json bakes = Json::array();
    for (const PlannedBake& b : r.bakes)
        bakes.push_back({{"where", b.where},
                         {"mesh", b.mesh},
                         {"quantities", b.quantities},
                         {"details", b.details},
                         {"key", b.key},
                         {"lighting_dependent", b.lighting_dependent},
                         {"read_by", b.read_by},
                         {"status", b.status}});
    Json j = {{"tool", "sphbasis render"},
              {"scene", r.scene},
              {"command", r.command},
              {"width", r.width},
              {"height", r.height},
              {"threads", r.threads},
              {"tonemap", r.tonemap},
              {"exposure", r.exposure},
              {"auto_exposure", r.auto_exposure},
              {"noise_limit", r.noise_limit},
              {"flip_ppd", r.flip_ppd},
              {"ranked_by", "flip"},
              {"ranking_reason", ranking_reason}};
    Json defs = Json::object();
    for (const auto& [k, v] : metric_definitions(r)) defs[k] = v;
    j["metrics"] = defs;
    if (!r.lighting_rotation_deg.empty()) j["lighting_rotation_deg"] = r.lighting_rotation_deg;
    j["plan"] = plan;
    j["reference"] = {{"bounces", r.bounces},
                      {"effects", r.effects},
                      {"spp", r.spp},
                      {"relative_noise", r.relative_noise},
                      {"seconds", r.reference_seconds},
                      {"rays_per_second", r.rays_per_second},
                      {"counters",
                       {{"camera_rays", r.camera_rays},
                        {"shadow_rays", r.shadow_rays},
                        {"bounce_rays", r.bounce_rays},
                        {"normal_map_lookups", r.normal_map_lookups},
                        {"specular_evaluations", r.specular_evaluations},
                        {"environment_samples", r.environment_samples},
                        {"light_samples", r.light_samples}}},
                      {"image", r.reference_image},
                      {"exr", r.reference_exr},
                      {"stderr_exr", r.reference_stderr_exr}};
    if (r.specular_reference)
        j["specular_reference"] = {{"supersampling", r.specular_ss},
                                   {"seconds", r.specular_reference_seconds},
                                   {"image", r.specular_reference_image}};
    j["sampling"] = {{"rule", sampling_rule(r)},
                     {"filter", "box"},
                     {"representation_spp", r.representation_spp},
                     {"specular_spp", r.specular_spp},
                     {"camera_ns_per_sample", r.camera_ns_per_sample}};
    j["bakes"] = bakes;
    j["bakes_run"] = r.bakes_run;
    j["bakes_loaded"] = r.bakes_loaded;
    j["warnings"] = r.warnings;
    j["representations"] = rows_json(r);
    j["seconds"] = r.total_seconds;
    return j;
}

std::string report_markdown(const Report& r) {
    std::ostringstream o;
    o << "# sphbasis render: " << r.scene << "\n\n";
    o << r.width << "x" << r.height << " pixels; reference: path tracer, " << r.spp
      << " samples per pixel, relative noise " << g3(r.relative_noise) << ", "
      << g3(r.reference_seconds) << " s (" << g3(r.rays_per_second) << " rays/s); " << r.threads
      << " threads; tone mapping " << r.tonemap << ", exposure " << g3(r.exposure)
      << (r.auto_exposure ? " (auto)" : "") << ".\n\n";
    o << "Errors are over the pixels where the reference's own noise allows a verdict (its "
         "standard error at most "
      << g3(r.noise_limit)
      << " of the pixel's luminance; \"judged\"), FLIP and the 3-sigma fraction over the covered "
         "pixels. "
      << sampling_rule(r)
      << " Render ms are whole frames at one sample per pixel (the pixel "
         "centre). "
      << ranking_reason << "\n\n";
    o << "| rank | representation | FLIP | rel. MSE (floored) | sMAPE (floored) | > 3 stderr | "
         "RMSE | rel. MSE | sMAPE | judged | bake s | shading ns/pixel | render ms (1 thread) | "
         "render ms ("
      << r.threads << " threads) | memory | cannot show |\n";
    o << "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|\n";
    for (std::size_t k : by_rank(r)) {
        const ReportRow& x = r.rows[k];
        o << "| " << x.rank << " | " << md_cell(x.name)
          << (x.against == "path tracer" ? "" : " (vs " + x.against + ")") << " | " << g3(x.flip)
          << " | " << g3(x.rel_mse_floored) << " | " << g3(x.smape_floored) << " | "
          << fixed(100 * x.outside_3_stderr, 1) << "% | " << g3(x.rmse) << " | " << g3(x.rel_mse)
          << " | " << g3(x.smape) << " | " << percent(x.judged, x.total) << " | " << bake_text(x)
          << " | " << g3(x.shade_ns) << " | " << g3(x.render_ms_1) << " | " << g3(x.render_ms_all)
          << " | " << bytes_text(x) << " | " << md_cell(x.cannot_show.empty() ? "-" : x.cannot_show)
          << " |\n";
    }
    o << "\nMetrics:\n\n";
    for (const auto& [k, v] : metric_definitions(r)) o << "- `" << k << "`: " << v << "\n";
    o << "\n## Images\n\n";
    o << "Reference: ![reference](" << r.reference_image << ")\n\n";
    if (r.specular_reference && !r.specular_reference_image.empty())
        o << "Specular reference: ![specular reference](" << r.specular_reference_image << ")\n\n";
    o << "| representation | image | error (false colour, 1e-3 .. 1, grey: not judged) | FLIP "
         "(0 .. 1) |\n";
    o << "|---|---|---|---|\n";
    for (std::size_t k : by_rank(r)) {
        const ReportRow& x = r.rows[k];
        o << "| " << md_cell(x.name) << " | ![" << md_cell(x.name) << "](" << x.image << ") | !["
          << md_cell(x.name) << " error](" << x.error_image << ") | ![" << md_cell(x.name)
          << " FLIP](" << x.flip_image << ") |\n";
    }
    o << "\n## Plan\n\n```\n" << plan_text(r) << "```\n";
    if (!r.warnings.empty()) {
        o << "\n## Warnings\n\n";
        for (const std::string& w : r.warnings) o << "- " << w << "\n";
    }
    return o.str();
}

namespace {

/// The inline SVG plot: each row's flip against its own shading time per pixel sample, log axes.
std::string cost_plot_svg(const Report& r) {
    const double W = 640, H = 400, left = 70, right = 170, top = 20, bottom = 50;
    double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
    for (const ReportRow& x : r.rows) {
        if (x.shade_ns > 0) {
            xmin = std::min(xmin, x.shade_ns);
            xmax = std::max(xmax, x.shade_ns);
        }
        if (x.flip > 0) {
            ymin = std::min(ymin, x.flip);
            ymax = std::max(ymax, x.flip);
        }
    }
    if (!(xmax > 0)) xmin = xmax = 1;
    if (!(ymax > 0)) ymin = ymax = 1e-3;
    // Whole decades around the data; a value <= 0 sits on the bottom (left) edge.
    const double lx0 = std::floor(std::log10(xmin)),
                 lx1 = std::max(lx0 + 1, std::ceil(std::log10(xmax)));
    const double ly0 = std::floor(std::log10(ymin)),
                 ly1 = std::max(ly0 + 1, std::ceil(std::log10(ymax)));
    auto px = [&](double v) {
        const double l = v > 0 ? std::clamp(std::log10(v), lx0, lx1) : lx0;
        return left + (l - lx0) / (lx1 - lx0) * (W - left - right);
    };
    auto py = [&](double v) {
        const double l = v > 0 ? std::clamp(std::log10(v), ly0, ly1) : ly0;
        return H - bottom - (l - ly0) / (ly1 - ly0) * (H - top - bottom);
    };
    std::ostringstream o;
    o << "<svg id=\"cost-plot\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W
      << "\" height=\"" << H << "\" viewBox=\"0 0 " << W << " " << H
      << "\" font-size=\"11\" role=\"img\" aria-label=\"FLIP against shading time\">\n";
    o << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << W - left - right
      << "\" height=\"" << H - top - bottom << "\" fill=\"none\" stroke=\"#888\"/>\n";
    // Grid lines at 1, 2 and 5 times each decade (labelled; 1 only over more than 2 decades).
    for (double l = lx0; l <= lx1; ++l)
        for (double m : {1.0, 2.0, 5.0}) {
            const double v = m * std::pow(10.0, l);
            if (std::log10(v) > lx1 + 1e-9 || (m != 1 && lx1 - lx0 > 2)) continue;
            const double x = px(v);
            o << "<line x1=\"" << x << "\" x2=\"" << x << "\" y1=\"" << top << "\" y2=\""
              << H - bottom << "\" stroke=\"#ddd\"/><text x=\"" << x << "\" y=\"" << H - bottom + 14
              << "\" text-anchor=\"middle\">" << g3(v) << "</text>\n";
        }
    for (double l = ly0; l <= ly1; ++l)
        for (double m : {1.0, 2.0, 5.0}) {
            const double v = m * std::pow(10.0, l);
            if (std::log10(v) > ly1 + 1e-9 || (m != 1 && ly1 - ly0 > 2)) continue;
            const double y = py(v);
            o << "<line x1=\"" << left << "\" x2=\"" << W - right << "\" y1=\"" << y << "\" y2=\""
              << y << "\" stroke=\"#ddd\"/><text x=\"" << left - 4 << "\" y=\"" << y + 4
              << "\" text-anchor=\"end\">" << g3(v) << "</text>\n";
        }
    o << "<text x=\"" << (left + W - right) / 2 << "\" y=\"" << H - 12
      << "\" text-anchor=\"middle\">shading ns per pixel sample (one thread, log; camera rays "
      << g3(r.camera_ns_per_sample) << " ns apart)</text>\n";
    o << "<text transform=\"translate(16," << (top + H - bottom) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">FLIP (log; lower is better)</text>\n";
    // Points in rank order; a name is written where it overlaps no name already written (the
    // others show on hover: <title>).
    std::vector<std::array<double, 4>> placed;  // x0, y0, x1, y1 of the names written
    for (std::size_t k : by_rank(r)) {
        const ReportRow& x = r.rows[k];
        const double cx = px(x.shade_ns), cy = py(x.flip);
        o << "<g><title>" << html_escape(x.name) << ": FLIP " << g3(x.flip) << ", "
          << g3(x.shade_ns) << " ns</title><circle cx=\"" << cx << "\" cy=\"" << cy
          << "\" r=\"4\" fill=\"#3b528b\"/>";
        const std::array<double, 4> box = {cx + 6, cy - 7, cx + 6 + 6.2 * double(x.name.size()),
                                           cy + 5};
        const bool free = std::none_of(placed.begin(), placed.end(), [&box](const auto& b) {
            return box[0] < b[2] && b[0] < box[2] && box[1] < b[3] && b[1] < box[3];
        });
        if (free) {
            placed.push_back(box);
            o << "<text x=\"" << cx + 6 << "\" y=\"" << cy + 4 << "\">" << html_escape(x.name)
              << "</text>";
        }
        o << "</g>\n";
    }
    o << "</svg>\n";
    return o.str();
}

/// Sorts the table whose header cell was clicked by that column: numbers (data-v) as numbers,
/// else text; a second click reverses. aria-sort on the header says the order.
const char* const sort_script = R"(<script>
(function () {
  var table = document.getElementById('results');
  var heads = table.tHead.rows[0].cells;
  function key(row, col) {
    var c = row.cells[col], v = c.getAttribute('data-v');
    return v === null ? c.textContent.trim() : v;
  }
  Array.prototype.forEach.call(heads, function (th, col) {
    th.addEventListener('click', function () {
      var asc = th.getAttribute('aria-sort') !== 'ascending';
      Array.prototype.forEach.call(heads, function (h) { h.removeAttribute('aria-sort'); });
      th.setAttribute('aria-sort', asc ? 'ascending' : 'descending');
      var body = table.tBodies[0], rows = Array.prototype.slice.call(body.rows);
      rows.sort(function (a, b) {
        var x = key(a, col), y = key(b, col), nx = parseFloat(x), ny = parseFloat(y);
        var c = (!isNaN(nx) && !isNaN(ny)) ? nx - ny : String(x).localeCompare(String(y));
        return asc ? c : -c;
      });
      rows.forEach(function (r) { body.appendChild(r); });
    });
  });
})();
</script>
)";

}  // namespace

std::string report_html(const Report& r) {
    std::ostringstream o;
    o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      << "<title>sphbasis render: " << html_escape(r.scene) << "</title>\n"
      << "<style>\n"
         "body{font-family:sans-serif;margin:1.5em;color:#222}\n"
         "table{border-collapse:collapse;margin:1em 0}\n"
         "td,th{border:1px solid #bbb;padding:0.25em 0.5em}\n"
         "td.n{text-align:right;font-variant-numeric:tabular-nums}\n"
         ".grid{display:flex;flex-wrap:wrap;gap:1em}\n"
         "figure{margin:0}\nfigcaption{font-size:0.9em;text-align:center}\n"
         "img{image-rendering:pixelated;display:block}\n"
         "pre{background:#f4f4f4;padding:0.5em}\n"
         "th{cursor:pointer;background:#f4f4f4}\n"
         "th[aria-sort=ascending]::after{content:' \\25B2'}\n"
         "th[aria-sort=descending]::after{content:' \\25BC'}\n"
         "img.thumb{max-width:120px;height:auto;display:inline-block;vertical-align:middle}\n"
         "#results td:last-child{min-width:22em;font-size:0.9em}\n"
         "</style>\n</head>\n<body>\n";
    o << "<h1>sphbasis render: " << html_escape(r.scene) << "</h1>\n";
    o << "<p>" << r.width << "&times;" << r.height << " pixels; reference: path tracer, " << r.spp
      << " samples per pixel, relative noise " << g3(r.relative_noise) << ", "
      << g3(r.reference_seconds) << " s; " << r.threads << " threads; tone mapping "
      << html_escape(r.tonemap) << ", exposure " << g3(r.exposure)
      << (r.auto_exposure ? " (auto)" : "") << ". Errors over judged pixels (the reference's "
      << "standard error at most " << g3(r.noise_limit) << " of the luminance).</p>\n";
    o << "<p>" << html_escape(sampling_rule(r)) << "</p>\n";
    o << "<p>" << html_escape(ranking_reason)
      << " Click a column header to sort by it; click again to reverse.</p>\n";
    o << "<table id=\"results\">\n<thead><tr><th>rank</th><th>representation</th>"
         "<th>image</th><th>FLIP map</th><th>FLIP</th><th>rel. MSE (floored)</th>"
         "<th>sMAPE (floored)</th><th>&gt; 3 stderr</th><th>RMSE</th><th>rel. MSE</th>"
         "<th>sMAPE</th><th>judged</th><th>bake s</th><th>shading ns/pixel</th>"
         "<th>render ms (1 thread)</th>"
         "<th>render ms ("
      << r.threads << " threads)</th><th>memory</th><th>cannot show</th></tr></thead>\n<tbody>\n";
    auto num = [&o](double v, const std::string& text) {
        o << "<td class=\"n\" data-v=\"" << g17(v) << "\">" << html_escape(text) << "</td>";
    };
    auto thumb = [&o](const std::string& file, const std::string& alt) {
        o << "<td><a href=\"" << html_escape(file) << "\"><img class=\"thumb\" src=\""
          << html_escape(file) << "\" alt=\"" << html_escape(alt) << "\"></a></td>";
    };
    for (std::size_t k : by_rank(r)) {
        const ReportRow& x = r.rows[k];
        o << "<tr>";
        num(double(x.rank), std::to_string(x.rank));
        o << "<td>" << html_escape(x.name)
          << (x.against == "path tracer" ? "" : " (vs " + html_escape(x.against) + ")") << "</td>";
        thumb(x.image, x.name);
        thumb(x.flip_image, x.name + " FLIP");
        num(x.flip, g3(x.flip));
        num(x.rel_mse_floored, g3(x.rel_mse_floored));
        num(x.smape_floored, g3(x.smape_floored));
        num(x.outside_3_stderr, fixed(100 * x.outside_3_stderr, 1) + "%");
        num(x.rmse, g3(x.rmse));
        num(x.rel_mse, g3(x.rel_mse));
        num(x.smape, g3(x.smape));
        num(x.total ? double(x.judged) / double(x.total) : 0.0, percent(x.judged, x.total));
        num(x.bake_seconds, bake_text(x));
        num(x.shade_ns, g3(x.shade_ns));
        num(x.render_ms_1, g3(x.render_ms_1));
        num(x.render_ms_all, g3(x.render_ms_all));
        num(double(x.bytes_per_element) * double(x.elements), bytes_text(x));
        o << "<td>" << html_escape(x.cannot_show.empty() ? "-" : x.cannot_show) << "</td></tr>\n";
    }
    o << "</tbody>\n</table>\n";
    o << "<h2>Metrics</h2>\n<dl>\n";
    for (const auto& [k, v] : metric_definitions(r))
        o << "<dt>" << html_escape(k) << "</dt><dd>" << html_escape(v) << "</dd>\n";
    o << "</dl>\n";
    o << "<h2>Error against cost</h2>\n" << cost_plot_svg(r);
    auto figure = [&o, &r](const std::string& file, const std::string& caption) {
        o << "<figure><img src=\"" << html_escape(file) << "\" width=\"" << r.width
          << "\" height=\"" << r.height << "\" alt=\"" << html_escape(caption) << "\"><figcaption>"
          << html_escape(caption) << "</figcaption></figure>\n";
    };
    o << "<h2>Images</h2>\n<div class=\"grid\">\n";
    figure(r.reference_image, "reference (path tracer)");
    if (r.specular_reference && !r.specular_reference_image.empty())
        figure(r.specular_reference_image, "specular reference");
    o << "</div>\n";
    o << "<p>Each representation beside its relative error (false colour, logarithmic from "
         "1e-3 (blue) to 1 (yellow); grey: not judged) and its FLIP map (linear from 0 (blue) "
         "to 1 (yellow)).</p>\n";
    for (std::size_t k : by_rank(r)) {
        const ReportRow& x = r.rows[k];
        o << "<div class=\"grid\">\n";
        figure(x.image, x.name);
        figure(x.error_image, x.name + " error");
        figure(x.flip_image, x.name + " FLIP");
        o << "</div>\n";
    }
    o << "<h2>Plan</h2>\n<pre>" << html_escape(plan_text(r)) << "</pre>\n";
    if (!r.warnings.empty()) {
        o << "<h2>Warnings</h2>\n<ul>\n";
        for (const std::string& w : r.warnings) o << "<li>" << html_escape(w) << "</li>\n";
        o << "</ul>\n";
    }
    o << sort_script << "</body>\n</html>\n";
    return o.str();
}

}  // namespace sphbasis::cli
