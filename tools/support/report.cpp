// sphbasis CLI support: the render report (see report.hpp).
#include "report.hpp"

#include <cmath>
#include <cstdio>
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

Json rows_json(const Report& r) {
    Json rows = Json::array();
    for (const ReportRow& x : r.rows) {
        rows.push_back({{"name", x.name},
                        {"against", x.against},
                        {"rmse", x.rmse},
                        {"rel_mse", x.rel_mse},
                        {"smape", x.smape},
                        {"judged_pixels", x.judged},
                        {"pixels", x.total},
                        {"judged_fraction", x.total > 0 ? double(x.judged) / double(x.total) : 0.0},
                        {"bake_seconds", x.bake_seconds},
                        {"bake_rays", x.bake_rays},
                        {"bakes_cached", x.cached},
                        {"render_ms_1_thread", x.render_ms_1},
                        {"render_ms_all_threads", x.render_ms_all},
                        {"element", x.element},
                        {"bytes_per_element", x.bytes_per_element},
                        {"elements", x.elements},
                        {"cannot_show", x.cannot_show},
                        {"image", x.image},
                        {"error_image", x.error_image},
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
              {"noise_limit", r.noise_limit}};
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
      << " of the pixel's luminance; \"judged\"). Render times are per frame.\n\n";
    o << "| representation | RMSE | rel. MSE | sMAPE | judged | bake s | render ms (1 thread) | "
         "render ms ("
      << r.threads << " threads) | memory | cannot show |\n";
    o << "|---|---:|---:|---:|---:|---:|---:|---:|---|---|\n";
    for (const ReportRow& x : r.rows)
        o << "| " << md_cell(x.name)
          << (x.against == "path tracer" ? "" : " (vs " + x.against + ")") << " | " << g3(x.rmse)
          << " | " << g3(x.rel_mse) << " | " << g3(x.smape) << " | " << percent(x.judged, x.total)
          << " | " << bake_text(x) << " | " << g3(x.render_ms_1) << " | " << g3(x.render_ms_all)
          << " | " << bytes_text(x) << " | " << md_cell(x.cannot_show.empty() ? "-" : x.cannot_show)
          << " |\n";
    o << "\n## Images\n\n";
    o << "Reference: ![reference](" << r.reference_image << ")\n\n";
    if (r.specular_reference && !r.specular_reference_image.empty())
        o << "Specular reference: ![specular reference](" << r.specular_reference_image << ")\n\n";
    o << "| representation | image | error (false colour, 1e-3 .. 1, grey: not judged) |\n";
    o << "|---|---|---|\n";
    for (const ReportRow& x : r.rows)
        o << "| " << md_cell(x.name) << " | ![" << md_cell(x.name) << "](" << x.image << ") | !["
          << md_cell(x.name) << " error](" << x.error_image << ") |\n";
    o << "\n## Plan\n\n```\n" << plan_text(r) << "```\n";
    if (!r.warnings.empty()) {
        o << "\n## Warnings\n\n";
        for (const std::string& w : r.warnings) o << "- " << w << "\n";
    }
    return o.str();
}

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
         "</style>\n</head>\n<body>\n";
    o << "<h1>sphbasis render: " << html_escape(r.scene) << "</h1>\n";
    o << "<p>" << r.width << "&times;" << r.height << " pixels; reference: path tracer, " << r.spp
      << " samples per pixel, relative noise " << g3(r.relative_noise) << ", "
      << g3(r.reference_seconds) << " s; " << r.threads << " threads; tone mapping "
      << html_escape(r.tonemap) << ", exposure " << g3(r.exposure)
      << (r.auto_exposure ? " (auto)" : "") << ". Errors over judged pixels (the reference's "
      << "standard error at most " << g3(r.noise_limit) << " of the luminance).</p>\n";
    o << "<table>\n<tr><th>representation</th><th>RMSE</th><th>rel. MSE</th><th>sMAPE</th>"
         "<th>judged</th><th>bake s</th><th>render ms (1 thread)</th><th>render ms ("
      << r.threads << " threads)</th><th>memory</th><th>cannot show</th></tr>\n";
    for (const ReportRow& x : r.rows)
        o << "<tr><td>" << html_escape(x.name)
          << (x.against == "path tracer" ? "" : " (vs " + html_escape(x.against) + ")")
          << "</td><td class=\"n\">" << g3(x.rmse) << "</td><td class=\"n\">" << g3(x.rel_mse)
          << "</td><td class=\"n\">" << g3(x.smape) << "</td><td class=\"n\">"
          << percent(x.judged, x.total) << "</td><td class=\"n\">" << html_escape(bake_text(x))
          << "</td><td class=\"n\">" << g3(x.render_ms_1) << "</td><td class=\"n\">"
          << g3(x.render_ms_all) << "</td><td>" << html_escape(bytes_text(x)) << "</td><td>"
          << html_escape(x.cannot_show.empty() ? "-" : x.cannot_show) << "</td></tr>\n";
    o << "</table>\n";
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
         "1e-3 (blue) to 1 (yellow); grey: not judged).</p>\n";
    for (const ReportRow& x : r.rows) {
        o << "<div class=\"grid\">\n";
        figure(x.image, x.name);
        figure(x.error_image, x.name + " error");
        o << "</div>\n";
    }
    o << "<h2>Plan</h2>\n<pre>" << html_escape(plan_text(r)) << "</pre>\n";
    if (!r.warnings.empty()) {
        o << "<h2>Warnings</h2>\n<ul>\n";
        for (const std::string& w : r.warnings) o << "<li>" << html_escape(w) << "</li>\n";
        o << "</ul>\n";
    }
    o << "</body>\n</html>\n";
    return o.str();
}

}  // namespace sphbasis::cli
