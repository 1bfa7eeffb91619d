// Are this machine's cores independent? (What a 2-worker speed-up can reach: the grid diagram's
// target of 1.7x assumes they are.) Run: cmake --build build --target cores_probe &&
// build/tools/bench/cores_probe (or g++ -O2 -pthread tools/bench/cores_probe.cpp).
// Do two vCPUs share one physical core? A latency-bound loop (one dependent chain) scales ~2x on
// SMT siblings and on separate cores; a throughput-bound loop (many independent chains, high IPC)
// scales ~2x only on separate cores (~1.0-1.3x on siblings, which share the execution ports).
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <thread>
#include <vector>
static std::uint64_t latency(std::uint64_t n) { std::uint64_t x = 1; for (std::uint64_t i = 0; i < n; ++i) x = x * 6364136223846793005ull + 1442695040888963407ull; return x; }
static std::uint64_t throughput(std::uint64_t n) {
    std::uint64_t a = 1, b = 2, c = 3, d = 4, e = 5, f = 6, g = 7, h = 8;
    for (std::uint64_t i = 0; i < n; ++i) { a += i ^ b; b += i ^ c; c += i ^ d; d += i ^ e; e += i ^ f; f += i ^ g; g += i ^ h; h += i ^ a; asm volatile("" : "+r"(a), "+r"(b), "+r"(c), "+r"(d)); }
    return a + b + c + d + e + f + g + h;
}
template <class F> double run(int threads, F f, std::uint64_t n) {
    auto t0 = std::chrono::steady_clock::now();
    std::vector<std::thread> team; volatile std::uint64_t sink = 0;
    for (int k = 0; k < threads; ++k) team.emplace_back([&] { sink += f(n); });
    for (auto& t : team) t.join();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
int main() {
    const std::uint64_t n = 300000000;
    for (int rep = 0; rep < 3; ++rep) {
        double l1 = run(1, latency, n), l2 = run(2, latency, n), t1 = run(1, throughput, n / 2), t2 = run(2, throughput, n / 2);
        std::printf("latency-bound: 2 threads do 2x the work in %.2fx the time (scaling %.2fx); throughput-bound: %.2fx (scaling %.2fx)\n", l2 / l1, 2 * l1 / l2, t2 / t1, 2 * t1 / t2);
    }
}
