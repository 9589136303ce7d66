// Tests for core/simd.hpp and core/vec.hpp: batch lanes match scalar operations.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <sphbasis/core/simd.hpp>
#include <sphbasis/core/vec.hpp>

using namespace sphbasis;

TEMPLATE_TEST_CASE("simd: lane-wise operations equal scalar ones", "[simd]", float, double) {
    using T = TestType;
    using V = batch<T>;
    T a[V::size], b[V::size];
    for (int i = 0; i < V::size; ++i) {
        a[i] = T(i % 3 == 0 ? -0.0 : (i % 2 ? -1.5 * i : 0.25 * i));
        b[i] = T(0.5 - i);
    }
    const V va = V::load(a), vb = V::load(b);
    const V ab = vabs(va), mx = vmax(va, vb), mn = vmin(va, vb), sq = vsqrt(vabs(vb));
    const V sel = select(va < vb, va, vb), neg = V(T(-0.0));
    for (int i = 0; i < V::size; ++i) {
        CHECK(ab[i] == std::fabs(a[i]));
        CHECK(!std::signbit(ab[i]));
        CHECK(mx[i] == std::max(a[i], b[i]));
        CHECK(mn[i] == std::min(a[i], b[i]));
        CHECK(sq[i] == std::sqrt(std::fabs(b[i])));
        CHECK(sel[i] == (a[i] < b[i] ? a[i] : b[i]));
        CHECK(std::signbit(neg[i]));  // broadcast keeps the sign of zero
    }
}

TEMPLATE_TEST_CASE("vec: normalize_or_pole, scalar and batch", "[simd]", float, double) {
    using T = TestType;
    using V = batch<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
    const T dn = std::numeric_limits<T>::denorm_min(), big = std::numeric_limits<T>::max();
    const T in[][3] = {{0, 0, 0},  {nan, 0, 1},     {0, inf, 0}, {3, 4, 0},
                       {dn, 0, 0}, {big, big, big}, {0, -2, 0},  {-0.2f, 0.3f, -0.5f}};
    const int n = sizeof in / sizeof in[0];
    for (int i = 0; i < n; ++i) {
        T x = in[i][0], y = in[i][1], z = in[i][2];
        normalize_or_pole(x, y, z);
        REQUIRE(std::isfinite(x));
        REQUIRE(std::isfinite(y));
        REQUIRE(std::isfinite(z));
        CHECK(std::fabs(x * x + y * y + z * z - 1) <= 4 * std::numeric_limits<T>::epsilon());
        // The same through every lane of a batch, which uses a refined reciprocal-sqrt
        // estimate: within 2 ulp of the scalar result (documented in vec.hpp).
        V bx(in[i][0]), by(in[i][1]), bz(in[i][2]);
        normalize_or_pole(bx, by, bz);
        const T tol = 2 * std::numeric_limits<T>::epsilon();
        for (int j = 0; j < V::size; ++j) {
            CHECK(std::fabs(bx[j] - x) <= tol);
            CHECK(std::fabs(by[j] - y) <= tol);
            CHECK(std::fabs(bz[j] - z) <= tol);
        }
    }
    T x = 0, y = 0, z = 0;
    normalize_or_pole(x, y, z);
    CHECK((x == 0 && y == 0 && z == 1));
    x = 3, y = 4, z = 0;
    normalize_or_pole(x, y, z);
    CHECK(x == Approx(0.6));
    CHECK(y == Approx(0.8));
}

TEMPLATE_TEST_CASE("simd: all and any see every lane", "[simd]", float, double) {
    using T = TestType;
    using V = batch<T>;
    T a[V::size];
    for (int i = 0; i < V::size; ++i) a[i] = T(1);
    CHECK(all(V::load(a) > V(T(0))));
    CHECK(any(V::load(a) > V(T(0))));
    CHECK(!any(V::load(a) < V(T(0))));
    // One lane differs, at every position: all() must see it false, any() true.
    for (int j = 0; j < V::size; ++j) {
        T b[V::size];
        for (int i = 0; i < V::size; ++i) b[i] = i == j ? T(-1) : T(1);
        const V vb = V::load(b);
        INFO("lane " << j);
        CHECK(!all(vb > V(T(0))));
        CHECK(any(vb < V(T(0))));
        CHECK(!all(vb < V(T(0))));
    }
    // NaN compares false in every ordered comparison.
    T c[V::size];
    for (int i = 0; i < V::size; ++i)
        c[i] = i == V::size - 1 ? std::numeric_limits<T>::quiet_NaN() : T(1);
    CHECK(!all(V::load(c) > V(T(0))));
    CHECK(!all(V::load(c) <= V(T(0))));
}
