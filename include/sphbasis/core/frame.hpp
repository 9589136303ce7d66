// sphbasis: tangent frames, 3x3 rotation matrices and quaternions, and the adapters through
// which GLM and Eigen matrices and quaternions enter the library (standard library only).
//
//   * Frame<T>: an orthonormal frame (s, t, n) with to_local / to_world and the spherical
//     coordinate helpers of the local frame, after Mitsuba 3's core/frame.h. Built from a unit
//     normal by the branchless orthonormal basis of Duff, Burgess, Christensen, Hery, Kensler,
//     Liani and Villemin, "Building an Orthonormal Basis, Revisited" (JCGT 6(1), 2017,
//     Listing 3): coordinate_system(n, s, t).
//   * Mat3<T>: a ROW-MAJOR 3x3 matrix, std::array<T, 9>, entry (i, j) at 3 i + j. A rotation R
//     acts on column vectors, v' = R v.
//   * Quat<T>: a quaternion (w, x, y, z), w the scalar part; the rotation of a unit quaternion
//     is active and right-handed, v' = q v q*. quaternion_of() converts a matrix by Shepperd's
//     method (S. W. Shepperd, "Quaternion from Rotation Matrix", J. Guidance and Control 1(3),
//     1978, 223).
//   * frame_to_normal(n): the minimal rotation taking +z to n (the tangent frame of Sloan,
//     Lehtinen and Kautz, "Precomputed Radiance Transfer: Theory and Practice", SIGGRAPH 2005
//     course, "Normal Mapping for PRT"). It equals Frame(n) for n_z >= 0 and, unlike it, stays
//     continuous into n_z < 0.
//
// Types users hold (read without including GLM or Eigen; to_mat3() and to_quat()):
//   * std::array<T, 9>      row-major, r[3 i + j] = R_ij;
//   * glm::mat3 / dmat3     COLUMN-major, read as m[col][row] (GLM's own convention, so a glm
//                           matrix means the same rotation here as in GLM); detected by its
//                           col_type / row_type members;
//   * Eigen::Matrix3f/d     read as m(row, col) (any storage order; dynamic matrices must be
//                           3x3 at run time); detected by rows(), cols() and m(i, j);
//   * quaternions           glm::quat / dquat (members w, x, y, z), Eigen::Quaternionf/d
//                           (w(), x(), y(), z()), sphbasis::Quat: read BY NAME, whatever the
//                           storage order (GLM and Eigen store x, y, z, w; both construct from
//                           (w, x, y, z)).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

#include "../config.hpp"
#include "contiguous.hpp"
#include "error.hpp"
#include "vec.hpp"

namespace sphbasis {

/// A row-major 3x3 matrix: entry (i, j) at 3 i + j.
template <class T>
using Mat3 = std::array<T, 9>;

/// A quaternion (w, x, y, z), w the scalar part.
template <class T>
struct Quat {
    T w, x, y, z;
};
using Quatf = Quat<float>;
using Quatd = Quat<double>;

// ---------------------------------------------------------------------------------------------
// Frames

/// An orthonormal basis (s, t, n) built from a unit normal n by the branchless method of
/// Duff et al. (JCGT 2017, Listing 3): with sign = copysign(1, n_z), a = -1/(sign + n_z),
/// b = n_x n_y a,
///   s = (1 + sign n_x^2 a, sign b, -sign n_x),   t = (b, sign + n_y^2 a, -n_y),
/// right-handed (s x t = n), exact at n = +-z and accurate to a few ulp everywhere; it
/// switches branch (and jumps) at n_z = 0. No normalisation: n must be unit length.
template <class T>
void coordinate_system(const vec3<T>& n, vec3<T>& s, vec3<T>& t) noexcept {
    const T sign = std::copysign(T(1), n.z);
    const T a = T(-1) / (sign + n.z);
    const T b = n.x * n.y * a;
    s = {T(1) + sign * n.x * n.x * a, sign * b, -sign * n.x};
    t = {b, sign + n.y * n.y * a, -n.y};
}

/// A tangent frame: local coordinates (x, y, z) along (s, t, n), as Mitsuba 3's Frame.
/// Local directions have the pole n at z, the convention of every basis in this library.
template <class T>
struct Frame {
    static_assert(std::is_floating_point_v<T>, "sphbasis::Frame: T is float or double.");
    vec3<T> s{T(1), T(0), T(0)}, t{T(0), T(1), T(0)}, n{T(0), T(0), T(1)};

