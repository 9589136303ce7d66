// sphbasis CLI support: load_exr_luminance (see exr.hpp).
#include "exr.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>

#if defined(SPHBASIS_HAVE_OPENEXR)
#include <ImfArray.h>
#include <ImfRgbaFile.h>
#endif

namespace sphbasis::cli {

LuminanceImage load_exr_luminance(const std::string& path) {
#if defined(SPHBASIS_HAVE_OPENEXR)
    Imf::RgbaInputFile file(path.c_str());
    const Imath::Box2i dw = file.dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    if (w < 2 || h < 1) throw std::runtime_error("empty image " + path);
    Imf::Array2D<Imf::Rgba> px(h, w);
    file.setFrameBuffer(&px[0][0] - dw.min.x - static_cast<std::ptrdiff_t>(dw.min.y) * w, 1,
                        static_cast<std::size_t>(w));
    file.readPixels(dw.min.y, dw.max.y);
    LuminanceImage m;
    m.width = w;
    m.height = h;
    m.values.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    auto clamp = [](float v) { return std::isfinite(v) && v > 0 ? static_cast<double>(v) : 0.0; };
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const Imf::Rgba& p = px[j][i];
            m.values[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) +
                     static_cast<std::size_t>(i)] = 0.2126 * clamp(float(p.r)) +
                                                    0.7152 * clamp(float(p.g)) +
                                                    0.0722 * clamp(float(p.b));
        }
    return m;
#else
    throw std::runtime_error("reading " + path + " needs OpenEXR, and this build has none");
#endif
}

}  // namespace sphbasis::cli
