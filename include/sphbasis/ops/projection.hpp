// sphbasis: projection of functions onto a basis, least-squares fits, Gram matrices and
// conversion matrices between bases, all over a domain given by a quadrature rule.
//
// Every function here works with any basis B of basis/basis.hpp through its evaluator, and with
// a DirectionalRule (core/quadrature.hpp) that defines the domain and the inner product
//   <f, g> = sum_i w_i f(d_i) g(d_i)  ~  integral of f g over the domain.
// With sphere_rule / hemisphere_rule of a high enough degree the inner products of polynomial
// bases are exact (see exact_rule()).
//
//   project():    c_k = <f, B_k>, the orthogonal projection; correct for orthonormal bases.
//   project_mc(): the same from weighted samples (Monte Carlo): c_k = sum_i w_i f_i B_k(d_i).
//   fit():        least squares over the domain for any basis: solve G c = <B, f>, with the Gram
//                 matrix G_jk = <B_j, B_k> (Cholesky, Eigen). Needed for non-orthonormal sets
//                 (modified H-basis) and for SH restricted to the hemisphere.
//   LeastSquares: the same fit precomputed for one basis and rule (evaluation matrix, Gram
//                 matrix and its factorisation), for fitting and scoring many signals (the IMSE
//                 experiment of ops/imse.hpp uses it); fit() is one call of it.
//   conversion(): the matrix T taking coefficients of basis A to the least-squares coefficients
//                 of basis B over the domain: T = G_B^-1 <B, A>. E.g. SH -> H-basis over the
//                 hemisphere, SH -> modified H-basis (Ishmukhametov, "Irradiance
//                 Normal Mapping" (thesis), Listing 2.1), SH -> HSH.
// Costs: building an evaluation matrix is one basis evaluation per rule point; a fit or a
// conversion adds an n x n Cholesky factorisation.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "../basis/basis.hpp"
#include "../core/contiguous.hpp"
#include "../core/error.hpp"
#include "../core/quadrature.hpp"
#include "../core/vec.hpp"

