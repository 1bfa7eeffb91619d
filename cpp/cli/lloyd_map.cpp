// `dvoronoi lloyd POINTS -r R --map MAP`: Lloyd coverage on geodesic cells of an occupancy grid (ROS YAML,
// PGM, PNG or MovingAI .map, read as `dvoronoi gvd MAP` reads it); the run as JSON.
#include "lloyd_map.hpp"

#include "common.hpp"

#include "dvoronoi/coverage/geodesic_lloyd.hpp"
#include "dvoronoi/io/occupancy_map.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

namespace dvoronoi::cli {

int run_lloyd_map(const LloydMapRequest& r) {
    if (!r.radius_column && (std::isnan(r.radius) || !(r.radius > 0.0)))
        throw UsageError("--radius: with --map, the geodesic range: a positive number or inf, got " + show(r.radius));
    if (!(r.gain > 0.0 && r.gain <= 1.0)) throw UsageError("--gain: must be in (0, 1], got " + show(r.gain));
    if (r.steps < 0) throw UsageError("--steps: must be >= 0, got " + std::to_string(r.steps));
    if (r.record_every < 1) throw UsageError("--svg-every: must be >= 1, got " + std::to_string(r.record_every));
    const std::string ext = io::detail::lower_ext(r.map);
    if ((ext == ".yaml" || ext == ".yml") && (r.resolution > 0 || !r.origin.empty()))
        throw UsageError("--resolution/--origin: a map_server YAML brings its own resolution and origin");
    if (ext == ".map" && r.unknown != "occupied") throw UsageError("--unknown: a MovingAI map has no unknown cells");
    const bool to_stdout = r.output.empty() || r.output == "-";
    if (!to_stdout && lower_extension(r.output) != ".json")
        throw UsageError("-o/--output: the run is written as JSON; use a .json file name or '-', got '" + r.output + "'");

    check_outputs(r.output, "", {{r.points, "POINTS"}, {r.map, "--map"}});

    io::MapReadOptions ro;
    ro.unknown_occupied = r.unknown == "occupied";
    if (r.resolution > 0) ro.resolution = r.resolution;
    if (!r.origin.empty()) ro.origin = Vec2(r.origin[0], r.origin[1]);
    const io::LoadedMap map = io::read_occupancy_map(r.map, ro);
    const gvd::OccupancyGrid& g = map.grid;
    const coverage::MapFrame frame{g.rows, g.cols, g.resolution, g.origin.x(), g.origin.y()};

    const io::PointFile file = read_points_argument(r.points, r.columns, true);
    std::vector<double> xy;
    for (Index i = 0; i < file.points.rows(); ++i) {
        xy.push_back(file.points(i, 0));
        xy.push_back(file.points(i, 1));
    }
    std::vector<coverage::PixelPoint> agents;
    try {
        agents = coverage::agents_on_map(g.occupied.data(), frame, xy.data(), file.points.rows());
    } catch (const std::invalid_argument& e) {
        throw InputError(file.name + ": " + e.what() + " (--map " + r.map + ")");
    }
    std::unique_ptr<io::AtomicFile> out;
    if (!to_stdout) out = open_output(r.output, "-o/--output");

    const int workers = r.threads == 0 ? static_cast<int>(std::max(1u, std::thread::hardware_concurrency())) : r.threads;
    double limit = std::isinf(r.radius) ? std::numeric_limits<double>::infinity() : r.radius / g.resolution;
    std::vector<double> ranges;  // a heterogeneous team's ranges, pixel units
    if (r.radius_column) {
        for (const double R : file.radii) ranges.push_back(R / g.resolution);
        limit = ranges.empty() ? 1.0 : *std::max_element(ranges.begin(), ranges.end());
    }
    coverage::GeodesicLloyd lloyd({g.occupied.begin(), g.occupied.end()}, g.rows, g.cols, std::move(agents), limit, {}, r.gain, workers, 12, ranges);
    const double area2 = std::pow(g.resolution, 4);  // cost: pixel units -> map units
    auto map_points = [&](const std::vector<coverage::PixelPoint>& pts) {
        nlohmann::json a = nlohmann::json::array();
        for (const auto& p : pts) {
            double x, y;
            frame.to_map(p, x, y);
            a.push_back({x, y});
        }
        return a;
    };
    std::vector<double> cost;
    nlohmann::json frames = nlohmann::json::array({map_points(lloyd.points())});
    std::vector<int> frame_steps{0};
    Progress progress("lloyd steps", r.steps, r.quiet, 1);
    for (int t = 0; t < r.steps; ++t) {
        cost.push_back(lloyd.step() * area2);
        if ((t + 1) % r.record_every == 0 || t + 1 == r.steps) {
            if (r.trajectory) frames.push_back(map_points(lloyd.points()));
            frame_steps.push_back(t + 1);
        }
        progress(t + 1, r.steps);
    }
    cost.push_back(lloyd.cost() * area2);
    progress.finish();

    const auto& m = lloyd.moments();
    nlohmann::json areas = nlohmann::json::array(), centroids = nlohmann::json::array();
    for (std::size_t i = 0; i < m.mass.size(); ++i) {
        areas.push_back(double(m.pixels[i]) * g.resolution * g.resolution);
        const coverage::PixelPoint c = m.mass[i] > 0 ? coverage::PixelPoint{m.mu[i] / m.mass[i], m.mw[i] / m.mass[i]}
                                                     : lloyd.points()[i];
        double x, y;
        frame.to_map(c, x, y);
        centroids.push_back({x, y});
    }
    nlohmann::json doc;
    doc["map"] = r.map;
    doc["shape"] = {g.rows, g.cols};
    doc["resolution"] = g.resolution;
    doc["origin"] = {g.origin.x(), g.origin.y()};
    if (r.radius_column) {
        doc["radius"] = file.radii.empty() ? nlohmann::json(nullptr)
                                           : nlohmann::json(*std::max_element(file.radii.begin(), file.radii.end()));
        doc["radii"] = file.radii;
    } else {
        doc["radius"] = std::isinf(r.radius) ? nlohmann::json(nullptr) : nlohmann::json(r.radius);
    }
    doc["gain"] = r.gain;
    doc["steps"] = r.steps;
    doc["cost"] = cost;
    doc["points"] = map_points(lloyd.points());
    doc["areas"] = areas;
    doc["centroids"] = centroids;
    if (r.trajectory) {
        doc["frame_steps"] = frame_steps;
        doc["trajectory"] = frames;
    }
    const std::string text = doc.dump() + "\n";
    std::unique_ptr<io::AtomicFile> no_svg;
    return deliver(out, no_svg, [&](std::ostream& os) { os << text; });
}

}  // namespace dvoronoi::cli
