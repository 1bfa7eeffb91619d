// Shared machinery of the parallel drivers: the OpenMP team size, the progress callback and the
// tracker that reports progress and carries failures out of a parallel region (limited and exact
// cells, distances, coverage), and chunks of rows handed to an OpenMP team (the occupancy grids'
// passes); and a team of std::threads for workers that wait for each other's messages (the grid
// diagram's cooperative slices), which OpenMP cannot promise to start together:
// a region may get fewer threads than asked (nested regions, OMP_DYNAMIC, thread limits), and a
// worker waiting for a message from one that never started would hang.
#pragma once

#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace dvoronoi {

/// Progress callback: called with (agents done, agents total) from the calling thread only.
using ProgressFn = std::function<void(Index, Index)>;

namespace detail {

/// This thread's number in its OpenMP team (0 without OpenMP).
inline int thread_id() {
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

/// Progress and failures of a parallel loop over blocks of agents: counts finished agents, calls the
/// callback from the calling thread (OpenMP thread 0), and turns an exception thrown by the callback
/// (e.g. a Python KeyboardInterrupt) into a cancellation that is rethrown after the parallel region.
/// An exception thrown by an agent's work must not leave the parallel region (that would terminate
/// the program): the worker catches it and hands it to fail(), which keeps the failure of the lowest
/// loop position, so the error reported does not depend on the thread count, and lets the blocks
/// after it be skipped.
class ProgressTracker {
public:
    ProgressTracker(const ProgressFn& progress, Index total) : progress_(progress), total_(total) {}
    bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
    /// True when the block starting at loop position `lo` need not run: the callback failed, or an
    /// agent before `lo` did (its failure is the one reported).
    bool skip(Index lo) const { return cancelled() || lo > failed_at_.load(std::memory_order_relaxed); }
    void block_done(Index agents) {
        const Index now = done_.fetch_add(agents) + agents;
        if (!progress_ || thread_id() != 0) return;  // only the calling thread reports
        try {
            progress_(now, total_);
        } catch (...) {
            failure_ = std::current_exception();
            cancelled_ = true;
        }
    }
    /// Called in a worker's catch block: the work at loop position `pos` (agent `agent`) threw. A
    /// RangeError is given the agent in front of its message: `before` agent `after` (default
    /// "points[17]: ...").
    void fail(Index pos, Index agent, const char* before = "points[", const char* after = "]") {
        std::exception_ptr e = std::current_exception();
        try {
            throw;
        } catch (const RangeError& r) {
            try {
                e = std::make_exception_ptr(
                    RangeError(before + std::to_string(agent) + after + ": " + r.what()));
            } catch (...) {  // no memory for the longer message: keep the original
            }
        } catch (...) {
        }
        const std::lock_guard<std::mutex> lock(mu_);
        if (pos < failed_at_.load(std::memory_order_relaxed)) {
            failed_at_.store(pos, std::memory_order_relaxed);
            agent_failure_ = e;
        }
    }
    /// After the parallel region: rethrow the callback's exception, else the first agent's failure.
    void rethrow_if_failed() const {
        if (failure_) std::rethrow_exception(failure_);
        if (agent_failure_) std::rethrow_exception(agent_failure_);
    }
    /// At the very end: the callback sees (total, total).
    void report_all() const {
        if (progress_) progress_(total_, total_);
    }

private:
    const ProgressFn& progress_;
    Index total_;
    std::atomic<Index> done_{0};
    std::atomic<bool> cancelled_{false};
    std::exception_ptr failure_;
    std::mutex mu_;
    std::atomic<Index> failed_at_{std::numeric_limits<Index>::max()};
    std::exception_ptr agent_failure_;
};

/// f(), with `what: ` in front of the message of a RangeError it throws: for the steps over all
/// agents (a convex hull, a triangulation), where no single agent is to blame.
template <class F>
auto naming_range_error(const char* what, F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const RangeError& e) {
        throw RangeError(std::string(what) + ": " + e.what());
    }
}

/// Agents per block of the parallel drivers (the unit of scheduling and of progress reports).
inline constexpr Index kBlock = 2048;

/// The most threads a team starts: answers are the same for any count, and a request of 100,000
/// threads would fail in the system (libgomp aborts, std::thread throws) long before it could help.
inline int max_team() {
    static const int cap = static_cast<int>(std::max(64u, 8u * std::thread::hardware_concurrency()));
    return cap;
}

/// OpenMP team size for `blocks` blocks: `threads` (0 = all cores), never more than one thread per
/// block, so small inputs start no team, nor more than max_team().
inline int thread_team(int threads, Index blocks) {
#ifdef _OPENMP
    const int wanted = threads > 0 ? threads : omp_get_max_threads();
#else
    const int wanted = 1;
    (void)threads;
#endif
    return static_cast<int>(std::min<Index>({wanted, std::max<Index>(blocks, 1), ::dvoronoi::detail::max_team()}));
}

/// Blocks of kBlock agents that cover n agents.
inline Index block_count(Index n) { return (n + kBlock - 1) / kBlock; }

/// The per-agent loop of the parallel drivers: positions 0..n-1 in blocks of kBlock, handed to the
/// `team` OpenMP threads as each becomes free. Each thread makes its scratch by make(thread) and runs
/// work(scratch, pos) for the positions of its blocks; a work that returns bool returns false for a
/// position it puts off (not counted as done in the progress). A throw at `pos` goes to
/// tracker.fail(pos, agent_at(pos)) and the blocks after the first failure are skipped. After the
/// loop each thread hands its scratch to leave(scratch), one thread at a time; then the failure of
/// the lowest position (or the progress callback's) is rethrown. Results written per position do
/// not depend on the team.
template <class Make, class Work, class AgentAt, class Leave>
void for_each_block(Index n, int team, ProgressTracker& tracker, Make&& make, Work&& work, AgentAt&& agent_at,
                    Leave&& leave) {
    const Index nblocks = block_count(n);
#pragma omp parallel num_threads(team)
    {
        auto scratch = make(thread_id());
#pragma omp for schedule(dynamic, 1)
        for (Index b = 0; b < nblocks; ++b) {
            const Index lo = b * kBlock, hi = std::min(n, lo + kBlock);
            if (tracker.skip(lo)) continue;
            Index put_off = 0;
            Index pos = lo;
            try {
                for (; pos < hi; ++pos) {
                    if constexpr (std::is_void_v<decltype(work(scratch, pos))>)
                        work(scratch, pos);
                    else if (!work(scratch, pos))
                        ++put_off;
                }
            } catch (...) {
                tracker.fail(pos, agent_at(pos));
            }
            tracker.block_done(hi - lo - put_off);
        }
#pragma omp critical(dvoronoi_for_each_block)
        leave(scratch);
    }
    tracker.rethrow_if_failed();
}

/// The same with nothing to hand over at the end.
template <class Make, class Work, class AgentAt>
void for_each_block(Index n, int team, ProgressTracker& tracker, Make&& make, Work&& work, AgentAt&& agent_at) {
    for_each_block(n, team, tracker, std::forward<Make>(make), std::forward<Work>(work),
                   std::forward<AgentAt>(agent_at), [](auto&) {});
}

}  // namespace detail

/// fn(k) for k = 0..count-1, one std::thread each (the calling thread alone when count is 1, so one
/// worker never pays for a thread). Callers bound count by max_team().
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
    // one thread a chunk at most, and never more than max_team()
    workers = std::min({workers, (count + chunk - 1) / std::max(chunk, 1), ::dvoronoi::detail::max_team()});
    std::atomic<std::int32_t> next{0};
    auto take_chunks = [&] {
        auto state = make();
        for (std::int32_t lo; (lo = next.fetch_add(chunk, std::memory_order_relaxed)) < count;)
            fn(state, lo, std::min(count, lo + chunk));
    };
#ifdef _OPENMP
    // Chunks wait for no partner, so an OpenMP team serves with however many threads it gives; its
    // threads stay between regions (a grid diagram build runs several: a std::thread start each
    // would cost tens of microseconds).
#pragma omp parallel num_threads(std::max(1, workers)) if (workers > 1)
    take_chunks();
#else
    run_team(workers, [&](int) { take_chunks(); });
#endif
}

}  // namespace dvoronoi
