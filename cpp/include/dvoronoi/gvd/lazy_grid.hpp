// A lazily allocated 2-d array for the grid diagram: the grid is cut into 8 x 8 tiles and a tile is
// allocated (filled with a default value) the first time one of its entries is written, so memory
// follows the traced diagram (a thin curve) rather than the grid's area, while a lookup stays two
// array reads with good locality (neighbouring cells share tiles). It replaces a hash map, whose
// random probes dominated the tracer's profile.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace dvoronoi::gvd {

template <class T>
class LazyGrid {
public:
    static constexpr int kShift = 3, kSide = 1 << kShift, kMask = kSide - 1;
    using Tile = std::array<T, kSide * kSide>;

    LazyGrid() = default;
    /// Columns [i0, i0 + width), rows [0, height); `empty` is the value of entries never written.
    LazyGrid(std::int64_t i0, std::int64_t width, std::int64_t height, T empty)
        : i0_(i0), tw_((width + kMask) >> kShift), th_((height + kMask) >> kShift), empty_(empty),
          dir_(static_cast<std::size_t>(tw_ * th_), nullptr) {}

    /// The entry at (i, j), or `empty` if its tile was never written. (i, j) must be in range.
    const T& get(std::int64_t i, std::int64_t j) const {
        const Tile* t = dir_[tile_index(i, j)];
        return t ? (*t)[slot(i - i0_, j)] : empty_;
    }

    /// A writable reference to the entry at (i, j), allocating its tile on first use.
    T& at(std::int64_t i, std::int64_t j) {
        Tile*& t = dir_[tile_index(i, j)];
        if (!t) t = new_tile();
        return (*t)[slot(i - i0_, j)];
    }

    std::size_t memory_bytes() const {
        return dir_.capacity() * sizeof(Tile*) + chunks_.size() * kChunk * sizeof(Tile);
    }

private:
    static constexpr std::size_t kChunk = 256;  // tiles allocated together

    Tile* new_tile() {
        if (used_ == kChunk || chunks_.empty()) {
            chunks_.emplace_back(new Tile[kChunk]);
            used_ = 0;
        }
        Tile* t = &chunks_.back()[used_++];
        t->fill(empty_);
        return t;
    }

    std::size_t tile_index(std::int64_t i, std::int64_t j) const {
        return static_cast<std::size_t>(((i - i0_) >> kShift) * th_ + (j >> kShift));
    }
    static std::size_t slot(std::int64_t i, std::int64_t j) {
        return static_cast<std::size_t>(((i & kMask) << kShift) | (j & kMask));
    }

    std::int64_t i0_ = 0, tw_ = 0, th_ = 0;
    T empty_{};
    std::vector<Tile*> dir_;                        // nullptr: never written
    std::vector<std::unique_ptr<Tile[]>> chunks_;  // the tiles' storage
    std::size_t used_ = 0;                          // tiles used in the last chunk
};

}  // namespace dvoronoi::gvd