    /// The identity frame (s, t, n) = (x, y, z).
    Frame() = default;
    /// An explicit frame; the caller keeps it orthonormal.
    Frame(const vec3<T>& s_, const vec3<T>& t_, const vec3<T>& n_) noexcept : s(s_), t(t_), n(n_) {}
    /// The frame of a unit normal (any 3-vector type) by coordinate_system().
    template <class D, std::enable_if_t<!std::is_same_v<D, Frame>, int> = 0>
    explicit Frame(const D& normal) noexcept
        : n{T(component<0>(normal)), T(component<1>(normal)), T(component<2>(normal))} {
        coordinate_system(n, s, t);
    }

    /// World -> local: (v.s, v.t, v.n). v is any 3-vector type.
    template <class D>
    vec3<T> to_local(const D& v) const noexcept {
        const vec3<T> w{T(component<0>(v)), T(component<1>(v)), T(component<2>(v))};
        return {dot(w, s), dot(w, t), dot(w, n)};
    }
    /// Local -> world: x s + y t + z n. v is any 3-vector type.
    template <class D>
    vec3<T> to_world(const D& v) const noexcept {
        const T x = T(component<0>(v)), y = T(component<1>(v)), z = T(component<2>(v));
        return {s.x * x + t.x * y + n.x * z, s.y * x + t.y * y + n.y * z,
                s.z * x + t.z * y + n.z * z};
    }
    /// The rotation matrix of to_world (columns s, t, n); its transpose is to_local.
    Mat3<T> matrix() const noexcept { return {s.x, t.x, n.x, s.y, t.y, n.y, s.z, t.z, n.z}; }

    // Spherical coordinates of a LOCAL unit direction v (theta from n, phi from s).
    static T cos_theta(const vec3<T>& v) noexcept { return v.z; }
    static T cos_theta_2(const vec3<T>& v) noexcept { return v.z * v.z; }
    static T sin_theta_2(const vec3<T>& v) noexcept { return v.x * v.x + v.y * v.y; }
    static T sin_theta(const vec3<T>& v) noexcept { return std::sqrt(sin_theta_2(v)); }
    /// cos(phi), sin(phi); (1, 0) at the pole.
    static T cos_phi(const vec3<T>& v) noexcept {
        T s_, c, sn;
        polar_xy(v.x, v.y, s_, c, sn);
        return c;
    }
    static T sin_phi(const vec3<T>& v) noexcept {
        T s_, c, sn;
        polar_xy(v.x, v.y, s_, c, sn);
        return sn;
    }
};

// ---------------------------------------------------------------------------------------------
// 3x3 matrices and quaternions

namespace detail {

template <class T>
constexpr T default_orthonormal_tolerance() noexcept {
    // 256 ulp for float (3e-5); for double 1e-6, loose enough for matrices that passed
    // through float once. The check catches scaled, sheared and non-rotation input.
    return std::is_same_v<T, float> ? T(256) * std::numeric_limits<T>::epsilon() : T(1e-6);
}

/// Throws unless R is orthogonal within tol (max |R R^T - I| <= tol, all entries finite):
/// "sphbasis::fn(): expected an orthonormal 3x3 matrix (max |R R^T - I| <= tol), got ...".
template <class T>
void check_orthonormal(const Mat3<T>& r, T tol, const char* fn) {
    T worst = 0;
    bool finite = true;
    for (T v : r) finite = finite && std::isfinite(v);
    if (finite) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                T s = 0;
                for (int k = 0; k < 3; ++k)
                    s += r[static_cast<std::size_t>(3 * i + k)] *
                         r[static_cast<std::size_t>(3 * j + k)];
                const T e = std::fabs(s - (i == j ? T(1) : T(0)));
                worst = e > worst ? e : worst;
            }
    }
    if (!finite || !(worst <= tol))
        throw_invalid(
            fn, "an orthonormal 3x3 matrix (max |R R^T - I| <= " +
                    std::to_string(static_cast<double>(tol)) + "), got " +
                    (finite ? "max |R R^T - I| = " + std::to_string(static_cast<double>(worst))
                            : std::string("a non-finite entry")));
}

}  // namespace detail

