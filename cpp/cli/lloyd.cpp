// `dvoronoi lloyd POINTS -r R --steps K`: Lloyd coverage control on limited cells (uniform density),
// optionally in a convex environment, with the run as JSON and the cells of each step as SVG files.
#include "common.hpp"
#include "lloyd_map.hpp"

#include "dvoronoi/coverage/lloyd.hpp"
#include "dvoronoi/io/svg.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dvoronoi::cli {
namespace {

struct LloydOptions {
    std::string points;
    double radius = 0.0;
    bool radius_given = false;
    int steps = 100;
    double gain = 1.0;
    std::vector<double> bounds;
    std::string polygon;
    std::string columns;
    int threads = 0;
    std::string output;
    std::string svg_dir;
    int svg_every = 1;
    bool trajectory = false;
    bool quiet = false;
    LloydMapRequest map;  // --map: geodesic cells on an occupancy grid (lloyd_map.cpp)
};

std::optional<ConvexPolygon> environment(const LloydOptions& o) {
    if (!o.bounds.empty() && !o.polygon.empty())
        throw UsageError("--bounds and --polygon: give one environment, not both");
    if (!o.bounds.empty()) {
        if (o.bounds.size() != 4)
            throw UsageError("--bounds: expected 4 numbers XMIN YMIN XMAX YMAX, got " +
                             std::to_string(o.bounds.size()));
        try {
            return ConvexPolygon::box(o.bounds[0], o.bounds[1], o.bounds[2], o.bounds[3], "--bounds");
        } catch (const InputError& e) {
            throw UsageError(e.what());
        }
    }
    if (!o.polygon.empty()) {
        const io::PointFile f = io::read_point_file(o.polygon, io::Columns{});
        std::vector<Vec2> v;
        for (Index i = 0; i < f.points.rows(); ++i) v.push_back(f.points.row(i).transpose());
        return ConvexPolygon(std::move(v), o.polygon);
    }
    return std::nullopt;
}

nlohmann::json points_json(const Points& p) {
    nlohmann::json a = nlohmann::json::array();
    for (Index i = 0; i < p.rows(); ++i) a.push_back({p(i, 0), p(i, 1)});
    return a;
}

/// The picture of step `step` in --svg-dir.
std::string frame_path(const LloydOptions& o, int step) {
    char name[32];
    std::snprintf(name, sizeof name, "step_%06d.svg", step);
    return (std::filesystem::path(o.svg_dir) / name).string();
}

/// Refuses an --svg-dir whose pictures (steps 0, every --svg-every and the last) would replace an input.
void check_frames(const LloydOptions& o, const std::vector<ReadFile>& inputs) {
    if (o.svg_dir.empty()) return;
    for (const ReadFile& in : inputs) {
        int step = -1;
        const std::string name = std::filesystem::path(in.path).filename().string();
        if (in.path.empty() || in.path == "-" || std::sscanf(name.c_str(), "step_%d", &step) != 1 || step < 0 || step > o.steps ||
            (step != 0 && step != o.steps && step % o.svg_every != 0))
            continue;
        if (same_file(frame_path(o, step), in.path))
            throw UsageError("--svg-dir: the picture '" + frame_path(o, step) + "' is the same file as " + in.name + " ('" +
                             in.path + "'): an output may not overwrite an input");
    }
}

int run_lloyd(const LloydOptions& o) {
    // --columns X,Y,R reads one sensing radius per agent (a heterogeneous team); otherwise --radius.
    const bool radius_column = !o.columns.empty() && io::parse_columns(o.columns, "--columns", true).has_radius();
    if (radius_column && o.radius_given)
        throw UsageError("--radius: not with a radius column (--columns X,Y,R); give one or the other");
    if (!radius_column && !o.radius_given)
        throw UsageError("--radius: required (or one radius per agent with --columns X,Y,R)");
    if (!o.map.map.empty()) {
        if (!o.bounds.empty() || !o.polygon.empty()) throw UsageError("--map: give the environment as --map or --bounds/--polygon, not both");
        if (!o.svg_dir.empty()) throw UsageError("--svg-dir: not drawn for --map runs (Python's run.animate draws them)");
        LloydMapRequest r = o.map;
        r.points = o.points, r.columns = o.columns, r.output = o.output, r.radius = o.radius, r.steps = o.steps;
        r.radius_column = radius_column;
        r.threads = o.threads, r.record_every = o.svg_every, r.gain = o.gain, r.trajectory = o.trajectory, r.quiet = o.quiet;
        return run_lloyd_map(r);
    }
    if (!o.map.origin.empty() || o.map.resolution > 0) throw UsageError("--resolution/--origin: only with --map");
    if (o.radius_given && (!std::isfinite(o.radius) || !(o.radius > 0.0)))
        throw UsageError("--radius: must be a positive finite number, got " + show(o.radius));
    if (!(o.gain > 0.0 && o.gain <= 1.0))
        throw UsageError("--gain: must be in (0, 1], got " + show(o.gain));
    if (o.steps < 0) throw UsageError("--steps: must be >= 0, got " + std::to_string(o.steps));
    if (o.svg_every < 1) throw UsageError("--svg-every: must be >= 1, got " + std::to_string(o.svg_every));
    const bool to_stdout = o.output.empty() || o.output == "-";
    if (!to_stdout && lower_extension(o.output) != ".json")
        throw UsageError("-o/--output: the run is written as JSON; use a .json file name or '-', got '" +
                         o.output + "'");
    const std::vector<ReadFile> inputs = {{o.points, "POINTS"}, {o.polygon, "--polygon"}};
    check_outputs(o.output, "", inputs);
    check_frames(o, inputs);
    std::optional<ConvexPolygon> env = environment(o);

    const io::PointFile file = read_points_argument(o.points, o.columns, true);
    if (env)
        for (Index i = 0; i < file.points.rows(); ++i)
            if (!env->contains(file.points.row(i).transpose()))
                throw InputError(file.where(i) + ": point " + std::to_string(i) +
                                 " lies outside the environment");
    if (!o.svg_dir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(o.svg_dir, ec);
        if (ec || !std::filesystem::is_directory(o.svg_dir))
            throw UsageError("--svg-dir: cannot create directory '" + o.svg_dir + "'");
    }
    std::unique_ptr<io::AtomicFile> out;
    if (!to_stdout) out = open_output(o.output, "-o/--output");

    // The whole run first (positions kept for the pictures), outputs only once it succeeded.
    LloydStepper stepper = radius_column ? LloydStepper(file.points, file.radii, env, o.gain, o.threads)
                                         : LloydStepper(file.points, o.radius, env, o.gain, o.threads);
    const std::vector<double>& radii = stepper.radii().by_row();  // empty unless the radii differ
    std::vector<Points> frames{stepper.points()};
    std::vector<int> frame_steps{0};
    std::vector<double> cost;
    Progress progress("lloyd steps", o.steps, o.quiet, 1);
    try {
        for (int t = 0; t < o.steps; ++t) {
            cost.push_back(stepper.step());
            if ((t + 1) % o.svg_every == 0 || t + 1 == o.steps) {
                if (!o.svg_dir.empty() || o.trajectory) frames.push_back(stepper.points());
                frame_steps.push_back(t + 1);
            }
            progress(t + 1, o.steps);
        }
        cost.push_back(stepper.cost());
    } catch (const CoincidentError& e) {
        progress.abort();
        throw InputError(file.name + ": " + e.what() + " during the run (step " +
                         std::to_string(cost.size()) + ")");
    } catch (...) {
        progress.abort();
        throw;
    }
    progress.finish();

    if (!o.svg_dir.empty()) {
        Progress pictures("svg frames", static_cast<Index>(frames.size()), o.quiet, 1);
        for (std::size_t k = 0; k < frames.size(); ++k) {
            const Swarm swarm(frames[k], stepper.radius());
            const AgentRadii team = radii.empty() ? AgentRadii{} : AgentRadii(swarm, radii);
            const LimitedPartition cells = coverage_cells(swarm, team, stepper.environment(), -1, o.threads);
            io::AtomicFile f(frame_path(o, frame_steps[k]));
            io::write_svg(f.stream(), cells);
            f.commit();
            pictures(static_cast<Index>(k + 1), static_cast<Index>(frames.size()));
        }
        pictures.finish();
    }

    nlohmann::json doc;
    doc["kind"] = "lloyd";  // the result type, as in every result JSON (dv.load reads it back)
    doc["radius"] = stepper.radius();  // the largest of a heterogeneous team, whose "radii" follow
    if (!radii.empty()) doc["radii"] = radii;
    doc["gain"] = o.gain;
    doc["steps"] = o.steps;
    doc["bounds"] = nullptr;
    if (env) {
        nlohmann::json b = nlohmann::json::array();
        for (const Vec2& v : env->vertices()) b.push_back({v.x(), v.y()});
        doc["bounds"] = b;
    }
    doc["cost"] = cost;
    doc["points"] = points_json(stepper.points());
    if (o.trajectory) {
        doc["frame_steps"] = frame_steps;
        nlohmann::json t = nlohmann::json::array();
        for (const Points& p : frames) t.push_back(points_json(p));
        doc["trajectory"] = t;
    }
    const std::string text = doc.dump() + "\n";
    std::unique_ptr<io::AtomicFile> no_svg;
    return deliver(out, no_svg, [&](std::ostream& os) { os << text; });
}

}  // namespace