namespace sphbasis {

// Why the functions below are templates with a defaulted parameter (Basis = BasisFunctions,
// Scalar = double) rather than plain inline functions: the Eigen products in a plain inline
// function are instantiated in every translation unit that includes this header, used or not
// (that made including the library cost 3x what Eigen/Dense alone costs); a template's body is
// instantiated only where it is called.

/// The matrix A with A(i, k) = B_k(d_i) over the rule's points. Basis: BasisFunctions or any
/// type with an int n and an eval(x, y, z, double* out).
namespace detail {
/// Throws unless b.n >= 1 and, for a BasisFunctions, b.eval is set: a default-constructed or
/// hand-built BasisFunctions{-1, f} / {4, {}} is an error message, not an Eigen assertion or
/// std::bad_function_call.
template <class Basis>
void check_basis_functions(const Basis& b, const char* fn) {
    if (b.n < 1)
        sphbasis::detail::throw_invalid(
            fn, "a basis of n >= 1 functions, got n = " + std::to_string(b.n));
    if constexpr (std::is_constructible_v<bool, decltype(b.eval)>)
        if (!static_cast<bool>(b.eval))
            sphbasis::detail::throw_invalid(
                fn, "a basis with an evaluation function, got an empty one");
}
}  // namespace detail

template <class Basis = BasisFunctions>
Eigen::MatrixXd evaluation_matrix(const Basis& b, const DirectionalRule& rule) {
    detail::check_basis_functions(b, "evaluation_matrix");
    Eigen::MatrixXd a(static_cast<Eigen::Index>(rule.size()), b.n);
    std::vector<double> row(static_cast<std::size_t>(b.n));
    for (std::size_t i = 0; i < rule.size(); ++i) {
        b.eval(rule.x[i], rule.y[i], rule.z[i], row.data());
        for (int k = 0; k < b.n; ++k)
            a(static_cast<Eigen::Index>(i), k) = row[static_cast<std::size_t>(k)];
    }
    return a;
}

namespace detail {
inline Eigen::Map<const Eigen::VectorXd> weights_of(const DirectionalRule& rule) {
    return {rule.w.data(), static_cast<Eigen::Index>(rule.w.size())};
}
/// The single parameter type of a non-generic callable (lambda, function object, function
/// pointer), or void.
template <class F, class = void>
struct single_parameter {
    using type = void;
};
template <class R, class P>
struct single_parameter<R (*)(P)> {
    using type = P;
};
template <class M>
struct member_single_parameter {
    using type = void;
};
template <class R, class C, class P>
struct member_single_parameter<R (C::*)(P) const> {
    using type = P;
};
template <class R, class C, class P>
struct member_single_parameter<R (C::*)(P)> {
    using type = P;
};
template <class F>
struct single_parameter<F, std::void_t<decltype(&F::operator())>>
    : member_single_parameter<decltype(&F::operator())> {};

/// Calls f at the unit direction (x, y, z): f(x, y, z) if f takes three numbers, else
/// f(sphbasis::vec3<double>) if it takes that, else f(P(x, y, z)) for the direction type P of
/// its one parameter (glm::dvec3, Eigen::Vector3d, ...).
template <class F>
double call_direction(F& f, double x, double y, double z) {
    using G = std::decay_t<F>;
    if constexpr (std::is_invocable_v<F&, double, double, double>) {
        return static_cast<double>(f(x, y, z));
    } else if constexpr (std::is_invocable_v<F&, const vec3<double>&>) {
        return static_cast<double>(f(vec3<double>{x, y, z}));
    } else {
        using P = std::remove_cv_t<std::remove_reference_t<typename single_parameter<G>::type>>;
        static_assert(!std::is_void_v<P> && std::is_constructible_v<P, double, double, double>,
                      "sphbasis::project: the function is called as f(x, y, z) or f(direction), "
                      "with direction a sphbasis::vec3<double> or a 3-vector type constructible "
                      "from (x, y, z) (glm::dvec3, Eigen::Vector3d).");
        if constexpr (!std::is_void_v<P> && std::is_constructible_v<P, double, double, double>) {
            using S = std::remove_cv_t<std::remove_reference_t<decltype(component<0>(P(x, y, z)))>>;
            return static_cast<double>(
                f(P(static_cast<S>(x), static_cast<S>(y), static_cast<S>(z))));
        } else {
            return 0.0;
        }
    }
}

template <class F>
Eigen::VectorXd sample(F&& f, const DirectionalRule& rule) {
    Eigen::VectorXd v(static_cast<Eigen::Index>(rule.size()));
    for (std::size_t i = 0; i < rule.size(); ++i)
        v(static_cast<Eigen::Index>(i)) = call_direction(f, rule.x[i], rule.y[i], rule.z[i]);
    return v;
}
}  // namespace detail

/// Inner products <A_j, B_k> over the rule: Aᵀ W B (n_a x n_b).
template <class Basis = BasisFunctions>
Eigen::MatrixXd cross_gram(const Basis& a, const Basis& b, const DirectionalRule& rule) {
    const Eigen::MatrixXd ea = evaluation_matrix(a, rule), eb = evaluation_matrix(b, rule);
    return ea.transpose() * detail::weights_of(rule).asDiagonal() * eb;
}

/// The Gram matrix G_jk = <B_j, B_k> over the rule (identity for an orthonormal basis on the
/// rule's domain when the rule is exact).
template <class Basis = BasisFunctions>
Eigen::MatrixXd gram(const Basis& b, const DirectionalRule& rule) {
    return cross_gram(b, b, rule);
}

/// Orthogonal projection c_k = <f, B_k> of f over the rule's domain. f is called at unit
/// directions as f(x, y, z) or as f(direction), direction a sphbasis::vec3<double>, glm::dvec3,
/// Eigen::Vector3d or any 3-vector type constructible from (x, y, z).
template <class F>
Eigen::VectorXd project(const BasisFunctions& b, F&& f, const DirectionalRule& rule) {
    return evaluation_matrix(b, rule).transpose() *
           (detail::weights_of(rule).asDiagonal() * detail::sample(f, rule));
}

/// Monte Carlo projection from samples: c_k = sum_i weights[i] values[i] B_k(dirs[i]), where
/// weights[i] = 1 / (N pdf(d_i)) for N samples drawn with density pdf (e.g. 2 pi / N for
/// uniform hemisphere samples, Ishmukhametov, eq. 2.2). dirs is any contiguous container
/// (std::vector, std::array, std::span) of any 3-vector type (sphbasis::vec3, glm::vec3,
/// Eigen::Vector3f, ...); values and weights are contiguous containers of numbers. Directions
/// are normalised as by basis_eval. Throws std::invalid_argument if the lengths differ.
template <class Dirs, class Values, class Weights>
Eigen::VectorXd project_mc(const BasisFunctions& b, const Dirs& dirs, const Values& values,
                           const Weights& weights) {
    static_assert(sphbasis::detail::is_contiguous_range_v<const Dirs> &&
                      sphbasis::detail::is_contiguous_range_v<const Values> &&
                      sphbasis::detail::is_contiguous_range_v<const Weights>,
                  "sphbasis::project_mc: dirs, values and weights are contiguous containers "
                  "(std::vector, std::array, std::span).");
    using D = std::remove_cv_t<sphbasis::detail::range_value_t<const Dirs>>;
    static_assert(sphbasis::detail::is_direction_v<D>,
                  "sphbasis::project_mc: dirs holds 3-vectors (.x/.y/.z, x()/y()/z() or [i]).");
    const std::size_t n = static_cast<std::size_t>(dirs.size());
    if (static_cast<std::size_t>(values.size()) != n ||
        static_cast<std::size_t>(weights.size()) != n)
        sphbasis::detail::throw_invalid(
            "project_mc", "as many values and weights as directions, got " + std::to_string(n) +
                              " directions, " + std::to_string(values.size()) + " values and " +
                              std::to_string(weights.size()) + " weights");
    detail::check_basis_functions(b, "project_mc");
    const D* pd = dirs.data();
    const auto* pv = values.data();
    const auto* pw = weights.data();
    Eigen::VectorXd c = Eigen::VectorXd::Zero(b.n);
    std::vector<double> y(static_cast<std::size_t>(b.n));
    for (std::size_t i = 0; i < n; ++i) {
        double x = static_cast<double>(component<0>(pd[i]));
        double yy = static_cast<double>(component<1>(pd[i]));
        double z = static_cast<double>(component<2>(pd[i]));
        normalize_or_pole(x, yy, z);
        b.eval(x, yy, z, y.data());
        const double wv = static_cast<double>(pw[i]) * static_cast<double>(pv[i]);
        for (int k = 0; k < b.n; ++k) c(k) += wv * y[static_cast<std::size_t>(k)];
    }
    return c;
}

/// A factorised Gram matrix: solves G c = r. Throws std::runtime_error if G is not positive
/// definite to working precision (the functions are linearly dependent on the domain).
/// Use it as GramSolver (Scalar = double).
template <class Scalar = double>
class BasicGramSolver {
    static_assert(std::is_same_v<Scalar, double>,
                  "sphbasis::GramSolver: the Gram solve is in double.");

