// sphbasis: mathematical constants to full double precision, each with its closed form.
#pragma once

namespace sphbasis::constants {

inline constexpr double pi = 3.14159265358979323846;                 // pi
inline constexpr double two_pi = 6.28318530717958647693;             // 2*pi
inline constexpr double four_pi = 12.5663706143591729539;            // 4*pi
inline constexpr double inv_pi = 0.318309886183790671538;            // 1/pi
inline constexpr double inv_two_pi = 0.159154943091895335769;        // 1/(2*pi)
inline constexpr double inv_four_pi = 0.0795774715459476678845;      // 1/(4*pi)
inline constexpr double sqrt2 = 1.41421356237309504880;              // sqrt(2)
inline constexpr double inv_sqrt2 = 0.707106781186547524401;         // 1/sqrt(2)
inline constexpr double sqrt3 = 1.73205080756887729353;              // sqrt(3)
inline constexpr double sqrt_pi = 1.77245385090551602730;            // sqrt(pi)
inline constexpr double inv_sqrt_pi = 0.564189583547756286948;       // 1/sqrt(pi)
inline constexpr double inv_sqrt_two_pi = 0.398942280401432677940;   // 1/sqrt(2*pi)
inline constexpr double inv_sqrt_four_pi = 0.282094791773878143474;  // 1/(2*sqrt(pi)) = Y00

}  // namespace sphbasis::constants
