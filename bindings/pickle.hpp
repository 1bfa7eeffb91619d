// Pickling of compiled results: a result's state is (format version, dict of its fields as numpy
// arrays and numbers), so pickle, copy.deepcopy, joblib and multiprocessing work on every result, and
// a stored state says what it holds. Arrays are copied out and back in; nothing is recomputed.
#pragma once

#include "arrays.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace dvoronoi_bindings {

namespace py = pybind11;

/// Bumped when a pickled field changes meaning; older states are refused with a clear error.
constexpr int kPickleVersion = 1;

/// A new 1-d numpy array copied from a vector.
template <class T>
py::array_t<T> np_of(const std::vector<T>& v) {
    py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

/// A new (n, 2) float64 array copied from points.
inline py::array_t<double> np_of(const Points& p) {
    py::array_t<double> a({static_cast<py::ssize_t>(p.rows()), py::ssize_t{2}});
    std::copy(p.data(), p.data() + 2 * p.rows(), a.mutable_data());
    return a;
}

/// The pickled dict of a `type` state, its version checked.
inline py::dict state_dict(const py::tuple& t, const char* type) {
    if (t.size() != 2 || !py::isinstance<py::int_>(t[0]) || !py::isinstance<py::dict>(t[1]))
        throw py::value_error(std::string("not a pickled ") + type + " state");
    const int version = t[0].cast<int>();
    if (version != kPickleVersion)
        throw py::value_error(std::string("a pickled ") + type + " of format " + std::to_string(version) +
                              "; this dvoronoi reads format " + std::to_string(kPickleVersion));
    return t[1].cast<py::dict>();
}

inline py::tuple make_state(const py::dict& d) { return py::make_tuple(kPickleVersion, d); }

/// Field `key` of a state as a vector.
template <class T>
std::vector<T> vec_of(const py::dict& d, const char* key) {
    const auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(d[key]);
    if (!a || a.ndim() != 1) throw py::value_error(std::string("pickled field ") + key + " is not a 1-d array");
    return std::vector<T>(a.data(), a.data() + a.size());
}

/// Field `key` of a state as (n, 2) points.
inline Points points_of(const py::dict& d, const char* key) {
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(d[key]);
    if (!a || a.ndim() != 2 || a.shape(1) != 2) throw py::value_error(std::string("pickled field ") + key + " is not an (n, 2) array");
    Points p(a.shape(0), 2);
    std::copy(a.data(), a.data() + a.size(), p.data());
    return p;
}

inline Vec2 vec2_of(const py::dict& d, const char* key) {
    const auto v = vec_of<double>(d, key);
    if (v.size() != 2) throw py::value_error(std::string("pickled field ") + key + " is not a point");
    return Vec2(v[0], v[1]);
}

inline py::array_t<double> np_of(const Vec2& v) { return np_of(std::vector<double>{v.x(), v.y()}); }

/// (n, 2) points back into a vector of Vec2 (written with arrays.hpp's xy_array).
inline std::vector<Vec2> vec2s_of(const py::dict& d, const char* key) {
    const Points p = points_of(d, key);
    std::vector<Vec2> out;
    for (Eigen::Index k = 0; k < p.rows(); ++k) out.emplace_back(p(k, 0), p(k, 1));
    return out;
}

}  // namespace dvoronoi_bindings
