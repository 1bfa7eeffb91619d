// `dvoronoi lloyd POINTS -r R --map MAP`: geodesic Lloyd on an occupancy grid (lloyd_map.cpp).
#pragma once

#include <string>
#include <vector>

namespace dvoronoi::cli {

struct LloydMapRequest {
    std::string points, columns, map, output;
    double radius = 0.0;  // geodesic range, map units; inf = unlimited
    bool radius_column = false;  // one range per agent from the point file (--columns X,Y,R)
    int steps = 100, threads = 0, record_every = 1;
    double gain = 1.0;
    double resolution = 0.0;  // images without YAML (0: not given)
    std::vector<double> origin;
    std::string unknown = "occupied";
    bool trajectory = false, quiet = false;
};

int run_lloyd_map(const LloydMapRequest& r);

}  // namespace dvoronoi::cli
