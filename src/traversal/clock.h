// SPDX-License-Identifier: MIT
// The clocks that time a culler's own work: the traversal's setup and test
// ms (traversal/traversal.h, FrameStats) and occu-bench-choice's choice.
// The wall clock counts everything between two readings, the time the
// thread was not run among it; the thread clock counts the calling
// thread's CPU time alone (CLOCK_THREAD_CPUTIME_ID, user and system), so
// that work done on the calling thread measures about the same on a
// machine shared with other work as on a quiet one. It does not count
// other threads' work nor the time spent waiting for them: llvmpipe draws
// and answers occlusion queries on its own threads (LP_NUM_THREADS), so a
// frame's time and the culling of a strategy that draws or queries through
// the GL stay on the wall clock's terms (docs/walkthrough.md says which
// columns take which).
#pragma once

#include <time.h>

#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace occu {

enum class Clock { wall, thread };

// "wall" or "thread", as --clock takes it.
inline const char *clock_name(Clock clock)
{
    return clock == Clock::thread ? "thread" : "wall";
}

// --clock wall|thread; throws std::invalid_argument naming `option` and
// what it got otherwise.
inline Clock clock_option(const std::string &option, const std::string &text)
{
    if (text != "wall" && text != "thread")
        throw std::invalid_argument(option + " wants wall or thread, got '" + text + "'");
    return text == "thread" ? Clock::thread : Clock::wall;
}

// A reading of `clock`, in nanoseconds from an origin of its own: only the
// difference of two readings of one clock means anything.
inline std::int64_t clock_ns(Clock clock)
{
    if (clock == Clock::wall)
        return std::chrono::duration_cast<std::chrono::nanoseconds>(
                   std::chrono::steady_clock::now().time_since_epoch())
            .count();
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return std::int64_t(t.tv_sec) * 1000000000 + std::int64_t(t.tv_nsec);
}

// Milliseconds between two readings of one clock.
inline double elapsed_ms(std::int64_t start_ns, std::int64_t end_ns)
{
    return std::chrono::duration<double, std::milli>(std::chrono::nanoseconds(end_ns - start_ns)).count();
}

// Adds the time `work` takes on one clock to a sum of milliseconds.
class Stopwatch {
public:
    explicit Stopwatch(Clock clock = Clock::wall) : clock_(clock) {}
    Clock clock() const { return clock_; }
    std::int64_t now() const { return clock_ns(clock_); }
    template <typename Work> void time(double &ms, Work &&work) const
    {
        const std::int64_t start = now();
        work();
        ms += elapsed_ms(start, now());
    }

private:
    Clock clock_;
};

}  // namespace occu
