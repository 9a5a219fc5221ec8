// python: raylane.Mesh and raylane.load_mesh: ray queries against a triangle mesh from NumPy
// arrays, over the library's raylane::Mesh (raylane/mesh.h), and raylane.save_rays, the ray
// file of bench_intersect.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "python/bindings.h"
#include "raylane/error.h"
#include "raylane/mesh.h"

namespace raylane::python {
namespace {

std::string shape_text(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t k = 0; k < a.ndim(); ++k) {
        if (k > 0) s.append(", ");
        s.append(std::to_string(a.shape(k)));
    }
    if (a.ndim() == 1) s.append(",");
    return s.append(")");
}

std::string dtype_text(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

py::array as_array(const py::handle& obj, const char* name) {
    if (!py::isinstance<py::array>(obj)) {
        std::string m = name;
        throw BadArgument(m.append(": expected a NumPy array, got ")
                              .append(py::str(py::type::of(obj).attr("__name__"))));
    }
    return py::reinterpret_borrow<py::array>(obj);
}

void require_shape(const py::array& a, const char* name, py::ssize_t cols) {
    if (a.ndim() != 2 || a.shape(1) != cols) {
        std::string m = name;
        m.append(": shape ").append(shape_text(a)).append(", expected (N, ");
        throw BadArgument(m.append(std::to_string(cols)).append(")"));
    }
}

/// Element (i, j) of a 2-D array of any strides as T.
template <class T, class Out>
Out element(const py::array& a, py::ssize_t i, py::ssize_t j) {
    const auto* p = static_cast<const char*>(a.data()) + i * a.strides(0) + j * a.strides(1);
    T v;
    std::memcpy(&v, p, sizeof v);
    return static_cast<Out>(v);
}

/// Row i of an integer array of any integer dtype and any strides.
bool read_index_row(const py::array& a, py::ssize_t i, int64_t (&row)[3]) {
    const char kind = a.dtype().kind();
    const auto size = a.itemsize();
    for (py::ssize_t j = 0; j < 3; ++j) {
        if (kind == 'i' && size == 8)
            row[j] = element<int64_t, int64_t>(a, i, j);
        else if (kind == 'i' && size == 4)
            row[j] = element<int32_t, int64_t>(a, i, j);
        else if (kind == 'i' && size == 2)
            row[j] = element<int16_t, int64_t>(a, i, j);
        else if (kind == 'i' && size == 1)
            row[j] = element<int8_t, int64_t>(a, i, j);
        else if (kind == 'u' && size == 4)
            row[j] = element<uint32_t, int64_t>(a, i, j);
        else if (kind == 'u' && size == 2)
            row[j] = element<uint16_t, int64_t>(a, i, j);
        else if (kind == 'u' && size == 1)
            row[j] = element<uint8_t, int64_t>(a, i, j);
        else if (kind == 'u' && size == 8) {
            const uint64_t v = element<uint64_t, uint64_t>(a, i, j);
            row[j] = v > uint64_t(INT64_MAX) ? INT64_MAX : int64_t(v);
        } else {
            return false;
        }
    }
    return true;
}

std::shared_ptr<Mesh> mesh_from_arrays(const py::object& vertices_obj,
                                       const py::object& triangles_obj) {
    const py::array vertices = as_array(vertices_obj, "vertices");
    const py::array triangles = as_array(triangles_obj, "triangles");
    require_shape(vertices, "vertices", 3);
    require_shape(triangles, "triangles", 3);
    if (!vertices.dtype().is(py::dtype::of<float>()))
        throw BadArgument(join("vertices: dtype ", dtype_text(vertices),
                               ", expected float32 (vertices.astype(numpy.float32))"));
    const char kind = triangles.dtype().kind();
    if (kind != 'i' && kind != 'u')
        throw BadArgument(join("triangles: dtype ", dtype_text(triangles),
                               ", expected an integer type (int32, int64, uint32, ...)"));
    const py::ssize_t n = vertices.shape(0), m = triangles.shape(0);
    if (n > py::ssize_t(UINT32_MAX))
        throw BadArgument(join("vertices: ", std::to_string(n), " rows, more than 2^32 - 1"));
    // copied once into the library's layout: float32 (N, 3) and uint32 (M, 3), row by row
    std::vector<float> points(size_t(n) * 3);
    for (py::ssize_t i = 0; i < n; ++i)
        for (py::ssize_t j = 0; j < 3; ++j)
            points[size_t(3 * i + j)] = element<float, float>(vertices, i, j);
    std::vector<uint32_t> corners(size_t(m) * 3);
    for (py::ssize_t i = 0; i < m; ++i) {
        int64_t row[3];
        read_index_row(triangles, i, row);
        for (int j = 0; j < 3; ++j) {
            if (row[j] < 0 || row[j] >= n) {
                std::string msg = "triangles: row ";
                msg.append(std::to_string(i))
                    .append(" holds index ")
                    .append(std::to_string(row[j]));
                msg.append(", outside 0 .. ").append(std::to_string(n - 1));
                throw BadArgument(
                    msg.append(" (vertices has ").append(std::to_string(n)).append(" rows)"));
            }
            corners[size_t(3 * i + j)] = static_cast<uint32_t>(row[j]);
        }
    }
    py::gil_scoped_release release;
    return std::make_shared<Mesh>(points.data(), size_t(n), corners.data(), size_t(m));
}

std::shared_ptr<Mesh> load_mesh_file(const std::string& path) {
    std::string file = path;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec) && std::filesystem::path(path).is_relative()) {
        try {  // a model name on RAYLANE_MODEL_PATH, as scenes name them
            file = find_model(path);
        } catch (const Error& e) {
            throw MissingFile(e.what());
        }
    }
    require_file(file);
    py::gil_scoped_release release;
    return std::make_shared<Mesh>(Mesh::load(file));
}

