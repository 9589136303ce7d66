// sphbasis CLI support: reading environment maps and textures, writing bake outputs. File
// formats live in the tool, not in the library: the library takes the pixels (e.g.
// imse::LatLongMap, render::Environment).
#pragma once

#include <string>
#include <vector>

namespace sphbasis::cli {

/// One channel of a lat-long image, row-major from the top row (row 0 at the north pole).
struct LuminanceImage {
    int width = 0, height = 0;
    std::vector<double> values;  // width * height
};

/// Luminance (Rec. 709: 0.2126 R + 0.7152 G + 0.0722 B) of an OpenEXR image, each channel
/// clamped to >= 0 first (lossy compressions such as DWAB leave small negative values) and
/// non-finite values taken as 0. Throws std::runtime_error if the file cannot be read, is
/// narrower than 2 pixels, or this build has no OpenEXR.
LuminanceImage load_exr_luminance(const std::string& path);

/// A linear RGB float image, row-major from the top row, 3 floats per pixel.
struct RgbImage {
    int width = 0, height = 0;
    std::vector<float> rgb;  // width * height * 3
};

/// The R, G, B channels of an OpenEXR image as float (a file with only a Y channel is read as
/// grey; missing channels are 0). Negative values are clamped to 0 and non-finite values
/// become 0 (radiance is non-negative; lossy compressions undershoot). Throws
/// std::runtime_error "cannot read EXR 'path': ..." if the file cannot be read, or this build
/// has no OpenEXR.
RgbImage load_exr_rgb(const std::string& path);

/// The R, G, B channels of an OpenEXR image as stored, as float (a file with only a Y channel
/// is read as grey; missing channels are 0): nothing clamped, non-finite values kept (the
/// caller decides). Throws std::runtime_error with OpenEXR's message, or "expected 1 to 2^20
/// pixels a side", or when this build has no OpenEXR. load_exr_rgb is this one, cleaned.
RgbImage read_exr_rgb_as_stored(const std::string& path);

/// A multi-channel float (32-bit) OpenEXR image with ZIP compression, as the bytes of its file:
/// channel k of pixel (x, y) (y down from the top row) at values[(y * width + x) *
/// names.size() + k]. The bytes depend only on the arguments (no time stamp in the header), so
/// equal images give equal files. Note that OpenEXR stores channels sorted by name. Throws
/// std::invalid_argument on a size mismatch and std::runtime_error if the encoding fails or
/// this build has no OpenEXR. `half`: 16-bit half channels (each value rounded to the nearest
/// half) instead of float.
std::string encode_exr(int width, int height, const std::vector<std::string>& names,
                       const std::vector<float>& values, bool half = false);

/// encode_exr() written to `path` by write_file_atomic (support/output_file.hpp). Throws
/// std::runtime_error on failure.
void write_exr_channels(const std::string& path, int width, int height,
                        const std::vector<std::string>& names, const std::vector<float>& values);

/// True when this build reads and writes OpenEXR.
bool have_openexr() noexcept;

}  // namespace sphbasis::cli
