// sphbasis: contiguous ranges at the API boundary. An entry point that takes a buffer as a raw
// pointer also takes anything with .data() and .size() (std::vector, std::array, std::span,
// Eigen vectors), checks the size and forwards the pointer. Standard library only.
#pragma once

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>

#include "error.hpp"

namespace sphbasis::detail {

template <class R, class = void>
struct is_contiguous_range : std::false_type {};
template <class R>
struct is_contiguous_range<
    R, std::void_t<decltype(std::declval<R&>().data()), decltype(std::declval<R&>().size())>>
    : std::is_pointer<decltype(std::declval<R&>().data())> {};
template <class R>
inline constexpr bool is_contiguous_range_v =
    is_contiguous_range<std::remove_reference_t<R>>::value;

/// The element type of a contiguous range (const kept for const ranges).
template <class R>
using range_value_t = std::remove_pointer_t<decltype(std::declval<R&>().data())>;

/// r.data() after checking r.size() >= needed: "expected <name> of at least <needed> elements,
/// got <size>".
template <class R>
auto checked_data(const char* fn, const char* name, R& r, std::size_t needed) {
    const std::size_t n = static_cast<std::size_t>(r.size());
    if (n < needed)
        throw_invalid(fn, std::string(name) + " of at least " + std::to_string(needed) +
                              " elements, got " + std::to_string(n));
    return r.data();
}

}  // namespace sphbasis::detail

namespace sphbasis::detail {

/// An output (or input) buffer given as a pointer or as a contiguous range: the pointer itself
/// (null is checked by the callee), or the range's data() after checking size() >= needed.
template <class B>
auto buffer_pointer(const char* fn, const char* name, B&& b, std::size_t needed) {
    using D = std::remove_cv_t<std::remove_reference_t<B>>;
    if constexpr (std::is_pointer_v<D>) {
        return b;
    } else {
        static_assert(is_contiguous_range_v<D>,
                      "sphbasis: a buffer is a pointer or a contiguous range with .data() and "
                      ".size() (std::vector, std::array, std::span).");
        return checked_data(fn, name, b, needed);
    }
}

/// Whether C * S and C + C are valid, for the coefficient types of the SH operations.
template <class C, class S, class = void>
struct is_scalable : std::false_type {};
template <class C, class S>
struct is_scalable<C, S,
                   std::void_t<decltype(std::declval<const C&>() * std::declval<const S&>()),
                               decltype(std::declval<const C&>() + std::declval<const C&>())>>
    : std::true_type {};

/// Whether D is a 3-vector type as core/vec.hpp's component() reads it (not a number).
template <class D, class = void>
struct is_direction : std::false_type {};
template <class D>
struct is_direction<D, std::enable_if_t<!std::is_arithmetic_v<D> && !std::is_pointer_v<D>,
                                        std::void_t<decltype(std::declval<const D&>().x),
                                                    decltype(std::declval<const D&>().z)>>>
    : std::true_type {};
template <class D, class = void>
struct is_direction_call : std::false_type {};
template <class D>
struct is_direction_call<D, std::enable_if_t<!std::is_arithmetic_v<D> && !std::is_pointer_v<D>,
                                             std::void_t<decltype(std::declval<const D&>().x()),
                                                         decltype(std::declval<const D&>().z())>>>
    : std::true_type {};
template <class D, class = void>
struct is_direction_index : std::false_type {};
template <class D>
struct is_direction_index<
    D, std::enable_if_t<!std::is_arithmetic_v<D> && !std::is_pointer_v<D> &&
                        std::is_arithmetic_v<std::remove_cv_t<
                            std::remove_reference_t<decltype(std::declval<const D&>()[2])>>>>>
    : std::true_type {};
template <class D>
inline constexpr bool is_direction_v =
    is_direction<std::remove_cv_t<std::remove_reference_t<D>>>::value ||
    is_direction_call<std::remove_cv_t<std::remove_reference_t<D>>>::value ||
    is_direction_index<std::remove_cv_t<std::remove_reference_t<D>>>::value;

}  // namespace sphbasis::detail