/// An (N, cols) array of rays' floats: read in place when it is float32 with its columns next
/// to each other; otherwise copied once to a contiguous float32 array (`keep` holds it).
struct FloatRows {
    const float* data = nullptr;
    size_t stride = 0;  ///< floats from one row to the next
    size_t rows = 0;
    py::array keep;
};

FloatRows float_rows(const py::object& obj, const char* name, py::ssize_t cols) {
    py::array a = as_array(obj, name);
    require_shape(a, name, cols);
    const char kind = a.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        throw BadArgument(join(name, ": dtype ", dtype_text(a), ", expected float32"));
    const bool in_place = a.dtype().is(py::dtype::of<float>()) && a.strides(1) == 4 &&
                          a.strides(0) >= 0 && a.strides(0) % 4 == 0;
    if (!in_place) a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
    FloatRows r;
    r.rows = size_t(a.shape(0));
    r.data = static_cast<const float*>(a.data());
    r.stride = in_place ? size_t(a.strides(0) / 4) : size_t(cols);
    r.keep = a;
    return r;
}

/// The rays of intersect / occluded: (origins, directions) or one (N, 6) array, and t_max as a
/// number or an (N,) array.
struct RayInput {
    Rays rays;
    FloatRows org, dir, t_max;
};

RayInput ray_input(const py::object& origins, const py::object& directions,
                   const py::object& tmax) {
    RayInput in;
    if (directions.is_none()) {
        in.org = float_rows(origins, "rays", 6);
        in.rays.origins = in.org.data;
        in.rays.directions = in.org.data + 3;
        in.rays.origin_stride = in.rays.direction_stride = in.org.stride * sizeof(float);
    } else {
        in.org = float_rows(origins, "origins", 3);
        in.dir = float_rows(directions, "directions", 3);
        if (in.org.rows != in.dir.rows)
            throw BadArgument(join("origins and directions: ", std::to_string(in.org.rows), " and ",
                                   std::to_string(in.dir.rows), " rows, expected the same"));
        in.rays.origins = in.org.data;
        in.rays.directions = in.dir.data;
        in.rays.origin_stride = in.org.stride * sizeof(float);
        in.rays.direction_stride = in.dir.stride * sizeof(float);
    }
    in.rays.count = in.org.rows;
    if (py::isinstance<py::array>(tmax)) {
        py::array a = py::reinterpret_borrow<py::array>(tmax);
        if (a.ndim() == 1) {
            if (size_t(a.shape(0)) != in.rays.count)
                throw BadArgument(join("tmax: ", std::to_string(a.shape(0)), " values for ",
                                       std::to_string(in.rays.count), " rays"));
            a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
            in.t_max.keep = a;
            in.rays.t_max = static_cast<const float*>(a.data());
            return in;
        }
        if (a.ndim() != 0)
            throw BadArgument(join("tmax: shape ", shape_text(a), ", expected a number or (N,)"));
    }
    in.rays.t_max_all = tmax.cast<float>();
    return in;
}

QuerySettings query_settings(const std::string& path, const py::object& coherent, int threads) {
    QuerySettings q;
    if (path == "scalar")
        q.path = TracePath::scalar;
    else if (path != "packet")
        throw BadArgument(join("path: unknown path \"", path, "\" (use packet or scalar)"));
    if (!coherent.is_none())
        q.coherence = coherent.cast<bool>() ? Coherence::coherent : Coherence::incoherent;
    if (threads < 0 || threads > 1024)
        throw BadArgument(join("threads: ", std::to_string(threads), " is outside 0 .. 1024"));
    q.threads = threads;
    return q;
}

