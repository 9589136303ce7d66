// sphbasis CLI support: encode_png (see png.hpp).
#include "png.hpp"

#include <stdexcept>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace sphbasis::cli {

namespace {
void append(void* context, void* data, int size) {
    auto* out = static_cast<std::string*>(context);
    out->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}
}  // namespace

std::string encode_png(const std::vector<std::uint8_t>& pixels, int width, int height,
                       int channels) {
    if (width < 1 || height < 1 || width > 65535 || height > 65535 ||
        !(channels == 1 || channels == 3 || channels == 4) ||
        pixels.size() != std::size_t(width) * std::size_t(height) * std::size_t(channels))
        throw std::invalid_argument(
            "sphbasis::cli::encode_png(): expected width * height * channels bytes (1 <= width, "
            "height <= 65535, channels 1, 3 or 4), got " +
            std::to_string(pixels.size()) + " bytes for " + std::to_string(width) + "x" +
            std::to_string(height) + "x" + std::to_string(channels));
    std::string out;
    if (stbi_write_png_to_func(append, &out, width, height, channels, pixels.data(),
                               width * channels) == 0 ||
        out.empty())
        throw std::runtime_error("cannot encode a PNG image of " + std::to_string(width) + "x" +
                                 std::to_string(height) + " pixels");
    return out;
}

}  // namespace sphbasis::cli
