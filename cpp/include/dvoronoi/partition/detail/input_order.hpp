// Per-agent results computed in grid order by a team of threads, put into input order: each thread
// appends its agents' runs (pieces, neighbours) to a column of its own; the columns are joined in
// thread order and every agent's run moved to its place in a CSR layout, its neighbours ascending.
// Shared by the partition drivers (limited cells through cell_columns.hpp, exact Voronoi cells).
#pragma once

#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace dvoronoi::detail {

/// How many agents ahead the gathers prefetch.
inline constexpr Index kAhead = 16;
/// How many agents ahead a driver prefetches the lines it will write an agent's results to, in
/// input order: one agent is over a microsecond of work, and more lines in flight stall the loads
/// the work needs (measured: 4 ahead beats 2, 8 and 16 by 1-3%; none is 10% slower).
inline constexpr Index kWriteAhead = 4;

/// Puts runs of 8-byte values in CSR order: the run of agent i moves from [from(i), from(i) + len)
/// of `src` to [ptr[i], ptr[i + 1]) of `dst`, len = ptr[i + 1] - ptr[i]; then moved(i, run, len)
/// sees it in its new place. The reads are scattered, so a few agents ahead are prefetched. `src`
/// is read as bytes: it may be another column's storage holding a copy of these values.
template <class T, class From, class Moved>
void move_runs(T* dst, const void* src, const std::vector<Index>& ptr, From&& from, int team, Moved&& moved) {
    static_assert(sizeof(T) == 8 && std::is_trivially_copyable<T>::value, "columns of 8-byte values");
    const auto n = static_cast<Index>(ptr.size()) - 1;
    const auto* old = static_cast<const unsigned char*>(src);
#pragma omp parallel for num_threads(team) schedule(static)
    for (Index i = 0; i < n; ++i) {
        if (i + kAhead < n) prefetch(old + 8 * from(i + kAhead));
        const auto at = static_cast<std::size_t>(ptr[static_cast<std::size_t>(i)]);
        const auto len = static_cast<std::size_t>(ptr[static_cast<std::size_t>(i) + 1]) - at;
        const unsigned char* run = old + 8 * from(i);
        for (std::size_t k = 0; k < len; ++k) std::memcpy(dst + at + k, run + 8 * k, 8);  // a load and a store each
        moved(i, dst + at, len);
    }
}

/// Where each agent sits in `order` (the grid order the drivers compute in): pos_of[i].
inline std::vector<Index> positions_of(const std::vector<Index>& order) {
    std::vector<Index> pos_of(order.size());
    for (std::size_t pos = 0; pos < order.size(); ++pos) pos_of[static_cast<std::size_t>(order[pos])] = static_cast<Index>(pos);
    return pos_of;
}

/// Reads per-agent results stored by grid position in input order: fn(i, pos, by_pos[pos]) with
/// pos = pos_of[i]. The reads are scattered, so a few agents ahead are prefetched and the misses
/// overlap.
template <class R, class Fn>
void gather_in_input_order(const std::vector<Index>& pos_of, const std::vector<R>& by_pos, Fn&& fn) {
    const auto n = static_cast<Index>(pos_of.size());
    for (Index i = 0; i < n; ++i) {
        if (i + kAhead < n) prefetch(&by_pos[static_cast<std::size_t>(pos_of[static_cast<std::size_t>(i + kAhead)])]);
        const auto pos = static_cast<std::size_t>(pos_of[static_cast<std::size_t>(i)]);
        fn(i, pos, by_pos[pos]);
    }
}

/// Where an agent's run starts while each thread appends runs to its own column: offset * team +
/// thread. Once the columns are joined in thread order (sizes: their lengths before), to_joined
/// turns these places into offsets in the joined column.
inline Index column_place(std::size_t offset, int team, int thread) {
    return static_cast<Index>(offset) * team + thread;
}
inline void to_joined(std::vector<Index>& places, const std::vector<Index>& sizes) {
    const auto team = static_cast<Index>(sizes.size());
    if (team <= 1) return;  // offset * 1 + 0: already the offset
    std::vector<Index> base(sizes.size(), 0);
    for (std::size_t t = 1; t < base.size(); ++t) base[t] = base[t - 1] + sizes[t - 1];
    for (Index& at : places) at = base[static_cast<std::size_t>(at % team)] + at / team;
}

