// python: the module `raylane` (pybind11): scenes rendered to NumPy images, and batched ray
// queries against triangle meshes. Bad files raise raylane.Error (a ValueError) carrying the
// command line's one-line message; missing files FileNotFoundError.
#include <filesystem>

#include "core/error.h"
#include "core/isa.h"
#include "python/bindings.h"

namespace raylane::python {

namespace {

py::list isa_names(const std::vector<Isa>& sets) {
    py::list names;
    for (Isa isa : sets) names.append(isa_name(isa));
    return names;
}

}  // namespace

void add_isa(py::module_& m) {
    m.def(
        "instruction_sets",
        [] {
            std::vector<Isa> compiled, cpu;
            for (Isa isa : all_isas) {
                if (isa_compiled(isa)) compiled.push_back(isa);
                if (cpu_runs(isa)) cpu.push_back(isa);
            }
            const Isa in_use = active_isa();
            py::dict d;
            d["compiled"] = isa_names(compiled);
            d["cpu"] = isa_names(cpu);
            d["in_use"] = isa_name(in_use);
            d["packet_width"] = isa_width(in_use);
            return d;
        },
        "The packet path's instruction sets: 'compiled' (in this module), 'cpu' (those this CPU "
        "runs), 'in_use' (RAYLANE_ISA's, or use_isa's, else the widest) and its 'packet_width'.");
    m.def(
        "use_isa",
        [](const std::string& name) {
            if (name.empty())  // use_isa_named leaves the choice as it is for an empty name
                throw InputError(
                    join("use_isa: unknown instruction set '' (sets: sse4.2, avx2, "
                         "avx512; this machine runs: ",
                         runnable_isa_names(), ")"));
            use_isa_named(name, "use_isa");
        },
        py::arg("name"),
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
    m.attr("__version__") = RAYLANE_VERSION;
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
    add_isa(m);
}
