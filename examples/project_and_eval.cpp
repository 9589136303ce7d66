// Example: project a function of direction onto SH, convert it to the modified H-basis over the
// hemisphere (Ishmukhametov, "Irradiance Normal Mapping" (thesis), Listing 2.1), and evaluate
// both at a normal, as a shader's CPU mirror would.
#include <cmath>
#include <cstdio>
#include <sphbasis/sphbasis.hpp>

namespace sb = sphbasis;  // an alias, not `using namespace`: see the README, "Use it"

int main() {
    // Radiance: a sky brighter towards +z and +x.
    auto sky = [](double x, double, double z) { return 1.0 + 0.8 * z + 0.3 * x; };
    const auto rule = sb::sphere_rule(16);  // exact for degree <= 16
    const Eigen::VectorXd L =
        sb::project(sb::evaluator<sb::SH>(9), sky, rule);  // 3 bands, 9 coefficients
    // Irradiance / pi: the normalised clamped-cosine factors a_l = 1, 2/3, 1/4 per band.
    Eigen::VectorXd E(9);
    sb::sh::convolve(3, sb::sh::clamped_cosine_kernel(3, sb::sh::KernelScale::normalized), L, E);
    const Eigen::MatrixXd T = sb::conversion(
        sb::evaluator<sb::SH>(9), sb::evaluator<sb::HBasisMod>(6), sb::hemisphere_rule(8));
    const Eigen::VectorXd H = T * E;       // 6 modified H-basis coefficients
    const double n[3] = {0.3, 0.1, 0.95};  // a tangent-space normal
    std::printf("SH-9 irradiance %.6f, modified H-basis-6 %.6f\n",
                sb::sh::eval_sum(3, E.data(), n[0], n[1], n[2]),
                sb::basis_eval_sum<sb::HBasisMod>(6, H.data(), n[0], n[1], n[2]));
    return 0;
}
