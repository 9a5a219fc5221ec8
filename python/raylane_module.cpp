// python: the module `raylane` (pybind11): scenes rendered to NumPy images, and batched ray
// queries against triangle meshes. Bad files raise raylane.Error (a ValueError) carrying the
// command line's one-line message; missing files FileNotFoundError.
#include <filesystem>

#include "core/error.h"
#include "python/bindings.h"
#include "simd/simd.h"

namespace raylane::python {

void require_file(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw MissingFile(join(path, ": no such file"));
}

}  // namespace raylane::python

PYBIND11_MODULE(raylane, m) {
    namespace py = pybind11;
    using namespace raylane::python;
    m.doc() =
        "Raylane: scenes rendered to NumPy images, and ray queries against triangle meshes on "
        "the SIMD packet path. See docs/python.md.";
    m.attr("__version__") = RAYLANE_VERSION;
    m.attr("packet_width") = raylane::native_width;
    py::register_exception<raylane::InputError>(m, "Error", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const MissingFile& e) {
            PyErr_SetString(PyExc_FileNotFoundError, e.what());
        } catch (const BadArgument& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });
    add_scene(m);
    add_mesh(m);
}
