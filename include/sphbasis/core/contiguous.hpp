// sphbasis: buffers at the API boundary. Every entry point that takes a buffer as a raw pointer
// also takes a C array or anything with .data() and .size() (std::vector, std::array,
// std::span, Eigen vectors): the size of an array or a range is checked against what the call
// needs, a pointer is checked for null where it would be used, and the messages follow
// core/error.hpp ("sphbasis::fn(): expected <name> buffer of at least N elements, got M",
// "sphbasis::fn(): expected a non-null <name> buffer"). Standard library only.
#pragma once

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>

#include "../config.hpp"
#include "error.hpp"

namespace sphbasis::detail {

/// For static_assert in the last branch of an if constexpr chain.
template <class>
inline constexpr bool always_false = false;

template <class R, class = void>
struct is_contiguous_range : std::false_type {};
template <class R>
struct is_contiguous_range<
    R, std::void_t<decltype(std::declval<R&>().data()), decltype(std::declval<R&>().size())>>
    : std::is_pointer<decltype(std::declval<R&>().data())> {};
template <class R>
inline constexpr bool is_contiguous_range_v =
    is_contiguous_range<std::remove_reference_t<R>>::value;

/// A buffer argument: a pointer, a C array or a contiguous range.
template <class B>
inline constexpr bool is_buffer_v =
    std::is_pointer_v<std::decay_t<B>> || std::is_array_v<std::remove_reference_t<B>> ||
    is_contiguous_range_v<B>;

/// The first element of a buffer, unchecked.
template <class B>
SPHBASIS_FORCEINLINE auto buffer_data(B& b) noexcept {
    using P = std::remove_cv_t<B>;
    if constexpr (std::is_pointer_v<P>)
        return static_cast<P>(b);
    else if constexpr (std::is_array_v<P>)
        return &b[0];
    else
        return b.data();
}

/// The element type of a buffer (const-qualified for read-only ranges and const pointers).
template <class B>
using buffer_element_t =
    std::remove_pointer_t<decltype(buffer_data(std::declval<std::remove_reference_t<B>&>()))>;

/// The element type of a contiguous range (const kept for const ranges).
template <class R>
using range_value_t = std::remove_pointer_t<decltype(std::declval<R&>().data())>;

[[noreturn]] SPHBASIS_NOINLINE inline void throw_small_buffer(const char* fn, const char* name,
                                                              std::size_t need, std::size_t size) {
    throw_invalid(fn, std::string(name) + " buffer of at least " + std::to_string(need) +
                          " elements, got " + std::to_string(size));
}

/// Throws unless the buffer can hold `need` elements: a pointer must not be null when need > 0,
/// an array or a range must have at least `need` elements. One compare (none for an array
/// known to be large enough); the message is built out of line.
template <class B>
SPHBASIS_FORCEINLINE void check_buffer_size(const char* fn, const char* name, const B& b,
                                            std::size_t need) {
    using P = std::remove_cv_t<B>;
    if constexpr (std::is_array_v<P>) {
        if (std::extent_v<P> < need) throw_small_buffer(fn, name, need, std::extent_v<P>);
    } else if constexpr (std::is_pointer_v<P>) {
        check_buffer(fn, name, b, need);
    } else if constexpr (is_contiguous_range_v<P>) {
        if (static_cast<std::size_t>(b.size()) < need)
            throw_small_buffer(fn, name, need, static_cast<std::size_t>(b.size()));
    } else {
        static_assert(always_false<B>,
                      "sphbasis: a buffer is a pointer, a C array or a contiguous range with "
                      ".data() and .size() (std::vector, std::array, std::span).");
    }
}

/// The first element of a buffer that must hold `need` elements, after check_buffer_size().
template <class B>
SPHBASIS_FORCEINLINE auto buffer_data(const char* fn, const char* name, B& b, std::size_t need) {
    check_buffer_size(fn, name, b, need);
    return buffer_data(b);
}

/// Whether C * S and C + C are valid, for the coefficient types of the SH operations.
template <class C, class S, class = void>
struct is_scalable : std::false_type {};
template <class C, class S>
struct is_scalable<C, S,
                   std::void_t<decltype(std::declval<const C&>() * std::declval<const S&>()),
                               decltype(std::declval<const C&>() + std::declval<const C&>())>>
    : std::true_type {};

}  // namespace sphbasis::detail