  public:
    explicit BasicGramSolver(const Eigen::MatrixXd& g) : llt_(g) {
        if (llt_.info() != Eigen::Success)
            sphbasis::detail::throw_runtime("GramSolver",
                                            "a positive definite Gram matrix (are the functions "
                                            "linearly independent on the domain?)");
        // Reject numerically singular sets: the Cholesky diagonal bounds the conditioning.
        const Eigen::VectorXd d = llt_.matrixLLT().diagonal();
        if (d.minCoeff() <= 1e-7 * d.maxCoeff())
            sphbasis::detail::throw_runtime(
                "GramSolver",
                "a Gram matrix that is not numerically singular on the domain, got "
                "a Cholesky diagonal ratio of " +
                    std::to_string(d.minCoeff() / d.maxCoeff()));
    }
    Eigen::VectorXd solve(const Eigen::VectorXd& r) const { return llt_.solve(r); }
    Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const { return llt_.solve(r); }

  private:
    Eigen::LLT<Eigen::MatrixXd> llt_;
};
using GramSolver = BasicGramSolver<>;

/// The least-squares fit of functions sampled on a rule's points, for one basis: precomputes
/// the evaluation matrix, the Gram matrix and its factorisation once; then fits and scores many
/// signals. With orthonormal = true the fit is the orthogonal projection c = <B, f>, after
/// checking that the Gram matrix on the rule is the identity within `tolerance`
/// (std::runtime_error if not: the basis or the rule is wrong); otherwise G c = <B, f>
/// (GramSolver: std::runtime_error if the functions are dependent on the domain). Cost to build:
/// rule.size() * n evaluations and an n x n Cholesky factorisation. Copies share the
/// factorisation. Use it as LeastSquares (Scalar = double).
template <class Scalar = double>
class BasicLeastSquares {
    static_assert(std::is_same_v<Scalar, double>,
                  "sphbasis::LeastSquares: the least-squares fit is in double.");

  public:
    /// The Gram solve (any basis).
    BasicLeastSquares(const BasisFunctions& b, const DirectionalRule& rule)
        : BasicLeastSquares(b, false, rule) {}
    BasicLeastSquares(const BasisFunctions& b, bool orthonormal, const DirectionalRule& rule,
                      double tolerance = 1e-10)
        : n_((detail::check_basis_functions(b, "LeastSquares"), b.n)),
          orthonormal_(orthonormal),
          w_(detail::weights_of(rule)),
          phi_(evaluation_matrix(b, rule)) {
        gram_ = phi_.transpose() * w_.asDiagonal() * phi_;
        if (orthonormal_) {
            const double dev = (gram_ - Eigen::MatrixXd::Identity(n_, n_)).cwiseAbs().maxCoeff();
            if (!(dev <= tolerance))
                sphbasis::detail::throw_runtime(
                    "LeastSquares",
                    "an orthonormal basis on the rule's domain, got max |G - I| = " +
                        std::to_string(dev));
        } else {
            solver_ = std::make_shared<const GramSolver>(gram_);
        }
    }

