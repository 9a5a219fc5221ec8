// python: the module `raylane` (pybind11): scenes rendered to NumPy images, and batched ray
// queries against triangle meshes. Bad files raise raylane.Error (a ValueError) carrying the
// command line's one-line message; missing files FileNotFoundError.
#include <filesystem>

#include "python/bindings.h"
#include "raylane/raylane.h"

namespace raylane::python {

void add_isa(py::module_& m) {
    m.def(
        "instruction_sets",
        [] {
            py::dict d;
            d["compiled"] = compiled_instruction_sets();
            d["cpu"] = cpu_instruction_sets();
            d["in_use"] = instruction_set();
            d["packet_width"] = packet_width();
            return d;
        },
        "The packet path's instruction sets: 'compiled' (in this module), 'cpu' (those this CPU "
        "runs), 'in_use' (RAYLANE_ISA's, or use_isa's, else the widest) and its 'packet_width'.");
    m.def(
        "use_isa", [](const std::string& name) { use_instruction_set(name); }, py::arg("name"),
        "Uses the instruction set `name` ('sse4.2', 'avx2' or 'avx512') from now on; "
        "raylane.Error (a ValueError) when it is unknown or this CPU does not run it.");
}

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
    m.attr("__version__") = raylane::version();
    py::register_exception<raylane::Error>(m, "Error", PyExc_ValueError);
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
    add_isa(m);
}
