// sphbasis CLI support: 8-bit PNG encoding (stb_image_write), in memory, so that a caller can
// write the bytes with the other outputs all or none (support/output_file.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sphbasis::cli {

/// The PNG file bytes of a width x height image of `channels` (1, 3 or 4) bytes per pixel,
/// rows from the top. Throws std::invalid_argument for a size that does not match and
/// std::runtime_error if encoding fails. The bytes depend only on the arguments.
std::string encode_png(const std::vector<std::uint8_t>& pixels, int width, int height,
                       int channels = 3);

}  // namespace sphbasis::cli
