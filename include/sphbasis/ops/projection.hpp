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
//   conversion(): the matrix T taking coefficients of basis A to the least-squares coefficients
//                 of basis B over the domain: T = G_B^-1 <B, A>. E.g. SH -> H-basis over the
//                 hemisphere, SH -> modified H-basis (thesis Listing 2.1), SH -> HSH.
// Costs: building an evaluation matrix is one basis evaluation per rule point; a fit or a
// conversion adds an n x n Cholesky factorisation.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "../basis/basis.hpp"
#include "../core/quadrature.hpp"

namespace sphbasis {

/// The matrix A with A(i, k) = B_k(d_i) over the rule's points.
inline Eigen::MatrixXd evaluation_matrix(const BasisFunctions& b, const DirectionalRule& rule) {
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
template <class F>
Eigen::VectorXd sample(F&& f, const DirectionalRule& rule) {
    Eigen::VectorXd v(static_cast<Eigen::Index>(rule.size()));
    for (std::size_t i = 0; i < rule.size(); ++i)
        v(static_cast<Eigen::Index>(i)) = f(rule.x[i], rule.y[i], rule.z[i]);
    return v;
}
}  // namespace detail

/// Inner products <A_j, B_k> over the rule: Aᵀ W B (n_a x n_b).
inline Eigen::MatrixXd cross_gram(const BasisFunctions& a, const BasisFunctions& b,
                                  const DirectionalRule& rule) {
    const Eigen::MatrixXd ea = evaluation_matrix(a, rule), eb = evaluation_matrix(b, rule);
    return ea.transpose() * detail::weights_of(rule).asDiagonal() * eb;
}

/// The Gram matrix G_jk = <B_j, B_k> over the rule (identity for an orthonormal basis on the
/// rule's domain when the rule is exact).
inline Eigen::MatrixXd gram(const BasisFunctions& b, const DirectionalRule& rule) {
    return cross_gram(b, b, rule);
}

/// Orthogonal projection c_k = <f, B_k> of f(x, y, z) (called with unit directions).
template <class F>
Eigen::VectorXd project(const BasisFunctions& b, F&& f, const DirectionalRule& rule) {
    return evaluation_matrix(b, rule).transpose() *
           (detail::weights_of(rule).asDiagonal() * detail::sample(f, rule));
}

/// Monte Carlo projection from samples: c_k = sum_i weights[i] values[i] B_k(dirs[i]), where
/// weights[i] = 1 / (N pdf(d_i)) for N samples drawn with density pdf (e.g. 2 pi / N for
/// uniform hemisphere samples, thesis eq. 2.2). Directions are normalised as by basis_eval.
/// Throws std::invalid_argument if the arrays differ in length.
inline Eigen::VectorXd project_mc(const BasisFunctions& b, const std::vector<vec3<double>>& dirs,
                                  const std::vector<double>& values,
                                  const std::vector<double>& weights) {
    if (dirs.size() != values.size() || dirs.size() != weights.size())
        throw std::invalid_argument(
            "sphbasis::project_mc(): expected as many values and weights as directions");
    Eigen::VectorXd c = Eigen::VectorXd::Zero(b.n);
    std::vector<double> y(static_cast<std::size_t>(b.n));
    for (std::size_t i = 0; i < dirs.size(); ++i) {
        double x = dirs[i].x, yy = dirs[i].y, z = dirs[i].z;
        normalize_or_pole(x, yy, z);
        b.eval(x, yy, z, y.data());
        const double wv = weights[i] * values[i];
        for (int k = 0; k < b.n; ++k) c(k) += wv * y[static_cast<std::size_t>(k)];
    }
    return c;
}

/// A factorised Gram matrix: solves G c = r. Throws std::runtime_error if G is not positive
/// definite to working precision (the functions are linearly dependent on the domain).
class GramSolver {
  public:
    explicit GramSolver(const Eigen::MatrixXd& g) : llt_(g) {
        if (llt_.info() != Eigen::Success)
            throw std::runtime_error(
                "sphbasis::GramSolver(): expected a positive definite Gram matrix (are the "
                "functions linearly independent on the domain?)");
        // Reject numerically singular sets: the Cholesky diagonal bounds the conditioning.
        const Eigen::VectorXd d = llt_.matrixLLT().diagonal();
        if (d.minCoeff() <= 1e-7 * d.maxCoeff())
            throw std::runtime_error(
                "sphbasis::GramSolver(): the Gram matrix is numerically singular on the domain");
    }
    Eigen::VectorXd solve(const Eigen::VectorXd& r) const { return llt_.solve(r); }
    Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const { return llt_.solve(r); }

  private:
    Eigen::LLT<Eigen::MatrixXd> llt_;
};

/// Least-squares coefficients of f over the rule's domain: minimises sum_i w_i (f - sum c B)^2.
template <class F>
Eigen::VectorXd fit(const BasisFunctions& b, F&& f, const DirectionalRule& rule) {
    return GramSolver(gram(b, rule)).solve(project(b, f, rule));
}

/// Conversion matrix (n_to x n_from) taking coefficients in `from` to the least-squares
/// coefficients in `to` over the rule's domain: T = G_to^-1 <to, from>. When span(to) contains
/// span(from) on the domain the conversion is exact.
inline Eigen::MatrixXd conversion(const BasisFunctions& from, const BasisFunctions& to,
                                  const DirectionalRule& rule) {
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
