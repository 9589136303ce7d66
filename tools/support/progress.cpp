// sphbasis CLI support: Progress (see progress.hpp).
#include "progress.hpp"

#include <algorithm>
#include <cstdio>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace sphbasis::cli {

namespace {

bool stderr_is_terminal() {
#if defined(__unix__) || defined(__APPLE__)
    return isatty(fileno(stderr)) != 0;
#else
    return false;
#endif
}

// "1h02m", "3m05s", "12s".
std::string duration_text(double s) {
    if (!(s >= 0) || s > 1e7) return "--";
    const long t = static_cast<long>(s + 0.5);
    char buf[32];
    if (t >= 3600)
        std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
    else if (t >= 60)
        std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
    else
        std::snprintf(buf, sizeof buf, "%lds", t);
    return buf;
}

// "950/s", "12.3k/s", "4.1M/s".
std::string rate_text(double r) {
    char buf[32];
    if (r >= 1e6)
        std::snprintf(buf, sizeof buf, "%.1fM/s", r / 1e6);
    else if (r >= 1e4)
        std::snprintf(buf, sizeof buf, "%.1fk/s", r / 1e3);
    else
        std::snprintf(buf, sizeof buf, "%.3g/s", r);
    return buf;
}

constexpr long long kRedrawNs = 100000000;  // at most ten redraws a second

}  // namespace

Progress::Progress(std::string label, long long total)
    : label_(std::move(label)),
      total_(std::max(0LL, total)),
      enabled_(stderr_is_terminal()),
      start_(Clock::now()) {
    if (enabled_) draw(0, false);
}

Progress::~Progress() { done(); }

void Progress::update(long long units) {
    const long long now_done = done_.fetch_add(units, std::memory_order_relaxed) + units;
    if (!enabled_) return;
    const long long ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start_).count();
    long long due = next_draw_ns_.load(std::memory_order_relaxed);
    if (ns < due) return;
    // One thread wins the redraw; the others carry on.
    if (!next_draw_ns_.compare_exchange_strong(due, ns + kRedrawNs)) return;
    std::unique_lock<std::mutex> lock(draw_mutex_, std::try_to_lock);
    if (lock.owns_lock() && !finished_.load()) draw(now_done, false);
}

void Progress::done() {
    if (finished_.exchange(true)) return;
    if (!enabled_) return;
    const std::lock_guard<std::mutex> lock(draw_mutex_);
    draw(total_, true);
    std::fputc('\n', stderr);
    std::fflush(stderr);
}

void Progress::draw(long long done_units, bool final) {
    const long long d = std::min(done_units, total_);
    const double frac = total_ > 0 ? static_cast<double>(d) / static_cast<double>(total_) : 1.0;
    const int width = 30;
    const int fill = static_cast<int>(frac * width);
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const double rate = elapsed > 0 ? static_cast<double>(d) / elapsed : 0.0;
    std::string tail;
    if (final)
        tail = duration_text(elapsed);
    else if (d > 0 && rate > 0)
        tail = rate_text(rate) + ", ETA " + duration_text(static_cast<double>(total_ - d) / rate);
    std::fprintf(stderr, "\r%-24s [%s%s] %3d%% %-24s", label_.c_str(),
                 std::string(static_cast<std::size_t>(fill), '#').c_str(),
                 std::string(static_cast<std::size_t>(width - fill), ' ').c_str(),
                 static_cast<int>(frac * 100), tail.c_str());
    std::fflush(stderr);
}

}  // namespace sphbasis::cli