/// Quaternion of the proper part of an orthogonal matrix by Shepperd's method (the largest of
/// w, x, y, z from the diagonal, the others from off-diagonal sums; no cancellation), then
/// normalised, which also projects a slightly non-orthonormal matrix onto a rotation. Computed
/// in double. improper is set when det(R) < 0; the quaternion is then that of -R.
template <class T>
Quatd quaternion_of(const Mat3<T>& r, bool& improper) noexcept {
    double m[9];
    for (std::size_t i = 0; i < 9; ++i) m[i] = static_cast<double>(r[i]);
    const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                       m[2] * (m[3] * m[7] - m[4] * m[6]);
    improper = det < 0;
    if (improper)
        for (double& v : m) v = -v;
    const double tr = m[0] + m[4] + m[8];
    Quatd q;
    if (tr >= m[0] && tr >= m[4] && tr >= m[8]) {
        const double w = 0.5 * std::sqrt(1 + tr), f = 0.25 / w;
        q = {w, (m[7] - m[5]) * f, (m[2] - m[6]) * f, (m[3] - m[1]) * f};
    } else if (m[0] >= m[4] && m[0] >= m[8]) {
        const double x = 0.5 * std::sqrt(1 + m[0] - m[4] - m[8]), f = 0.25 / x;
        q = {(m[7] - m[5]) * f, x, (m[1] + m[3]) * f, (m[2] + m[6]) * f};
    } else if (m[4] >= m[8]) {
        const double y = 0.5 * std::sqrt(1 - m[0] + m[4] - m[8]), f = 0.25 / y;
        q = {(m[2] - m[6]) * f, (m[1] + m[3]) * f, y, (m[5] + m[7]) * f};
    } else {
        const double z = 0.5 * std::sqrt(1 - m[0] - m[4] + m[8]), f = 0.25 / z;
        q = {(m[3] - m[1]) * f, (m[2] + m[6]) * f, (m[5] + m[7]) * f, z};
    }
    const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    return {q.w / n, q.x / n, q.y / n, q.z / n};
}

/// The unit quaternion of a rotation matrix (quaternion_of() in T; for det(R) < 0, that of -R).
template <class T>
Quat<T> quaternion_from_matrix(const Mat3<T>& r) noexcept {
    bool improper = false;
    const Quatd q = quaternion_of(r, improper);
    return {T(q.w), T(q.x), T(q.y), T(q.z)};
}

