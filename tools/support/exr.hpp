// sphbasis CLI support: reading environment maps. File formats live in the tool, not in the
// library: the library takes the pixels (e.g. imse::LatLongMap).
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

}  // namespace sphbasis::cli
