// A team of threads for the grid diagram's workers: fn(k) for k = 0..count-1, one thread each (the
// calling thread alone when count is 1, so one worker never pays for a thread).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace dvoronoi::gvd {

template <class Fn>
void run_team(int count, Fn&& fn) {
    if (count <= 1) {
        if (count == 1) fn(0);
        return;
    }
    std::vector<std::thread> team;
    team.reserve(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) team.emplace_back([&fn, k] { fn(k); });
    for (auto& t : team) t.join();
}

/// fn(state, lo, hi) over [0, count) in chunks of `chunk`, handed to `workers` threads as each
/// becomes free; each thread's `state` is make()'s. Rows of a map cost what their free pixels and
/// their diagram cost, so fixed shares leave a worker idle on maps whose parts differ (a cave's
/// halves differ by a quarter); the chunks each thread gets depend on timing, so fn must give the
/// same result for any split.
template <class Make, class Fn>
void run_chunks(int workers, std::int32_t count, std::int32_t chunk, Make&& make, Fn&& fn) {
    std::atomic<std::int32_t> next{0};
    run_team(workers, [&](int) {
        auto state = make();
        for (std::int32_t lo; (lo = next.fetch_add(chunk, std::memory_order_relaxed)) < count;)
            fn(state, lo, std::min(count, lo + chunk));
    });
}

}  // namespace dvoronoi::gvd
