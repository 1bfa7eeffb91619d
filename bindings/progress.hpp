// A Python progress callback handed to the library's parallel drivers, shared by every bind_<area>.cpp.
//
// The callback runs with the GIL re-acquired and checks for signals (Ctrl-C). A Python exception
// must not unwind through the library's OpenMP region, so it is kept (later calls do nothing) and
// re-raised after the computation.
#pragma once

#include "dvoronoi/core/parallel.hpp"

#include <pybind11/pybind11.h>

#include <optional>
#include <utility>

namespace dvoronoi_bindings {

namespace py = pybind11;

class PyProgress {
public:
    explicit PyProgress(py::object progress) : progress_(std::move(progress)) {}

    /// The C++ callback (empty when `progress` is None). Valid while this object lives.
    dvoronoi::ProgressFn fn() {
        if (progress_.is_none()) return {};
        return [this](dvoronoi::Index done, dvoronoi::Index total) {
            py::gil_scoped_acquire gil;
            if (failure_) return;
            try {
                if (PyErr_CheckSignals() != 0) throw py::error_already_set();
                progress_(done, total);
            } catch (py::error_already_set& e) {
                failure_.emplace(std::move(e));
            } catch (const std::exception& e) {
                PyErr_SetString(PyExc_RuntimeError, e.what());
                failure_.emplace();
            }
        };
    }

    /// After the computation (GIL held): re-raise the callback's exception, if any.
    void rethrow() {
        if (failure_) throw std::move(*failure_);
    }

private:
    py::object progress_;
    std::optional<py::error_already_set> failure_;
};

}  // namespace dvoronoi_bindings
