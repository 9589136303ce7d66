// sphbasis CLI support: environment map images as linear RGB, read as they are (no clamping):
// OpenEXR (R, G, B as float; a Y-only file as grey), Radiance HDR (stb_image, linear), and PNG /
// JPEG / other 8- and 16-bit images of stb_image (sRGB-encoded, decoded to linear by the exact
// piecewise sRGB curve of IEC 61966-2-1). The format is chosen by the file's first bytes (EXR's
// magic number 76 2f 31 01, HDR's "#?"), not its name.
#pragma once

#include <string>
#include <vector>

namespace sphbasis::cli {

/// A linear RGB image, row-major from the top row, 3 floats per pixel.
struct LinearRgbImage {
    int width = 0, height = 0;
    std::vector<float> rgb;  // width * height * 3
    std::string format;      // "exr", "hdr" or "srgb"
};

/// Reads an image as described in the file comment. Throws std::runtime_error "cannot read
/// '<path>': <reason>" when the file is missing or unreadable, of a format that cannot be
/// decoded, or (for EXR) this build has no OpenEXR.
LinearRgbImage load_linear_rgb(const std::string& path);

/// The sRGB transfer function inverted (IEC 61966-2-1): v / 12.92 up to 0.04045, else
/// ((v + 0.055) / 1.055)^2.4; v in [0, 1].
double srgb_to_linear(double v);

/// The first non-finite value of an image as "pixel (x, y) channel C is nan|inf|-inf", or "".
std::string first_non_finite(const LinearRgbImage& img);

}  // namespace sphbasis::cli
