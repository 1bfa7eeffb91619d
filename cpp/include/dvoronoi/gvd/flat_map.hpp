// A small open-addressing hash map from 64-bit keys to values, for the lazily labelled corners and
// the traced cells of the grid diagram.
//
// Why not std::unordered_map: one node allocation per entry costs about 3x the memory and a cache
// miss per lookup; the tracer does several lookups per cell, and the memory budget is a fraction of a
// dense grid. Linear probing, power-of-two capacity, load factor <= 1/2, no erase.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace dvoronoi::gvd {

template <class V>
class FlatMap {
public:
    explicit FlatMap(std::size_t expected = 16) { rehash(capacity_for(expected)); }

    /// The value of `key`, or nullptr.
    const V* find(std::uint64_t key) const {
        std::size_t k = slot(key);
        while (true) {
            const std::uint64_t s = keys_[k];
            if (s == key + 1) return &values_[k];
            if (s == 0) return nullptr;
            k = (k + 1) & mask_;
        }
    }
    V* find(std::uint64_t key) { return const_cast<V*>(static_cast<const FlatMap&>(*this).find(key)); }

    /// Inserts (key, value) unless present; returns the stored value and whether it was inserted.
    std::pair<V*, bool> insert(std::uint64_t key, const V& value) {
        if (2 * (size_ + 1) > keys_.size()) rehash(keys_.size() * 2);
        std::size_t k = slot(key);
        while (true) {
            const std::uint64_t s = keys_[k];
            if (s == key + 1) return {&values_[k], false};
            if (s == 0) break;
            k = (k + 1) & mask_;
        }
        keys_[k] = key + 1;
        values_[k] = value;
        ++size_;
        return {&values_[k], true};
    }

    std::size_t size() const { return size_; }
    std::size_t memory_bytes() const { return keys_.capacity() * sizeof(std::uint64_t) + values_.capacity() * sizeof(V); }

private:
    static std::size_t capacity_for(std::size_t n) {
        std::size_t c = 16;
        while (c < 2 * n) c *= 2;
        return c;
    }
    std::size_t slot(std::uint64_t key) const {
        std::uint64_t x = key * 0x9E3779B97F4A7C15ull;  // Fibonacci hashing
        x ^= x >> 29;
        return static_cast<std::size_t>(x) & mask_;
    }
    void rehash(std::size_t cap) {
        std::vector<std::uint64_t> old_keys(cap, 0);
        std::vector<V> old_values(cap);
        old_keys.swap(keys_);
        old_values.swap(values_);
        mask_ = cap - 1;
        size_ = 0;
        for (std::size_t k = 0; k < old_keys.size(); ++k)
            if (old_keys[k] != 0) {
                std::size_t t = slot(old_keys[k] - 1);
                while (keys_[t] != 0) t = (t + 1) & mask_;
                keys_[t] = old_keys[k];
                values_[t] = old_values[k];
                ++size_;
            }
    }

    std::vector<std::uint64_t> keys_;  // key + 1; 0 = empty
    std::vector<V> values_;
    std::size_t mask_ = 0, size_ = 0;
};

}  // namespace dvoronoi::gvd