/// Rotation matrix of the quaternion (w, x, y, z) (active, right-handed: v' = q v q*).
/// A non-unit quaternion is normalised (q and s q, s != 0, are the same rotation); a zero or
/// non-finite quaternion throws std::invalid_argument.
template <class T>
Mat3<T> matrix_from_quaternion(T w, T x, T y, T z) {
    static_assert(std::is_floating_point_v<T>,
                  "sphbasis::matrix_from_quaternion: T is float or double.");
    if (!std::isfinite(w) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        detail::throw_invalid("matrix_from_quaternion", "a finite non-zero quaternion");
    // Scale by the largest magnitude first, so that quaternions of any finite size (1e-310
    // or 1e300 per component) normalise instead of under- or overflowing in the squared norm.
    const T big =
        std::fmax(std::fmax(std::fabs(w), std::fabs(x)), std::fmax(std::fabs(y), std::fabs(z)));
    if (!(big > T(0)))
        detail::throw_invalid("matrix_from_quaternion", "a finite non-zero quaternion");
    w /= big, x /= big, y /= big, z /= big;
    const T n2 = w * w + x * x + y * y + z * z;
    const T s = T(2) / n2;
    return {T(1) - s * (y * y + z * z), s * (x * y - w * z),        s * (x * z + w * y),
            s * (x * y + w * z),        T(1) - s * (x * x + z * z), s * (y * z - w * x),
            s * (x * z - w * y),        s * (y * z + w * x),        T(1) - s * (x * x + y * y)};
}

/// Rotation matrix for ZYZ Euler angles (radians): R = Rz(alpha) Ry(beta) Rz(gamma), active
/// right-handed rotations about the fixed axes (first gamma about z, then beta about y, then
/// alpha about z), the convention of Wigner's D(alpha, beta, gamma).
template <class T>
Mat3<T> matrix_from_euler_zyz(T alpha, T beta, T gamma) {
    const T ca = std::cos(alpha), sa = std::sin(alpha);
    const T cb = std::cos(beta), sb = std::sin(beta);
    const T cg = std::cos(gamma), sg = std::sin(gamma);
    return {ca * cb * cg - sa * sg,
            -ca * cb * sg - sa * cg,
            ca * sb,
            sa * cb * cg + ca * sg,
            -sa * cb * sg + ca * cg,
            sa * sb,
            -sb * cg,
            sb * sg,
            cb};
}

/// Rotation by angle (radians) about the z axis: [[c, -s, 0], [s, c, 0], [0, 0, 1]].
template <class T>
Mat3<T> matrix_rotation_z(T angle) {
    const T c = std::cos(angle), s = std::sin(angle);
    return {c, -s, T(0), s, c, T(0), T(0), T(0), T(1)};
}

/// Exact rotation by k quarter turns (k * 90 degrees, right-handed) about axis 0 (x), 1 (y) or
/// 2 (z): entries are exactly 0 and +-1. Throws std::invalid_argument for another axis.
template <class T>
Mat3<T> matrix_90(int axis, int quarter_turns) {
    if (axis < 0 || axis > 2)
        detail::throw_invalid("matrix_90",
                              "axis 0 (x), 1 (y) or 2 (z), got " + std::to_string(axis));
    const int k = ((quarter_turns % 4) + 4) % 4;
    constexpr int cs[4] = {1, 0, -1, 0}, sn[4] = {0, 1, 0, -1};
    const T c = T(cs[k]), s = T(sn[k]);
    if (axis == 0) return {T(1), T(0), T(0), T(0), c, -s, T(0), s, c};
    if (axis == 1) return {c, T(0), s, T(0), T(1), T(0), -s, T(0), c};
    return {c, -s, T(0), s, c, T(0), T(0), T(0), T(1)};
}

/// The rotation taking +z to the unit normal n (normalised first; a zero or non-finite n is
/// taken as +z): the minimal rotation, about the axis z x n by the angle acos(n_z). Its columns
/// are the tangent frame (t, b, n): R e_x = t, R e_y = b, R e_z = n, with
///   t = (1 - x^2 q, -x y q, -x),  b = (-x y q, 1 - y^2 q, -y),  q = 1/(1 + z) = (1 - z)/(x^2+y^2),
/// the second form used for z < 0 so that nothing cancels. This is the frame of Duff et al.
/// (JCGT 2017), Frame(n).matrix(), for z >= 0 and stays continuous into z < 0; at exactly
/// n = -z it is the half turn about x, diag(1, -1, -1) (the limit depends on the approach
/// direction there). To take world-space lighting into the tangent frame (the R of Sloan,
/// Lehtinen and Kautz 2005, e(n) = y(n)^T C R M l), apply the transpose.
template <class T>
Mat3<T> frame_to_normal(T nx, T ny, T nz) noexcept {
    double x = nx, y = ny, z = nz;
    normalize_or_pole(x, y, z);
    const double r2 = x * x + y * y;
    if (!(r2 > 0)) {
        if (z > 0) return {T(1), T(0), T(0), T(0), T(1), T(0), T(0), T(0), T(1)};
        return {T(1), T(0), T(0), T(0), T(-1), T(0), T(0), T(0), T(-1)};
    }
    const double q = z >= 0 ? 1 / (1 + z) : (1 - z) / r2;
    return {T(1 - x * x * q),
            T(-x * y * q),
            T(x),
            T(-x * y * q),
            T(1 - y * y * q),
            T(y),
            T(-x),
            T(-y),
            T(z)};
}

/// frame_to_normal() of any 3-vector type (glm::vec3, Eigen::Vector3d, vec3).
template <class D, std::enable_if_t<!std::is_arithmetic_v<D>, int> = 0>
Mat3<direction_scalar_t<D>> frame_to_normal(const D& n) noexcept {
    return frame_to_normal(component<0>(n), component<1>(n), component<2>(n));
}

/// The rotation whose columns are the orthonormal frame (t, b, n): R e_x = t, R e_y = b,
/// R e_z = n, i.e. tangent space to world. Throws std::invalid_argument unless the frame is
/// orthonormal within `tolerance` (a left-handed frame, det = -1, is accepted).
template <class T>
Mat3<T> matrix_from_frame(const vec3<T>& t, const vec3<T>& b, const vec3<T>& n,
                          T tolerance = detail::default_orthonormal_tolerance<T>()) {
    Mat3<T> r = {t.x, b.x, n.x, t.y, b.y, n.y, t.z, b.z, n.z};
    detail::check_orthonormal(r, tolerance, "matrix_from_frame");
    return r;
}

/// The product a b of two 3x3 matrices.
template <class T>
Mat3<T> multiply(const Mat3<T>& a, const Mat3<T>& b) noexcept {
    Mat3<T> c{};
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j)
            c[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
    return c;
}

/// The product R v of a matrix and a column vector.
template <class T>
vec3<T> multiply(const Mat3<T>& r, const vec3<T>& v) noexcept {
    return {r[0] * v.x + r[1] * v.y + r[2] * v.z, r[3] * v.x + r[4] * v.y + r[5] * v.z,
            r[6] * v.x + r[7] * v.y + r[8] * v.z};
}

/// The transpose (the inverse of a rotation).
template <class T>
Mat3<T> transpose(const Mat3<T>& a) noexcept {
    return {a[0], a[3], a[6], a[1], a[4], a[7], a[2], a[5], a[8]};
}

// ---------------------------------------------------------------------------------------------
// Adapters: matrices and quaternions of other libraries (see the header comment)

namespace detail {
template <class M, class = void>
struct is_glm_mat : std::false_type {};
template <class M>
struct is_glm_mat<M, std::void_t<typename M::col_type, typename M::row_type,
                                 decltype(std::declval<const M&>()[0][0])>> : std::true_type{};
template <class M, class = void>
struct is_eigen_mat : std::false_type {};
template <class M>
struct is_eigen_mat<M, std::void_t<decltype(std::declval<const M&>().rows()),
                                   decltype(std::declval<const M&>().cols()),
                                   decltype(std::declval<const M&>()(0, 0))>> : std::true_type {};
template <class M>
struct is_row_major_array : std::false_type {};
template <class T>
struct is_row_major_array<std::array<T, 9>> : std::is_floating_point<T> {};
template <class Q, class = void>
struct has_member_wxyz : std::false_type {};
template <class Q>
struct has_member_wxyz<
    Q, std::void_t<decltype(std::declval<const Q&>().w), decltype(std::declval<const Q&>().x),
                   decltype(std::declval<const Q&>().y), decltype(std::declval<const Q&>().z)>>
    : std::true_type {};
template <class Q, class = void>
struct has_call_wxyz : std::false_type {};
template <class Q>
struct has_call_wxyz<
    Q, std::void_t<decltype(std::declval<const Q&>().w()), decltype(std::declval<const Q&>().x()),
                   decltype(std::declval<const Q&>().y()), decltype(std::declval<const Q&>().z())>>
    : std::true_type {};
}  // namespace detail

/// True for the 3x3 matrix types to_mat3() reads: std::array<T, 9> (row-major), glm::mat3 /
/// dmat3 (column-major) and Eigen matrices (m(row, col)).
template <class M>
inline constexpr bool is_matrix3_v = detail::is_row_major_array<M>::value ||
                                     detail::is_glm_mat<M>::value || detail::is_eigen_mat<M>::value;

/// True for the quaternion types to_quat() reads (w, x, y, z by name; not a matrix).
template <class Q>
inline constexpr bool is_quaternion_v =
    !is_matrix3_v<Q> && (detail::has_member_wxyz<Q>::value || detail::has_call_wxyz<Q>::value);

namespace detail {
template <class M>
auto matrix_entry_probe() {
    if constexpr (is_row_major_array<M>::value)
        return typename M::value_type{};
    else if constexpr (is_glm_mat<M>::value)
        return std::decay_t<decltype(std::declval<const M&>()[0][0])>{};
    else if constexpr (is_eigen_mat<M>::value)
        return std::decay_t<decltype(std::declval<const M&>()(0, 0))>{};
    else
        return double{};
}
template <class Q>
auto quaternion_entry_probe() {
    if constexpr (has_member_wxyz<Q>::value)
        return std::decay_t<decltype(std::declval<const Q&>().w)>{};
    else
        return std::decay_t<decltype(std::declval<const Q&>().w())>{};
}
template <class R>
auto rotation_scalar_probe() {
    if constexpr (is_matrix3_v<R>)
        return matrix_entry_probe<R>();
    else if constexpr (is_quaternion_v<R>)
        return quaternion_entry_probe<R>();
    else
        return double{};
}
}  // namespace detail

/// The scalar of a matrix or quaternion type (float for glm::mat3 and glm::quat).
template <class R>
using rotation_scalar_t = decltype(detail::rotation_scalar_probe<R>());

/// The row-major Mat3 of a matrix type (see the header comment for each convention). A matrix
/// whose run-time size is not 3x3 (a dynamic Eigen matrix) throws std::invalid_argument naming
/// fn. Any other type is a compile-time error.
template <class M>
Mat3<rotation_scalar_t<M>> to_mat3(const M& m, const char* fn = "to_mat3") {
    using T = rotation_scalar_t<M>;
    if constexpr (detail::is_row_major_array<M>::value) {
        (void)fn;
        return m;
    } else if constexpr (detail::is_glm_mat<M>::value) {
        static_assert(sizeof(M) == 3 * sizeof(typename M::col_type) &&
                          sizeof(typename M::col_type) == 3 * sizeof(T),
                      "sphbasis: a glm matrix passed as a rotation must be a glm::mat3 / dmat3.");
        (void)fn;
        Mat3<T> r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r[static_cast<std::size_t>(3 * i + j)] = m[j][i];
        return r;
    } else if constexpr (detail::is_eigen_mat<M>::value) {
        if (m.rows() != 3 || m.cols() != 3)
            detail::throw_invalid(fn, "a 3x3 matrix, got " + std::to_string(m.rows()) + "x" +
                                          std::to_string(m.cols()));
        Mat3<T> r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r[static_cast<std::size_t>(3 * i + j)] = m(i, j);
        return r;
    } else {
        static_assert(detail::always_false<M>,
                      "sphbasis: a rotation matrix is a row-major std::array<T, 9>, a glm::mat3 / "
                      "dmat3 (column-major) or an Eigen::Matrix3f / Matrix3d.");
    }
}

/// The Quat of a quaternion type, read by the names w, x, y, z (see the header comment).
template <class Q>
Quat<rotation_scalar_t<Q>> to_quat(const Q& q) noexcept {
    static_assert(is_quaternion_v<Q>,
                  "sphbasis: a quaternion is a glm::quat / dquat, an Eigen::Quaternionf / "
                  "Quaterniond or a sphbasis::Quat (anything with w, x, y, z members or "
                  "w(), x(), y(), z()).");
    if constexpr (detail::has_member_wxyz<Q>::value)
        return {q.w, q.x, q.y, q.z};
    else
        return {q.w(), q.x(), q.y(), q.z()};
}

/// matrix_from_quaternion() of a quaternion type (glm::quat, Eigen::Quaterniond, Quat).
template <class Q, std::enable_if_t<is_quaternion_v<Q>, int> = 0>
Mat3<rotation_scalar_t<Q>> matrix_from_quaternion(const Q& q) {
    const auto p = to_quat(q);
    return matrix_from_quaternion(p.w, p.x, p.y, p.z);
}

/// The rotation matrix of a matrix or a quaternion type (to_mat3 / matrix_from_quaternion).
template <class R>
Mat3<rotation_scalar_t<R>> to_rotation_matrix(const R& r, const char* fn = "to_rotation_matrix") {
    if constexpr (is_quaternion_v<R>) {
        (void)fn;
        return matrix_from_quaternion(r);
    } else {
        return to_mat3(r, fn);
    }
}

}  // namespace sphbasis
