// Compiled by the packaging_warnings test as a user would, with g++/clang++ -O2 -Wall -Wextra
// -Wconversion -Werror and none of the project's own warning suppressions: warnings the headers
// give users are ours. Instantiates the templates that once warned at -O1+ ('o' and 'mu[0]'
// may be used uninitialized in sh_rotation.hpp and sh_product.hpp).
#include <sphbasis/sphbasis.hpp>
#include <vector>

int main() {
    using namespace sphbasis;
    std::vector<double> a(64, 0.5), b(64, 0.25), c(64);
    std::vector<float> af(64, 0.5f), cf(64);
    sh::rotate_z(8, 0.3, a, c);
    sh::rotate_z(8, 0.3f, af, cf);
    sh::rotate_quaternion(8, 0.9, 0.1, 0.2, 0.3, a, c);
    sh::rotate_zyz(8, 0.1, 0.2, 0.3, a, c);
    sh::rotate_z90(8, 1, a, c);
    const auto rot = sh::rotation_from_quaternion(8, 0.9, 0.1, 0.2, 0.3);
    rot.apply(a, c);
    sh::product(8, a, b, c);
    sh::product<3>(a.data(), b.data(), c.data());
    sh::product(4, a, 4, b, 7, c);
    sh::eval(8, 0.1, 0.2, 0.9, c.data());
    sh::eval<4>(0.1f, 0.2f, 0.9f, cf.data());
    sh::convolve(8, a, b, c);
    return c[0] > 1e300 ? 1 : 0;
}
