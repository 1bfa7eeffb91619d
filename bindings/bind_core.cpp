// The library's error policy in Python, and the version.
//
//   dvoronoi::CoincidentError -> dvoronoi.CoincidentError (a ValueError; `.indices` is the pair)
//   dvoronoi::InputError      -> ValueError
//   dvoronoi::Error           -> RuntimeError
// Messages are passed through unchanged (they name the argument, and the pair for coinciding agents),
// decoded as UTF-8 with any other byte as a \\xNN escape.
#include "dvoronoi/core/types.hpp"

#include <cstring>

#include <pybind11/gil_safe_call_once.h>
#include <pybind11/pybind11.h>

#ifndef DVORONOI_VERSION
#define DVORONOI_VERSION "0+unknown"
#endif

namespace py = pybind11;

namespace {

/// A message as a Python str: UTF-8, and any byte that is not (a file name, a line quoted from a
/// file) as a \xNN escape, so that the ValueError is raised rather than a UnicodeDecodeError.
py::str message(const char* what) {
    PyObject* s = PyUnicode_DecodeUTF8(what, static_cast<Py_ssize_t>(std::strlen(what)), "backslashreplace");
    if (!s) throw py::error_already_set();
    return py::reinterpret_steal<py::str>(s);
}

}  // namespace

void bind_core(py::module_& m) {
    m.attr("__version__") = DVORONOI_VERSION;

    PYBIND11_CONSTINIT static py::gil_safe_call_once_and_store<py::object> coincident;
    coincident.call_once_and_store_result([&]() -> py::object {
        return py::exception<dvoronoi::CoincidentError>(m, "CoincidentError", PyExc_ValueError);
    });
    m.attr("CoincidentError").attr("__doc__") =
        "Two agents coincide, so their Voronoi cells are undefined. A ValueError; `indices` is the "
        "pair (i, j), i < j, named in the message.";

    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const dvoronoi::CoincidentError& e) {
            const py::object& type = coincident.get_stored();
            py::object exc = type(message(e.what()));
            exc.attr("indices") = py::make_tuple(e.first(), e.second());
            PyErr_SetObject(type.ptr(), exc.ptr());
        } catch (const dvoronoi::InputError& e) {
            PyErr_SetObject(PyExc_ValueError, message(e.what()).ptr());
        } catch (const dvoronoi::Error& e) {
            PyErr_SetObject(PyExc_RuntimeError, message(e.what()).ptr());
        }
    });
}
