// sphbasis CLI support: the tool's one parallel-for, on oneTBB.
//
// Callers make their results independent of the thread count and of the scheduling: each index
// writes its own output slot, and sums are formed afterwards in index order.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <cstddef>

namespace sphbasis::cli {

/// Runs body(i) for every i in [0, count) on TBB's worker threads, one index per task (the
/// bodies are coarse: a block of directions, a batch of signals, a map). An exception thrown
/// by a body cancels the rest and is rethrown here.
template <class F>
void parallel_for(std::size_t count, F&& body) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
                      });
}

/// The callable form of parallel_for, for library functions that take a `for_each(count,
/// body)` (e.g. param::sh_reconstruction_error).
struct ParallelFor {
    template <class F>
    void operator()(std::size_t count, F&& body) const {
        parallel_for(count, body);
    }
};

/// Caps the number of threads TBB uses while it lives (a --threads option).
class ThreadLimit {
  public:
    explicit ThreadLimit(std::size_t threads)
        : control_(tbb::global_control::max_allowed_parallelism, threads) {}

  private:
    tbb::global_control control_;
};

}  // namespace sphbasis::cli
