// Joining the slices of the grid Voronoi diagram: which traced components to keep.
//
// A worker traces its slice from the area's corners, from the obstacles, from the cells the area's
// boundary cuts and from border seeds, and finds exactly its own cells of the diagram
// (slice_tracer.hpp): every component it reports is anchored, and every one is kept. The join stays
// general — components joined across the border lines to an anchored one are kept, the others
// dropped — so a slice that reports unanchored components (as the MPI program's protocol allows) is
// still joined correctly. The data exchanged is small: per slice, its component count, which are
// anchored, and the components of the cells beside its two border lines.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace dvoronoi::gvd {

/// Disjoint sets over 0..n-1 (path halving; the smaller index becomes the root, so roots are
/// deterministic).
class UnionFind {
public:
    explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
    std::int32_t find(std::int32_t x) {
        while (parent_[static_cast<std::size_t>(x)] != x) {
            auto& p = parent_[static_cast<std::size_t>(x)];
            p = parent_[static_cast<std::size_t>(p)];
            x = p;
        }
        return x;
    }
    void join(std::int32_t a, std::int32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }

private:
    std::vector<std::int32_t> parent_;
};

/// What one slice reports for the join.
struct SliceSummary {
    std::int32_t n_components = 0;
    std::vector<std::uint8_t> anchored;  ///< per component
    /// components of the cells beside the left / right border line, one per border label change, in
    /// the order of the border scan (the same rows on both sides of a line)
    std::vector<std::int32_t> left_links, right_links;
};

/// Per slice, per component: keep it (1) or not (0).
inline std::vector<std::vector<std::uint8_t>> keep_components(const std::vector<SliceSummary>& s) {
    std::vector<std::int32_t> offset(s.size() + 1, 0);
    for (std::size_t k = 0; k < s.size(); ++k) offset[k + 1] = offset[k] + s[k].n_components;
    UnionFind sets(static_cast<std::size_t>(offset.back()));
    for (std::size_t k = 1; k < s.size(); ++k) {
        const auto& left = s[k - 1].right_links;
        const auto& right = s[k].left_links;
        for (std::size_t t = 0; t < left.size() && t < right.size(); ++t) {
            if (left[t] < 0 || right[t] < 0) continue;
            sets.join(offset[k - 1] + left[t], offset[k] + right[t]);
        }
    }
    std::vector<std::uint8_t> root_anchored(static_cast<std::size_t>(offset.back()), 0);
    for (std::size_t k = 0; k < s.size(); ++k)
        for (std::int32_t c = 0; c < s[k].n_components; ++c)
            if (s[k].anchored[static_cast<std::size_t>(c)]) root_anchored[static_cast<std::size_t>(sets.find(offset[k] + c))] = 1;
    std::vector<std::vector<std::uint8_t>> keep(s.size());
    for (std::size_t k = 0; k < s.size(); ++k) {
        keep[k].resize(static_cast<std::size_t>(s[k].n_components));
        for (std::int32_t c = 0; c < s[k].n_components; ++c)
            keep[k][static_cast<std::size_t>(c)] = root_anchored[static_cast<std::size_t>(sets.find(offset[k] + c))];
    }
    return keep;
}

}  // namespace dvoronoi::gvd
