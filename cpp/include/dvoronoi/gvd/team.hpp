// A team of threads for the grid diagram's workers: fn(k) for k = 0..count-1, one thread each (the
// calling thread alone when count is 1, so one worker never pays for a thread).
#pragma once

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

}  // namespace dvoronoi::gvd
