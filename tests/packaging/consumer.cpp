// A user program: evaluates SH and checks a value, proving the headers are found and usable.
#include <cmath>
#include <cstdio>
#include <sphbasis/sphbasis.hpp>

int main() {
    double y[9];
    sphbasis::sh::eval(3, 0.0, 0.0, 1.0, y);
    std::printf("y00=%.17g y10=%.17g\n", y[0], y[2]);
    return std::fabs(y[2] - 0.48860251190291992) < 1e-15 ? 0 : 1;
}
