// sphbasis CLI support: OpenEXR input and output (see exr.hpp).
#include "exr.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>

#include "output_file.hpp"

#if defined(SPHBASIS_HAVE_OPENEXR)
#include <ImfArray.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>
#include <half.h>
#endif

namespace sphbasis::cli {

bool have_openexr() noexcept {
#if defined(SPHBASIS_HAVE_OPENEXR)
    return true;
#else
    return false;
#endif
}

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

RgbImage read_exr_rgb_as_stored(const std::string& path) {
#if defined(SPHBASIS_HAVE_OPENEXR)
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
    const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
    if (w < 1 || h < 1 || w > (1 << 20) || h > (1 << 20))
        throw std::runtime_error("expected 1 to 2^20 pixels a side, got " + std::to_string(w) +
                                 " x " + std::to_string(h));
    const Imf::ChannelList& ch = file.header().channels();
    const bool grey = ch.findChannel("R") == nullptr && ch.findChannel("Y") != nullptr;
    RgbImage img;
    img.width = static_cast<int>(w);
    img.height = static_cast<int>(h);
    img.rgb.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3, 0.0f);
    const std::size_t xs = 3 * sizeof(float), ys = xs * static_cast<std::size_t>(w);
    char* base = reinterpret_cast<char*>(img.rgb.data()) -
                 static_cast<std::ptrdiff_t>(dw.min.x) * static_cast<std::ptrdiff_t>(xs) -
                 static_cast<std::ptrdiff_t>(dw.min.y) * static_cast<std::ptrdiff_t>(ys);
    Imf::FrameBuffer fb;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < (grey ? 1 : 3); ++c)
        fb.insert(grey ? "Y" : names[c],
                  Imf::Slice(Imf::FLOAT, base + c * static_cast<std::ptrdiff_t>(sizeof(float)), xs,
                             ys, 1, 1, 0.0));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    if (grey)
        for (std::size_t i = 0; i < img.rgb.size(); i += 3)
            img.rgb[i + 1] = img.rgb[i + 2] = img.rgb[i];
    return img;
#else
    (void)path;
    throw std::runtime_error("reading EXR needs OpenEXR, and this build has none");
#endif
}

RgbImage load_exr_rgb(const std::string& path) {
    try {
        RgbImage img = read_exr_rgb_as_stored(path);
        for (float& v : img.rgb)
            if (!(std::isfinite(v) && v > 0)) v = 0.0f;
        return img;
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot read EXR '" + path + "': " + e.what());
    }
}

#if defined(SPHBASIS_HAVE_OPENEXR)
namespace {
/// An OpenEXR output stream into memory, so that an image joins the other outputs of a command
/// in one all-or-none commit (support/output_file.hpp) without a file of its own.
class MemoryStream : public Imf::OStream {
  public:
    MemoryStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        const std::size_t end = pos_ + static_cast<std::size_t>(n);
        if (end > bytes_.size()) bytes_.resize(end);
        std::memcpy(&bytes_[pos_], c, static_cast<std::size_t>(n));
        pos_ = end;
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = static_cast<std::size_t>(pos); }
    std::string take() { return std::move(bytes_); }

  private:
    std::string bytes_;
    std::size_t pos_ = 0;
};
}  // namespace
#endif

std::string encode_exr(int width, int height, const std::vector<std::string>& names,
                       const std::vector<float>& values, bool half) {
    const std::size_t nc = names.size();
    if (width < 1 || height < 1 || nc == 0 ||
        values.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * nc)
        throw std::invalid_argument(
            "sphbasis::cli::encode_exr(): expected width * "
            "height * channels values");
#if defined(SPHBASIS_HAVE_OPENEXR)
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer fb;
    const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;
    const std::size_t size = half ? sizeof(Imath::half) : sizeof(float);
    std::vector<Imath::half> halves;  // each value rounded to the nearest half
    if (half) halves.assign(values.begin(), values.end());
    const std::size_t xs = nc * size, ys = xs * static_cast<std::size_t>(width);
    char* base = half ? reinterpret_cast<char*>(halves.data())
                      : reinterpret_cast<char*>(const_cast<float*>(values.data()));
    for (std::size_t k = 0; k < nc; ++k) {
        header.channels().insert(names[k], Imf::Channel(type));
        fb.insert(names[k], Imf::Slice(type, base + k * size, xs, ys));
    }
    MemoryStream stream;
    {
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(fb);
        file.writePixels(height);
    }
    return stream.take();
#else
    (void)half;
    throw std::runtime_error("writing an EXR image needs OpenEXR, and this build has none");
#endif
}

void write_exr_channels(const std::string& path, int width, int height,
                        const std::vector<std::string>& names, const std::vector<float>& values) {
    std::string bytes;
    try {
        bytes = encode_exr(width, height, names, values);
    } catch (const std::invalid_argument&) {
        throw;
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot write '" + path + "': " + e.what());
    }
    write_file_atomic(path, bytes);
}

}  // namespace sphbasis::cli
