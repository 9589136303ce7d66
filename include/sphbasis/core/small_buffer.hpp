// sphbasis: a scratch buffer on the stack for small sizes and on the heap above, for the
// per-call temporaries of the SH operations (rotation, lights, products).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace sphbasis::detail {

/// n elements of T: in an inline array of N when n <= N, else on the heap. The elements are
/// not initialised (every user writes before it reads); not copyable or movable, since data()
/// may point into the object itself.
template <class T, std::size_t N>
class SmallBuffer {
  public:
    explicit SmallBuffer(std::size_t n) {
        if (n > N) heap_.resize(n);
        p_ = n > N ? heap_.data() : stack_.data();
    }
    SmallBuffer(const SmallBuffer&) = delete;
    SmallBuffer& operator=(const SmallBuffer&) = delete;
    T* data() noexcept { return p_; }
    const T* data() const noexcept { return p_; }
    T& operator[](std::size_t i) noexcept { return p_[i]; }
    const T& operator[](std::size_t i) const noexcept { return p_[i]; }

  private:
    std::array<T, N> stack_;  // not value-initialised: always written before it is read
    std::vector<T> heap_;
    T* p_;
};

}  // namespace sphbasis::detail