/// out[key] as T*, checked: a C-contiguous, writeable array of dtype T and shape (n,) or, with
/// cols > 0, (n, cols).
template <class T>
T* out_array(const py::handle& obj, const std::string& name, size_t n, py::ssize_t cols) {
    const std::string shape = cols > 0
                                  ? join("(", std::to_string(n), ", ", std::to_string(cols), ")")
                                  : join("(", std::to_string(n), ",)");
    const std::string expected = join(py::str(py::dtype::of<T>()).cast<std::string>(), " ", shape);
    if (!py::isinstance<py::array>(obj))
        throw BadArgument(join(name, ": expected a NumPy array (", expected, "), got ",
                               py::str(py::type::of(obj).attr("__name__")).cast<std::string>()));
    auto a = py::reinterpret_borrow<py::array>(obj);
    const bool shape_ok = cols > 0 ? a.ndim() == 2 && size_t(a.shape(0)) == n && a.shape(1) == cols
                                   : a.ndim() == 1 && size_t(a.shape(0)) == n;
    if (!a.dtype().is(py::dtype::of<T>()) || !shape_ok)
        throw BadArgument(
            join(name, ": ", dtype_text(a), " ", shape_text(a), ", expected ", expected));
    if (!(a.flags() & py::array::c_style))
        throw BadArgument(join(name, ": not C-contiguous (use numpy.ascontiguousarray)"));
    if (!a.writeable()) throw BadArgument(join(name, ": read-only"));
    return static_cast<T*>(a.mutable_data());
}

py::dict intersect(const Mesh& mesh, const py::object& origins, const py::object& directions,
                   const py::object& tmax, const std::string& path, const py::object& coherent,
                   int threads, const py::object& out) {
    const QuerySettings settings = query_settings(path, coherent, threads);
    const RayInput in = ray_input(origins, directions, tmax);
    const size_t n = in.rays.count;
    py::dict d;
    Hits hits;
    if (out.is_none()) {
        const auto rows = static_cast<py::ssize_t>(n);
        py::array_t<float> t(rows), u(rows), v(rows), normal({rows, py::ssize_t(3)});
        py::array_t<int32_t> prim(rows);
        hits.t = t.mutable_data(), hits.u = u.mutable_data(), hits.v = v.mutable_data();
        hits.triangle = prim.mutable_data(), hits.normal = normal.mutable_data();
        d["t"] = t, d["prim"] = prim, d["u"] = u, d["v"] = v, d["normal"] = normal;
    } else {
        if (!py::isinstance<py::dict>(out))
            throw BadArgument("out: expected a dict of arrays (t, prim, u, v, normal)");
        d = py::reinterpret_borrow<py::dict>(out);
        for (const auto& item : d) {
            const std::string key = py::str(item.first).cast<std::string>();
            const std::string name = join("out['", key, "']");
            if (key == "t")
                hits.t = out_array<float>(item.second, name, n, 0);
            else if (key == "prim")
                hits.triangle = out_array<int32_t>(item.second, name, n, 0);
            else if (key == "u")
                hits.u = out_array<float>(item.second, name, n, 0);
            else if (key == "v")
                hits.v = out_array<float>(item.second, name, n, 0);
            else if (key == "normal")
                hits.normal = out_array<float>(item.second, name, n, 3);
            else
                throw BadArgument(join("out: unknown key '", key, "' (t, prim, u, v, normal)"));
        }
    }
    {
        py::gil_scoped_release release;
        mesh.intersect(in.rays, hits, settings);
    }
    return d;
}

py::array occluded(const Mesh& mesh, const py::object& origins, const py::object& directions,
                   const py::object& tmax, const std::string& path, const py::object& coherent,
                   int threads, const py::object& out) {
    const QuerySettings settings = query_settings(path, coherent, threads);
    const RayInput in = ray_input(origins, directions, tmax);
    py::array result = out.is_none() ? py::array_t<bool>(static_cast<py::ssize_t>(in.rays.count))
                                     : py::reinterpret_borrow<py::array>(out);
    static_assert(sizeof(bool) == 1);
    auto* flags = reinterpret_cast<uint8_t*>(out_array<bool>(result, "out", in.rays.count, 0));
    {
        py::gil_scoped_release release;
        mesh.occluded(in.rays, flags, settings);
    }
    return result;
}

