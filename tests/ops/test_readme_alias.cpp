// The README's first example, verbatim in its body, in a translation unit that also has a
// top-level namespace ::sh (as google/spherical-harmonics does): with the alias idiom
// `namespace sb = sphbasis;` it compiles and gives the same irradiance in SH and in the modified
// H-basis. (With `using namespace sphbasis;` every `sh::` here would be ambiguous.)
#include <catch2/catch.hpp>
#include <cmath>
#include <sphbasis/sphbasis.hpp>

// google/spherical-harmonics' namespace, reduced to a name.
namespace sh {
inline double EvalSH(int, int, double) { return 0; }
}  // namespace sh

TEST_CASE("README example: the namespace alias next to a top-level ::sh", "[ops][readme]") {
    namespace sb = sphbasis;  // an alias, not `using namespace`: see below

    auto sky = [](double x, double, double z) { return 1.0 + 0.8 * z + 0.3 * x; };
    const Eigen::VectorXd L = sb::project(sb::evaluator<sb::SH>(9), sky, sb::sphere_rule(16));
    Eigen::VectorXd E(9);
    sb::sh::convolve(3, sb::sh::clamped_cosine_kernel(3, sb::sh::KernelScale::normalized), L, E);
    const Eigen::MatrixXd T = sb::conversion(
        sb::evaluator<sb::SH>(9), sb::evaluator<sb::HBasisMod>(6), sb::hemisphere_rule(8));
    const Eigen::VectorXd H = T * E;
    const double n[3] = {0.3, 0.1, 0.95};
    double e_sh = sb::sh::eval_sum(3, E.data(), n[0], n[1], n[2]);
    double e_hb = sb::basis_eval_sum<sb::HBasisMod>(6, H.data(), n[0], n[1], n[2]);
    // The sky is linear, so its irradiance / pi is exactly 1 + (2/3)(0.8 nz + 0.3 nx) at the
    // unit normal; the modified H-basis spans it over the hemisphere (Ishmukhametov, Listing 2.1).
    const double r = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double want = 1 + 2.0 / 3.0 * (0.8 * n[2] + 0.3 * n[0]) / r;
    CHECK(e_sh == Approx(want).epsilon(1e-12));
    CHECK(e_hb == Approx(want).epsilon(1e-9));
    CHECK(::sh::EvalSH(0, 0, 0.0) == 0);  // google's name is still usable unqualified-ly
}
