// numpy <-> Eigen glue shared by every bind_<area>.cpp.
//
// Input: an `n x 2` array of any memory layout binds as a PointsRef without a copy when its dtype is
// native float64 and its strides are non-negative multiples of 8 bytes; anything else numeric (ints,
// float32, Fortran order is fine already, negative strides, Python lists) is converted once. Shape and
// dtype errors name the argument. NaN/inf are left to the library, whose messages name the argument
// and the index.
//
// Output: `view()` hands out a read-only numpy array over memory owned by a bound C++ object; the
// object is the array's base, so the memory lives as long as any view of it.
#pragma once

#include "dvoronoi/core/types.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace dvoronoi_bindings {

namespace py = pybind11;
using dvoronoi::Index;
using dvoronoi::Points;
using dvoronoi::PointsRef;
using dvoronoi::Vec2;

/// "(5, 3)", numpy's spelling of a shape.
inline std::string shape_str(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) {
        if (d) s += ", ";
        s += std::to_string(a.shape(d));
    }
    if (a.ndim() == 1) s += ",";
    return s + ")";
}

/// Any array-like as a numpy array, or a TypeError naming the argument.
inline py::array as_array(py::handle obj, const char* name, const char* what) {
    if (py::isinstance<py::array>(obj)) return py::reinterpret_borrow<py::array>(obj);
    py::array arr = py::array::ensure(obj);
    if (!arr)
        throw py::type_error(std::string(name) + " must be " + what + ", got an object of type " +
                             std::string(py::str(py::type::handle_of(obj).attr("__name__"))) +
                             " that numpy cannot convert to an array");
    return arr;
}

/// True for native-byte-order float64, the dtype that binds without a copy.
inline bool is_float64(const py::array& arr) {
    // Created once and never destroyed (no Python object may be released after the interpreter).
    static const py::dtype* f64 = new py::dtype(py::dtype::of<double>());
    return arr.dtype().equal(*f64);
}

/// Numeric dtypes are converted to float64; anything else is a TypeError naming the argument.
inline py::array to_float64(const py::array& arr, const char* name, const char* what) {
    const char kind = arr.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'O')
        throw py::type_error(std::string(name) + " must be " + what + " of real numbers, got dtype " +
                             std::string(py::str(arr.dtype())));
    py::array out = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(arr);
    if (!out)
        throw py::type_error(std::string(name) + " must be " + what +
                             " of real numbers; its values do not convert to float64");
    return out;
}

/// An `n x 2` float64 array borrowed from numpy (or a converted copy), kept alive by `keep`.
struct PointsArg {
    py::array keep;
    const double* data = nullptr;
    Eigen::Index rows = 0;
    Eigen::Index row_stride = 2;  // in doubles
    Eigen::Index col_stride = 1;

    PointsRef ref() const {
        using DynStride = Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>;
        static const double none[2] = {0.0, 0.0};
        return PointsRef(Eigen::Map<const Points, 0, DynStride>(data ? data : none, rows, 2,
                                                               DynStride(row_stride, col_stride)));
    }
};

/// `obj` as an `n x 2` array of doubles. An empty 1-d array (`[]`) is the empty point set.
///
/// \throws ValueError naming `name` for a wrong shape; TypeError for a non-numeric dtype.
inline PointsArg points_arg(py::handle obj, const char* name) {
    static const char* what = "an (n, 2) array";
    PointsArg out;
    py::array arr = as_array(obj, name, what);
    if (arr.ndim() == 1 && arr.shape(0) == 0) {  // [] -> no agents
        out.keep = arr;
        return out;
    }
    if (arr.ndim() != 2 || arr.shape(1) != 2)
        throw py::value_error(std::string(name) + " must be an (n, 2) array, got shape " +
                              shape_str(arr));
    if (!is_float64(arr)) arr = to_float64(arr, name, what);

    const auto* ptr = static_cast<const double*>(arr.data());
    py::ssize_t s0 = arr.strides(0), s1 = arr.strides(1);
    const py::ssize_t rows = arr.shape(0);
    if (rows <= 1) s0 = 16;  // a length-1 axis may carry any stride
    const bool aligned = reinterpret_cast<std::uintptr_t>(ptr) % alignof(double) == 0;
    if (!aligned || s0 < 0 || s1 < 0 || s0 % 8 != 0 || s1 % 8 != 0) {
        arr = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(arr);
        ptr = static_cast<const double*>(arr.data());
        s0 = 16;
        s1 = 8;
    }
    out.keep = arr;
    out.data = ptr;
    out.rows = static_cast<Eigen::Index>(rows);
    out.row_stride = static_cast<Eigen::Index>(s0 / 8);
    out.col_stride = static_cast<Eigen::Index>(s1 / 8);
    return out;
}

