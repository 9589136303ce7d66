// A user program of the evaluation tier (sphbasis::core): every basis, the registry, the
// parameterizations and the shading helpers, with no Eigen anywhere on the include path.
#if __has_include(<Eigen/Core>)
#error "Eigen is reachable from this consumer's include path: the test would prove nothing"
#endif
#include <cmath>
#include <cstdio>
#include <sphbasis/core.hpp>

int main() {
    double y[9];
    sphbasis::sh::eval(3, 0.0, 0.0, 1.0, y);
    const auto& hb = sphbasis::find_basis("hbasis");
    float h[4];
    hb.eval_f(4, 0.0f, 0.0f, 1.0f, h);
    std::printf("y10=%.17g h0=%.9g\n", y[2], static_cast<double>(h[0]));
    return std::fabs(y[2] - 0.48860251190291992) < 1e-15 && std::isfinite(h[0]) ? 0 : 1;
}
