// asr_timing: the Boundary Scan paper's ASR experiments (He, Feng & Ren 2018, Section 4.1), timed in
// C++ on this machine. Driven by tools/reproduce/asr_table3_fig8.py, which writes the CSV and PNG.
//
//   asr_timing table3  [--configs 100] [--seed S]   30 sensors uniform in 3 x 3, sensing range r = 1
//   asr_timing figure8 [--configs 100] [--seed S]   500 sensors in L x L, L = 1..15, r = 1
//
// The paper's sensing range r is the neighbourhood; our cell radius is R = r/2 (docs/spec.md). Every
// sensor computes its R-limited cell from the sensors within r, by
//   EVT      exact tessellation (our exact Delaunay) of the sensor and those neighbours, cell
//            extracted and cut by the disk;
//   BS       Boundary Scan;
//   ASR+EVT, ASR+BS   the radius schedule (doubling from the nearest-neighbour distance) with EVT or
//            BS as the inner step, stopping early when a cell is certified below R.
// Each configuration's time is the total over all its sensors, best of --repeat runs. All four must
// give the same cells (checked, untimed); a mismatch exits with status 2.
// Output: CSV on stdout, one row per configuration: experiment,side,config,sensors,evt_s,bs_s,
// asr_evt_s,asr_bs_s,mean_neighbors,mean_asr_steps.
#include <dvoronoi/cells/asr_limited.hpp>
#include <dvoronoi/cells/limited_cell.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace dvoronoi;

double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// What each sensor knows: its position and those of the sensors within the sensing range r = 2R.
struct Sensor {
    Vec2 c;
    Points nearby;
};

std::vector<Sensor> sensors_of(const Points& p, double R) {
    std::vector<Sensor> out;
    for (Index i = 0; i < p.rows(); ++i) {
        const Vec2 c = p.row(i).transpose();
        std::vector<Index> ids;
        for (Index j = 0; j < p.rows(); ++j)
            if (j != i && pred::within_2r(c, p.row(j).transpose(), R) > 0) ids.push_back(j);
        Points nb(static_cast<Index>(ids.size()), 2);
        for (std::size_t k = 0; k < ids.size(); ++k) nb.row(static_cast<Index>(k)) = p.row(ids[k]);
        out.push_back({c, nb});
    }
    return out;
}

enum class Route { Evt, Bs, AsrEvt, AsrBs };

LimitedCell cell_by(Route r, const Sensor& s, double R, int* steps) {
    switch (r) {
        case Route::Evt: {
            detail::CellWorkspace ws;
            detail::DelaunayWorkspace dws;
            LimitedCell out;
            detail::evt_limited_cell(s.c, detail::candidates_within_2r(s.c, s.nearby, R), R, out, ws, dws);
            return out;
        }
        case Route::Bs: return limited_cell(s.c, s.nearby, R, Method::Scan);  // Boundary Scan itself
        case Route::AsrEvt: return asr_limited_cell(s.c, s.nearby, R, LimitedInner::Evt, steps);
        case Route::AsrBs: return asr_limited_cell(s.c, s.nearby, R, LimitedInner::Scan, steps);
    }
    return {};
}

double time_route(Route r, const std::vector<Sensor>& sensors, double R, int repeat, std::vector<LimitedCell>& keep,
                  double* mean_steps) {
    double best = 1e300;
    for (int k = 0; k < repeat; ++k) {
        std::vector<LimitedCell> cells;
        cells.reserve(sensors.size());
        long steps = 0;
        const double t0 = now();
        for (const Sensor& s : sensors) {
            int st = 0;
            cells.push_back(cell_by(r, s, R, &st));
            steps += st;
        }
        best = std::min(best, now() - t0);
        if (mean_steps) *mean_steps = static_cast<double>(steps) / static_cast<double>(std::max<std::size_t>(1, sensors.size()));
        keep = std::move(cells);
    }
    return best;
}

bool same(const std::vector<LimitedCell>& a, const std::vector<LimitedCell>& b) {
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].neighbors() != b[i].neighbors() ||
            std::abs(a[i].measures().area - b[i].measures().area) > 1e-12 * (1.0 + a[i].measures().area))
            return false;
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || (std::string(argv[1]) != "table3" && std::string(argv[1]) != "figure8")) {
        std::fprintf(stderr, "usage: asr_timing table3|figure8 [--configs N] [--repeat K] [--seed S] [--sides 1,2,..]\n");
        return 1;
    }
    const bool table3 = std::string(argv[1]) == "table3";
    int configs = 100, repeat = 3;
    unsigned long long seed = 2018;
    std::vector<double> sides;
    for (int a = 2; a + 1 < argc; a += 2) {
        const std::string k = argv[a], v = argv[a + 1];
        if (k == "--configs") configs = std::stoi(v);
        else if (k == "--repeat") repeat = std::stoi(v);
        else if (k == "--seed") seed = std::stoull(v);
        else if (k == "--sides") {
            for (std::size_t pos = 0; pos < v.size();) {
                const std::size_t comma = v.find(',', pos);
                sides.push_back(std::stod(v.substr(pos, comma - pos)));
                pos = comma == std::string::npos ? v.size() : comma + 1;
            }
        } else {
            std::fprintf(stderr, "asr_timing: unknown option %s\n", k.c_str());
            return 1;
        }
    }
    const Index n = table3 ? 30 : 500;
    if (sides.empty()) {
        if (table3) sides = {3.0};
        else for (int L = 1; L <= 15; ++L) sides.push_back(L);
    }
    const double R = 0.5;  // r = 1
    std::mt19937_64 rng(seed);
    std::printf("experiment,side,config,sensors,evt_s,bs_s,asr_evt_s,asr_bs_s,mean_neighbors,mean_asr_steps\n");
    long done = 0;
    const long total = static_cast<long>(sides.size()) * configs;
    for (double L : sides)
        for (int k = 0; k < configs; ++k) {
            std::uniform_real_distribution<double> u(0.0, L);
            Points p(n, 2);
            for (Index i = 0; i < n; ++i) p.row(i) << u(rng), u(rng);
            const std::vector<Sensor> sensors = sensors_of(p, R);
            double nb = 0;
            for (const Sensor& s : sensors) nb += static_cast<double>(s.nearby.rows());
            std::vector<LimitedCell> evt, bs, aevt, abs;
            double steps = 0;
            const double t_evt = time_route(Route::Evt, sensors, R, repeat, evt, nullptr);
            const double t_bs = time_route(Route::Bs, sensors, R, repeat, bs, nullptr);
            const double t_aevt = time_route(Route::AsrEvt, sensors, R, repeat, aevt, nullptr);
            const double t_abs = time_route(Route::AsrBs, sensors, R, repeat, abs, &steps);
            if (!same(bs, evt) || !same(bs, aevt) || !same(bs, abs)) {
                std::fprintf(stderr, "asr_timing: the four routes disagree (side %g, config %d)\n", L, k);
                return 2;
            }
            std::printf("%s,%g,%d,%lld,%.9g,%.9g,%.9g,%.9g,%.4g,%.4g\n", table3 ? "table3" : "figure8", L, k,
                        static_cast<long long>(n), t_evt, t_bs, t_aevt, t_abs, nb / static_cast<double>(n), steps);
            std::fflush(stdout);
            std::fprintf(stderr, "progress %ld/%ld\n", ++done, total);
        }
    return 0;
}
