// Small partitions shared by the io tests.
#pragma once

#include "dvoronoi/partition/limited_partition.hpp"

#include <random>

namespace io_test {

/// n points uniform in [0, side]^2 (fixed seed).
inline dvoronoi::Points random_points(int n, double side, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, side);
    dvoronoi::Points p(n, 2);
    for (int i = 0; i < n; ++i) {
        p(i, 0) = u(rng);
        p(i, 1) = u(rng);
    }
    return p;
}

/// A k x k square lattice of spacing 1 (degenerate: four cocircular agents everywhere).
inline dvoronoi::Points lattice(int k) {
    dvoronoi::Points p(k * k, 2);
    for (int i = 0; i < k * k; ++i) {
        p(i, 0) = i % k;
        p(i, 1) = i / k;
    }
    return p;
}

/// Random points plus one agent far from all others (a full disk).
inline dvoronoi::Points mixed_points() {
    dvoronoi::Points p = random_points(60, 6.0, 7);
    p.conservativeResize(61, 2);
    p(60, 0) = 100.0;
    p(60, 1) = 100.0;
    return p;
}

}  // namespace io_test
