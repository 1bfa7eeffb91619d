// dvoronoi._core: the compiled half of the Python package. Each area of the library binds itself in
// its own bind_<area>.cpp; this file only assembles them.
#include <pybind11/pybind11.h>

namespace py = pybind11;

void bind_core(py::module_& m);
void bind_cells(py::module_& m);
void bind_voronoi(py::module_& m);
void bind_gvd(py::module_& m);
void bind_gvd_occupancy(py::module_& m);
void bind_distances(py::module_& m);
void bind_coverage(py::module_& m);
void bind_network(py::module_& m);
void bind_geodesic(py::module_& m);

PYBIND11_MODULE(_core, m) {
    m.doc() = "dvoronoi compiled core (use the `dvoronoi` package, which re-exports it).";
    bind_core(m);
    bind_cells(m);
    bind_voronoi(m);
    bind_gvd(m);
    bind_gvd_occupancy(m);
    bind_distances(m);
    bind_coverage(m);
    bind_network(m);
    bind_geodesic(m);
}