/// The threads' columns of runs as one CSR array in input order: the columns are joined in thread
/// order (each freed once appended) and agent i's run, placed at places[i] (column_place; turned into
/// joined offsets here), moved to [ptr[i], ptr[i + 1]).
inline std::vector<Index> runs_in_input_order(std::vector<std::vector<Index>>& columns, std::vector<Index>& places,
                                              const std::vector<Index>& ptr, int team) {
    std::vector<Index> sizes;
    for (const std::vector<Index>& column : columns) sizes.push_back(static_cast<Index>(column.size()));
    to_joined(places, sizes);
    for (std::size_t t = 1; t < columns.size(); ++t) {
        const std::vector<Index> part = std::move(columns[t]);
        columns[0].insert(columns[0].end(), part.begin(), part.end());
    }
    std::vector<Index> out(static_cast<std::size_t>(ptr.back()));
    move_runs(
        out.data(), columns[0].data(), ptr, [&](Index i) { return static_cast<std::size_t>(places[static_cast<std::size_t>(i)]); },
        team, [](Index, const Index*, std::size_t) {});
    return out;
}

/// Sorts eight values ascending: Batcher's odd-even merge network, 19 compare-exchanges. Each
/// exchange selects by a mask, not a branch: its outcome is a coin flip, and as branches (what
/// the compiler made of std::min/max here) half of them were mispredicted, which took twice the time.
inline void sort8(Index (&v)[8]) {
    const auto exchange = [&v](int a, int b) {
        const Index x = v[a], y = v[b];
        const Index d = (x ^ y) & -static_cast<Index>(y < x);  // x ^ y if they must swap, else 0
        v[a] = x ^ d;
        v[b] = y ^ d;
    };
    exchange(0, 2), exchange(1, 3), exchange(4, 6), exchange(5, 7);
    exchange(0, 4), exchange(1, 5), exchange(2, 6), exchange(3, 7);
    exchange(0, 1), exchange(2, 3), exchange(4, 5), exchange(6, 7);
    exchange(2, 4), exchange(3, 5);
    exchange(1, 4), exchange(3, 6);
    exchange(1, 2), exchange(3, 4), exchange(5, 6);
}

/// Sorts a handful of indices (a cell's neighbours) ascending. Up to eight (the usual case) go
/// through sort8, padded with the largest index; more through std::sort. The values stay in
/// registers: the copies in and out are loops of constant length.
inline void sort_small(Index* first, Index* last) {
    const std::ptrdiff_t n = last - first;
    if (n > 8) {
        std::sort(first, last);
        return;
    }
    Index v[8];
    for (std::ptrdiff_t t = 0; t < 8; ++t) v[t] = t < n ? first[t] : std::numeric_limits<Index>::max();
    sort8(v);
    for (std::ptrdiff_t t = 0; t < 8; ++t)
        if (t < n) first[t] = v[t];
}

/// A cell's limited neighbours from its pieces' neighbours `run` (arcs are negative): the edges'
/// neighbours, ascending, written to out; returns how many. Measured on a swarm of 1e6 agents
/// (about six pieces each): 25 ms, against 46 ms for a filter loop and the branching network.
inline std::size_t sorted_edge_neighbors(const Index* run, std::size_t len, Index* out) {
    if (len > 8) {
        Index* last = out;
        for (std::size_t k = 0; k < len; ++k)
            if (run[k] >= 0) *last++ = run[k];
        std::sort(out, last);
        return static_cast<std::size_t>(last - out);
    }
    constexpr Index kMax = std::numeric_limits<Index>::max();
    Index v[8] = {kMax, kMax, kMax, kMax, kMax, kMax, kMax, kMax};
    std::size_t count = 0;
    for (std::size_t k = 0; k < len; ++k) {
        // An edge is kept (count moves on); an arc leaves the padding in its slot.
        const Index r = run[k];
        const Index arc = -static_cast<Index>(r < 0);  // all ones for an arc
        v[count] = (r & ~arc) | (kMax & arc);
        count += static_cast<std::size_t>(arc + 1);
    }
    sort8(v);
    for (std::size_t t = 0; t < 8; ++t)
        if (t < count) out[t] = v[t];
    return count;
}

}  // namespace dvoronoi::detail
