// The consistency step of Elwin, Freeman & Lynch (Section IV-C): every robot i sends its neighbour set
// V_i to its detection neighbours; a robot j that finds itself in V_i adds i to V_j. Afterwards
// j ∈ V_i iff i ∈ V_j. With exact distances it changes nothing (the relation is already symmetric).
#pragma once

#include "dvoronoi/core/types.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace dvoronoi::dist {

/// Makes the relation (CSR `indptr`, `indices`; rows in any order) symmetric by union, in place.
/// Each row keeps its entries in their order and gets the added ones appended in ascending order;
/// `added[i]` receives how many were added to row i.
/// \note O(E log E) for E entries. Not thread-safe on the same arrays.
inline void make_consistent(std::vector<Index>& indptr, std::vector<Index>& indices, std::vector<Index>& added) {
    const std::size_t n = indptr.size() - 1;
    std::vector<std::pair<Index, Index>> have;  // (row, column), sorted, to look reverse pairs up
    have.reserve(indices.size());
    for (std::size_t i = 0; i < n; ++i)
        for (Index q = indptr[i]; q < indptr[i + 1]; ++q) have.emplace_back(static_cast<Index>(i), indices[static_cast<std::size_t>(q)]);
    std::sort(have.begin(), have.end());
    std::vector<std::pair<Index, Index>> missing;  // (row j, column i): i lists j but j does not list i
    for (const auto& [i, j] : have)
        if (!std::binary_search(have.begin(), have.end(), std::make_pair(j, i))) missing.emplace_back(j, i);
    std::sort(missing.begin(), missing.end());
    added.assign(n, 0);
    for (const auto& mj : missing) ++added[static_cast<std::size_t>(mj.first)];
    if (missing.empty()) return;
    std::vector<Index> ptr(n + 1, 0), out;
    out.reserve(indices.size() + missing.size());
    std::size_t mpos = 0;
    for (std::size_t i = 0; i < n; ++i) {
        out.insert(out.end(), indices.begin() + indptr[i], indices.begin() + indptr[i + 1]);
        while (mpos < missing.size() && missing[mpos].first == static_cast<Index>(i)) out.push_back(missing[mpos++].second);
        ptr[i + 1] = static_cast<Index>(out.size());
    }
    indptr.swap(ptr);
    indices.swap(out);
}

}  // namespace dvoronoi::dist