Command add_lloyd(CLI::App& parent) {
    auto o = std::make_shared<LloydOptions>();
    CLI::App* sub = parent.add_subcommand(
        "lloyd",
        "Lloyd coverage control on limited cells (Cortes, Martinez & Bullo 2005): each agent moves "
        "--gain of the way to the centroid of its cell (uniform density), optionally clipped to a "
        "convex environment; writes the cost per step and the final positions as JSON. With --columns X,Y,R "
        "each agent has its own sensing radius (Pimenta et al. 2008: power cells clipped to the disks)");
    add_points_options(sub, o->points, o->columns, o->threads);
    sub->add_option_function<double>(
        "-r,--radius",
        [o](const double& r) {
            o->radius = r;
            o->radius_given = true;
        },
        "cell radius R > 0; or one radius per agent from the file with --columns X,Y,R");
    sub->add_option("--steps", o->steps, "number of Lloyd steps")->capture_default_str();
    sub->add_option("--gain", o->gain, "fraction of the way to the centroid per step, in (0, 1]")
        ->capture_default_str();
    sub->add_option("--bounds", o->bounds, "box environment XMIN YMIN XMAX YMAX (agents must start in it)")
        ->expected(4);
    sub->add_option("--polygon", o->polygon, "convex polygon environment: a point file of its vertices in order");
    sub->add_option("-o,--output", o->output, "JSON file for the run (default or '-': stdout)");
    sub->add_option("--svg-dir", o->svg_dir,
                    "draw the cells into DIR/step_NNNNNN.svg (every --svg-every steps and the last)");
    sub->add_option("--svg-every", o->svg_every, "steps between pictures and trajectory frames")
        ->capture_default_str();
    sub->add_flag("--trajectory", o->trajectory, "include the recorded positions in the JSON");
    sub->add_flag("-q,--quiet", o->quiet, "no progress counter on stderr");
    sub->add_option("--map", o->map.map,
                    "occupancy grid (ROS YAML, PGM, PNG, MovingAI .map): geodesic cells, agents move around walls; "
                    "-r is then the geodesic range (inf: none)");
    sub->add_option("--resolution", o->map.resolution, "--map images without YAML: map units per pixel (default 1)");
    sub->add_option("--origin", o->map.origin, "--map images without YAML: map coordinates X Y of the lower-left corner")
        ->expected(2);
    sub->add_option("--unknown", o->map.unknown, "--map: unknown pixels count as occupied or free")
        ->check(CLI::IsMember({"occupied", "free"}))
        ->capture_default_str();
    return {sub, [o] { return run_lloyd(*o); }};
}

}  // namespace dvoronoi::cli
