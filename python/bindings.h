// python: what the module's files share: the functions that add each part of the module, and
// the errors the module raises besides raylane.Error (InputError).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <stdexcept>
#include <string>

namespace raylane::python {

namespace py = pybind11;

/// Becomes FileNotFoundError.
struct MissingFile : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Becomes ValueError (argument checks; raylane.Error is for bad files).
struct BadArgument : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

/// The pieces one after the other, by append (GCC 12 warns falsely on chains of operator+).
template <class... Pieces>
std::string join(const Pieces&... pieces) {
    std::string s;
    (s.append(pieces), ...);
    return s;
}

/// Throws MissingFile "path: no such file" unless `path` names an existing file or folder.
void require_file(const std::string& path);

/// load_scene and Scene (scene_binding.cpp).
void add_scene(py::module_& m);
/// Mesh, load_mesh and save_rays (mesh_binding.cpp).
void add_mesh(py::module_& m);
/// instruction_sets and use_isa (raylane_module.cpp).
void add_isa(py::module_& m);

}  // namespace raylane::python
