// sphbasis CLI support: load_linear_rgb (see envmap.hpp).
#include "envmap.hpp"

#include <stb/stb_image.h>  // STB_IMAGE_IMPLEMENTATION is in scene_file.cpp

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "exr.hpp"

namespace sphbasis::cli {

double srgb_to_linear(double v) {
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

namespace {

LinearRgbImage load_exr(const std::string& path) {
    RgbImage stored = read_exr_rgb_as_stored(path);
    LinearRgbImage img;
    img.width = stored.width;
    img.height = stored.height;
    img.rgb = std::move(stored.rgb);
    img.format = "exr";
    return img;
}

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

LinearRgbImage load_stb(const std::string& path, bool hdr) {
    int w = 0, h = 0, n = 0;
    LinearRgbImage img;
    if (hdr) {
        std::unique_ptr<float, StbFree> px(stbi_loadf(path.c_str(), &w, &h, &n, 3));
        if (!px) throw std::runtime_error(stbi_failure_reason());
        img.rgb.assign(px.get(), px.get() + std::size_t(w) * std::size_t(h) * 3);
        img.format = "hdr";
    } else {
        const bool wide = stbi_is_16_bit(path.c_str()) != 0;
        const std::size_t count = [&] {
            if (wide) {
                std::unique_ptr<stbi_us, StbFree> px(stbi_load_16(path.c_str(), &w, &h, &n, 3));
                if (!px) throw std::runtime_error(stbi_failure_reason());
                const std::size_t k = std::size_t(w) * std::size_t(h) * 3;
                std::vector<float> table(65536);  // one pow per code, not per sample
                for (std::size_t v = 0; v < table.size(); ++v)
                    table[v] = static_cast<float>(srgb_to_linear(double(v) / 65535.0));
                img.rgb.resize(k);
                for (std::size_t i = 0; i < k; ++i) img.rgb[i] = table[px.get()[i]];
                return k;
            }
            std::unique_ptr<stbi_uc, StbFree> px(stbi_load(path.c_str(), &w, &h, &n, 3));
            if (!px) throw std::runtime_error(stbi_failure_reason());
            const std::size_t k = std::size_t(w) * std::size_t(h) * 3;
            float table[256];
            for (int v = 0; v < 256; ++v) table[v] = static_cast<float>(srgb_to_linear(v / 255.0));
            img.rgb.resize(k);
            for (std::size_t i = 0; i < k; ++i) img.rgb[i] = table[px.get()[i]];
            return k;
        }();
        (void)count;
        img.format = "srgb";
    }
    img.width = w;
    img.height = h;
    return img;
}

}  // namespace

LinearRgbImage load_linear_rgb(const std::string& path) {
    try {
        std::FILE* f = std::fopen(path.c_str(), "rb");
        if (!f) throw std::runtime_error(std::strerror(errno));
        unsigned char magic[4] = {0, 0, 0, 0};
        const std::size_t got = std::fread(magic, 1, 4, f);
        std::fclose(f);
        if (got == 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 &&
            magic[3] == 0x01)
            return load_exr(path);
        return load_stb(path, got >= 2 && magic[0] == '#' && magic[1] == '?');
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot read '" + path + "': " + e.what());
    }
}

std::string first_non_finite(const LinearRgbImage& img) {
    const char names[3] = {'R', 'G', 'B'};
    for (std::size_t i = 0; i < img.rgb.size(); ++i) {
        const float v = img.rgb[i];
        if (std::isfinite(v)) continue;
        const std::size_t p = i / 3;
        const std::size_t w = static_cast<std::size_t>(img.width);
        return "pixel (" + std::to_string(p % w) + ", " + std::to_string(p / w) + ") channel " +
               names[i % 3] + " is " + (std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf"));
    }
    return "";
}

}  // namespace sphbasis::cli