    int size() const noexcept { return n_; }
    bool orthonormal() const noexcept { return orthonormal_; }
    /// Phi(i, k) = B_k(d_i) over the rule's points.
    const Eigen::MatrixXd& evaluation() const noexcept { return phi_; }
    /// G = Phi^T W Phi.
    const Eigen::MatrixXd& gram() const noexcept { return gram_; }
    /// The rule's weights W.
    const Eigen::VectorXd& weights() const noexcept { return w_; }

    /// Solves G c = r (or c = r for an orthonormal basis) for the right-hand sides r = <B, f>.
    Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const {
        return orthonormal_ ? r : solver_->solve(r);
    }
    /// Least-squares coefficients (n x S) of S signals sampled on the rule's points
    /// (samples: rule.size() x S).
    Eigen::MatrixXd coefficients(const Eigen::MatrixXd& samples) const {
        check_rows(samples, "LeastSquares::coefficients");
        return solve(phi_.transpose() * (w_.asDiagonal() * samples));
    }
    /// The squared residual of the fit of each of S sampled signals, integrated by the rule:
    /// sum_i w_i (sum_k c_k B_k(d_i) - f(d_i))^2. Never negative.
    Eigen::VectorXd squared_residuals(const Eigen::MatrixXd& samples) const {
        check_rows(samples, "LeastSquares::squared_residuals");
        Eigen::VectorXd out(samples.cols());
        // In blocks of columns: the temporaries stay in cache and allocations small.
        const Eigen::Index block = 64;
        Eigen::MatrixXd r;
        for (Eigen::Index c0 = 0; c0 < samples.cols(); c0 += block) {
            const Eigen::Index len = std::min(block, samples.cols() - c0);
            const auto s = samples.middleCols(c0, len);
            r.noalias() = phi_ * solve(phi_.transpose() * (w_.asDiagonal() * s));
            r -= s;
            out.segment(c0, len) = (w_.asDiagonal() * r.cwiseAbs2()).colwise().sum().transpose();
        }
        return out;
    }
    /// The matrix T (n x m) that maps coefficients of the functions `from` (evaluated on the
    /// rule's points: rule.size() x m) to the fit's coefficients: T = G^-1 <B, from>.
    Eigen::MatrixXd conversion(const Eigen::MatrixXd& from_evaluation) const {
        check_rows(from_evaluation, "LeastSquares::conversion");
        return solve(phi_.transpose() * (w_.asDiagonal() * from_evaluation));
    }

  private:
    void check_rows(const Eigen::MatrixXd& m, const char* fn) const {
        if (m.rows() != phi_.rows())
            sphbasis::detail::throw_invalid(fn, "one row per rule point (" +
                                                    std::to_string(phi_.rows()) + "), got " +
                                                    std::to_string(m.rows()));
    }
    int n_;
    bool orthonormal_;
    Eigen::VectorXd w_;
    Eigen::MatrixXd phi_, gram_;
    std::shared_ptr<const GramSolver> solver_;
};
using LeastSquares = BasicLeastSquares<>;

/// Least-squares coefficients of f over the rule's domain: minimises sum_i w_i (f - sum c B)^2.
/// f is called as by project(). One LeastSquares (Gram solve) for one signal.
template <class F>
Eigen::VectorXd fit(const BasisFunctions& b, F&& f, const DirectionalRule& rule) {
    return LeastSquares(b, rule).coefficients(detail::sample(f, rule));
}

/// Conversion matrix (n_to x n_from) taking coefficients in `from` to the least-squares
/// coefficients in `to` over the rule's domain: T = G_to^-1 <to, from>. When span(to) contains
/// span(from) on the domain the conversion is exact.
template <class Basis = BasisFunctions>
Eigen::MatrixXd conversion(const Basis& from, const Basis& to, const DirectionalRule& rule) {
    return GramSolver(gram(to, rule)).solve(cross_gram(to, from, rule));
}

/// Weighted squared L2 distance over the rule between two expansions, or between an expansion
/// and a function: sum_i w_i (sum_k c_k B_k(d_i) - f(d_i))^2.
template <class F>
double squared_error(const BasisFunctions& b, const Eigen::VectorXd& c, F&& f,
                     const DirectionalRule& rule) {
    const Eigen::VectorXd r = evaluation_matrix(b, rule) * c - detail::sample(f, rule);
    double s = 0;
    for (std::size_t i = 0; i < rule.size(); ++i) {
        const double ri = r(static_cast<Eigen::Index>(i));
        s += rule.w[i] * ri * ri;
    }
    return s;
}

}  // namespace sphbasis