/// One point (x, y): a 2-sequence or an array of shape (2,) or (1, 2).
///
/// \throws ValueError naming `name` for a wrong shape; TypeError for a non-numeric value.
inline Vec2 point_arg(py::handle obj, const char* name) {
    PyObject* o = obj.ptr();
    // Fast path: a tuple or list of two Python numbers (no numpy array is made).
    if ((PyTuple_Check(o) && PyTuple_GET_SIZE(o) == 2) || (PyList_Check(o) && PyList_GET_SIZE(o) == 2)) {
        PyObject* a = PySequence_Fast_GET_ITEM(o, 0);
        PyObject* b = PySequence_Fast_GET_ITEM(o, 1);
        if ((PyFloat_Check(a) || PyLong_Check(a)) && (PyFloat_Check(b) || PyLong_Check(b))) {
            const double x = PyFloat_AsDouble(a), y = PyFloat_AsDouble(b);
            if (!PyErr_Occurred()) return Vec2(x, y);
            PyErr_Clear();
        }
    }
    static const char* what = "a point (x, y)";
    py::array arr = as_array(obj, name, what);
    const bool ok_shape = (arr.ndim() == 1 && arr.shape(0) == 2) ||
                          (arr.ndim() == 2 && arr.shape(0) == 1 && arr.shape(1) == 2);
    if (!ok_shape)
        throw py::value_error(std::string(name) + " must be a point (x, y) of shape (2,), got shape " +
                              shape_str(arr));
    if (!is_float64(arr)) arr = to_float64(arr, name, what);
    const auto* ptr = static_cast<const char*>(arr.data());
    const py::ssize_t step = arr.ndim() == 1 ? arr.strides(0) : arr.strides(1);
    double x, y;
    std::memcpy(&x, ptr, sizeof(double));
    std::memcpy(&y, ptr + step, sizeof(double));
    return Vec2(x, y);
}

/// An (n, 2) array of finite points (a route to draw or write); none for None.
///
/// \throws ValueError naming `name` and the point with a non-finite coordinate, or a wrong shape.
inline std::vector<Vec2> finite_points_arg(py::handle obj, const char* name) {
    std::vector<Vec2> pts;
    if (obj.is_none()) return pts;
    PointsArg a = points_arg(obj, name);
    for (Eigen::Index k = 0; k < a.ref().rows(); ++k) {
        if (!std::isfinite(a.ref()(k, 0)) || !std::isfinite(a.ref()(k, 1)))
            throw py::value_error(std::string(name) + ": point " + std::to_string(k) + " has a non-finite coordinate");
        pts.emplace_back(a.ref()(k, 0), a.ref()(k, 1));
    }
    return pts;
}

/// A real number (a Python or numpy number, or anything with __float__ but a bool or a string) as a
/// double; a TypeError naming `name` otherwise (pybind11's own conversion error would list the call's
/// arguments, arrays included), a ValueError for an int beyond the range of a double.
inline double real_arg(py::handle obj, const char* name) {
    PyObject* o = obj.ptr();
    if (PyFloat_Check(o)) return PyFloat_AS_DOUBLE(o);
    if (PyBool_Check(o) || PyUnicode_Check(o) || PyBytes_Check(o) || !PyObject_HasAttrString(o, "__float__"))
        throw py::type_error(std::string(name) + " must be a real number, got " +
                             std::string(py::str(py::type::handle_of(obj).attr("__name__"))) + " " +
                             std::string(py::repr(obj)).substr(0, 60));
    const double v = PyFloat_AsDouble(o);
    if (v == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        throw py::value_error(std::string(name) + " is out of the range of a double");
    }
    return v;
}

/// A str as std::string; a TypeError naming `name` otherwise.
inline std::string str_arg(py::handle obj, const char* name) {
    if (!PyUnicode_Check(obj.ptr()))
        throw py::type_error(std::string(name) + " must be a string, got " +
                             std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
    return obj.cast<std::string>();
}

/// A read-only numpy view of `data` (shape, strides in bytes), kept alive by `owner`.
template <class T>
py::array view(const T* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides,
               py::handle owner) {
    static const T none{};
    py::array a(py::dtype::of<T>(), std::move(shape), std::move(strides), data ? data : &none, owner);
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return a;
}

/// A 1-d read-only view of a std::vector owned by `owner`.
template <class T>
py::array view(const std::vector<T>& v, py::handle owner) {
    return view(v.data(), {static_cast<py::ssize_t>(v.size())}, {static_cast<py::ssize_t>(sizeof(T))},
                owner);
}

/// An `n x 2` read-only view of a row-major Points matrix owned by `owner`.
inline py::array view(const Points& p, py::handle owner) {
    return view(p.data(), {static_cast<py::ssize_t>(p.rows()), 2},
                {static_cast<py::ssize_t>(2 * sizeof(double)), static_cast<py::ssize_t>(sizeof(double))},
                owner);
}

/// A new numpy array of T copied (and converted) from a vector.
template <class T, class U = T>
py::array copy_array(const std::vector<U>& v) {
    py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
    T* out = a.mutable_data();
    for (std::size_t k = 0; k < v.size(); ++k) out[k] = static_cast<T>(v[k]);
    return a;
}

/// A new (k, 2) float64 array of points.
inline py::array xy_array(const std::vector<Vec2>& v) {
    py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{2}});
    double* out = a.mutable_data();
    for (std::size_t k = 0; k < v.size(); ++k) {
        out[2 * k] = v[k].x();
        out[2 * k + 1] = v[k].y();
    }
    return a;
}

}  // namespace dvoronoi_bindings