void save_rays(const std::string& path, const py::object& origins, const py::object& directions) {
    const RayInput in = ray_input(origins, directions, py::float_(1.0f));
    const auto n = static_cast<py::ssize_t>(in.rays.count);
    py::array_t<float> rays({n, py::ssize_t(6)});
    float* out = rays.mutable_data();
    const size_t org_stride = in.rays.origin_stride / sizeof(float);
    const size_t dir_stride = in.rays.direction_stride / sizeof(float);
    for (size_t i = 0; i < in.rays.count; ++i) {
        for (int k = 0; k < 3; ++k) {
            out[6 * i + size_t(k)] = in.rays.origins[i * org_stride + size_t(k)];
            out[6 * i + 3 + size_t(k)] = in.rays.directions[i * dir_stride + size_t(k)];
        }
    }
    py::module_::import("numpy").attr("save")(path, rays);
}

py::array vertex_array(const Mesh& mesh) {
    py::array_t<float> a({py::ssize_t(mesh.vertex_count()), py::ssize_t(3)});
    if (mesh.vertex_count() > 0)
        std::memcpy(a.mutable_data(), mesh.vertices(), mesh.vertex_count() * 3 * sizeof(float));
    return a;
}

py::array triangle_array(const Mesh& mesh) {
    py::array_t<int32_t> a({py::ssize_t(mesh.triangle_count()), py::ssize_t(3)});
    int32_t* out = a.mutable_data();
    const uint32_t* in = mesh.triangles();
    for (size_t i = 0; i < 3 * mesh.triangle_count(); ++i) out[i] = static_cast<int32_t>(in[i]);
    return a;
}

}  // namespace

void add_mesh(py::module_& m) {
    const float inf = std::numeric_limits<float>::infinity();
    py::class_<Mesh, std::shared_ptr<Mesh>>(
        m, "Mesh",
        "A triangle mesh and its BVHs, for ray queries on the packet path (or the scalar path, "
        "the reference).")
        .def(py::init(&mesh_from_arrays), py::arg("vertices"), py::arg("triangles"),
             "Builds a mesh from an (N, 3) float32 array of vertices and an (M, 3) integer "
             "array of vertex indices (copied once; any strides).")
        .def("intersect", &intersect, py::arg("origins"), py::arg("directions") = py::none(),
             py::arg("tmax") = inf, py::kw_only(), py::arg("path") = "packet",
             py::arg("coherent") = py::none(), py::arg("threads") = 0, py::arg("out") = py::none(),
             "Closest hits in (0, tmax) of rays given as (N, 3) origins and directions, or one "
             "(N, 6) array. Returns a dict of arrays: t (float32, inf on a miss), prim (int32 "
             "triangle index, -1 on a miss), u, v (barycentrics of the second and third "
             "corners), normal ((N, 3) unit geometric normal, 0 on a miss). With out= (a dict of "
             "C-contiguous arrays under some of those keys, of those dtypes and shapes) the hits "
             "are written into them, the others are not computed, and out is returned: repeated "
             "calls allocate nothing.")
        .def("occluded", &occluded, py::arg("origins"), py::arg("directions") = py::none(),
             py::arg("tmax") = inf, py::kw_only(), py::arg("path") = "packet",
             py::arg("coherent") = py::none(), py::arg("threads") = 0, py::arg("out") = py::none(),
             "Whether each ray hits anything in (0, tmax): a bool array (N,), or out= (a "
             "C-contiguous bool array (N,)) written and returned.")
        .def_property_readonly("vertices", &vertex_array, "(N, 3) float32 copy of the vertices")
        .def_property_readonly("triangles", &triangle_array, "(M, 3) int32 copy of the indices")
        .def_property_readonly("triangle_count", &Mesh::triangle_count, "number of triangles")
        .def_property_readonly("build_ms", &Mesh::build_ms, "milliseconds taken to build the BVHs")
        .def("__repr__", [](const Mesh& mesh) {
            return join("<raylane.Mesh ", std::to_string(mesh.vertex_count()), " vertices, ",
                        std::to_string(mesh.triangle_count()), " triangles>");
        });
    m.def("load_mesh", &load_mesh_file, py::arg("path"),
          "Loads an OBJ or PLY model (.obj, .ply, optionally .gz) as a Mesh; a relative name "
          "that is not a file is looked up on RAYLANE_MODEL_PATH. Zero-area faces are dropped, "
          "as when a scene loads the model.");
    m.def("save_rays", &save_rays, py::arg("path"), py::arg("origins"),
          py::arg("directions") = py::none(),
          "Writes rays as an (N, 6) float32 .npy file (origin, direction), the ray file of "
          "`bench_intersect --rays FILE`.");
}

}  // namespace raylane::python
