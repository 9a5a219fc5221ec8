// python: raylane.Mesh and raylane.load_mesh: ray queries against a triangle mesh from NumPy
// arrays (query/intersect_batch.h), and raylane.save_rays, the ray file of bench_intersect.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "app/commands.h"
#include "core/error.h"
#include "io/load_mesh.h"
#include "io/model_path.h"
#include "python/bindings.h"
#include "query/intersect_batch.h"

namespace raylane::python {
namespace {

/// A mesh as a scene of one object (so that every query goes through the same code as a
/// render), and its BVHs.
struct MeshHandle {
    SceneData scene;
    Accel accel;
    TriangleNormals normals;  ///< the triangles' unit normals, Mesh.intersect's `normal`
    double build_ms = 0.0;
};

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

std::shared_ptr<MeshHandle> make_handle(MeshData mesh) {
    auto h = std::make_shared<MeshHandle>();
    py::gil_scoped_release release;
    const double t = now_seconds();
    h->scene.materials.push_back(Material{});
    if (!mesh.tris.empty()) {
        Object object;
        object.kind = ShapeKind::mesh;
        h->scene.objects.push_back(object);
    }
    h->scene.meshes.push_back(std::move(mesh));
    h->accel = build_accel(h->scene, BuildParams{});
    h->normals = make_triangle_normals(h->scene);
    h->build_ms = elapsed_ms(t);
    return h;
}

std::shared_ptr<MeshHandle> mesh_from_arrays(const py::object& vertices_obj,
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
    MeshData mesh;
    mesh.name = "<arrays>";
    mesh.positions.resize(size_t(n));
    for (py::ssize_t i = 0; i < n; ++i) {
        vec3& p = mesh.positions[size_t(i)];
        for (py::ssize_t j = 0; j < 3; ++j) p[int(j)] = element<float, float>(vertices, i, j);
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw BadArgument(join("vertices: row ", std::to_string(i), " is not finite (",
                                   std::to_string(p.x), ", ", std::to_string(p.y), ", ",
                                   std::to_string(p.z), ")"));
    }
    mesh.tris.resize(size_t(m));
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
            mesh.tris[size_t(i)][j] = static_cast<uint32_t>(row[j]);
        }
    }
    return make_handle(std::move(mesh));
}

std::shared_ptr<MeshHandle> load_mesh_file(const std::string& path) {
    std::string file = path;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec) && std::filesystem::path(path).is_relative()) {
        try {  // a model name on RAYLANE_MODEL_PATH, as scenes name them
            file = find_model(path, ".");
        } catch (const InputError& e) {
            throw MissingFile(e.what());
        }
    }
    require_file(file);
    MeshData mesh;
    {
        py::gil_scoped_release release;
        mesh = load_mesh(file);
    }
    return make_handle(std::move(mesh));
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
    RayArrays rays;
    FloatRows org, dir, t_max;
};

RayInput ray_input(const py::object& origins, const py::object& directions,
                   const py::object& tmax) {
    RayInput in;
    if (directions.is_none()) {
        in.org = float_rows(origins, "rays", 6);
        in.rays.org = in.org.data;
        in.rays.dir = in.org.data + 3;
        in.rays.org_stride = in.rays.dir_stride = in.org.stride;
    } else {
        in.org = float_rows(origins, "origins", 3);
        in.dir = float_rows(directions, "directions", 3);
        if (in.org.rows != in.dir.rows)
            throw BadArgument(join("origins and directions: ", std::to_string(in.org.rows), " and ",
                                   std::to_string(in.dir.rows), " rows, expected the same"));
        in.rays.org = in.org.data;
        in.rays.dir = in.dir.data;
        in.rays.org_stride = in.org.stride;
        in.rays.dir_stride = in.dir.stride;
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

BatchParams batch_params(const std::string& path, const py::object& coherent, int threads) {
    BatchParams p;
    if (path == "scalar")
        p.path = BatchPath::scalar;
    else if (path != "packet")
        throw BadArgument(join("path: unknown path \"", path, "\" (use packet or scalar)"));
    if (!coherent.is_none())
        p.coherence = coherent.cast<bool>() ? Coherence::coherent : Coherence::incoherent;
    if (threads < 0 || threads > 1024)
        throw BadArgument(join("threads: ", std::to_string(threads), " is outside 0 .. 1024"));
    p.threads = threads;
    return p;
}

py::dict intersect(const MeshHandle& h, const py::object& origins, const py::object& directions,
                   const py::object& tmax, const std::string& path, const py::object& coherent,
                   int threads) {
    const BatchParams params = batch_params(path, coherent, threads);
    const RayInput in = ray_input(origins, directions, tmax);
    const auto n = static_cast<py::ssize_t>(in.rays.count);
    py::array_t<float> t(n), u(n), v(n), normal({n, py::ssize_t(3)});
    py::array_t<int32_t> prim(n);
    HitBuffers out;
    out.t = t.mutable_data(), out.u = u.mutable_data(), out.v = v.mutable_data();
    out.prim = prim.mutable_data(), out.normal = normal.mutable_data();
    {
        py::gil_scoped_release release;
        intersect_closest_batch(h.scene, h.accel, in.rays, out, params, &h.normals);
    }
    py::dict d;
    d["t"] = t, d["prim"] = prim, d["u"] = u, d["v"] = v, d["normal"] = normal;
    return d;
}

py::array occluded(const MeshHandle& h, const py::object& origins, const py::object& directions,
                   const py::object& tmax, const std::string& path, const py::object& coherent,
                   int threads) {
    const BatchParams params = batch_params(path, coherent, threads);
    const RayInput in = ray_input(origins, directions, tmax);
    py::array_t<bool> result(static_cast<py::ssize_t>(in.rays.count));
    static_assert(sizeof(bool) == 1);
    auto* out = reinterpret_cast<uint8_t*>(result.mutable_data());
    {
        py::gil_scoped_release release;
        intersect_any_batch(h.scene, h.accel, in.rays, out, params);
    }
    return result;
}

void save_rays(const std::string& path, const py::object& origins, const py::object& directions) {
    const RayInput in = ray_input(origins, directions, py::float_(infinity));
    const auto n = static_cast<py::ssize_t>(in.rays.count);
    py::array_t<float> rays({n, py::ssize_t(6)});
    float* out = rays.mutable_data();
    for (size_t i = 0; i < in.rays.count; ++i) {
        for (int k = 0; k < 3; ++k) {
            out[6 * i + size_t(k)] = in.rays.org[i * in.rays.org_stride + size_t(k)];
            out[6 * i + 3 + size_t(k)] = in.rays.dir[i * in.rays.dir_stride + size_t(k)];
        }
    }
    py::module_::import("numpy").attr("save")(path, rays);
}

py::array vertex_array(const MeshHandle& h) {
    const MeshData& m = h.scene.meshes[0];
    py::array_t<float> a({py::ssize_t(m.positions.size()), py::ssize_t(3)});
    if (!m.positions.empty())
        std::memcpy(a.mutable_data(), m.positions.data(), m.positions.size() * sizeof(vec3));
    return a;
}

py::array triangle_array(const MeshHandle& h) {
    const MeshData& m = h.scene.meshes[0];
    py::array_t<int32_t> a({py::ssize_t(m.tris.size()), py::ssize_t(3)});
    int32_t* out = a.mutable_data();
    for (size_t i = 0; i < m.tris.size(); ++i)
        for (int k = 0; k < 3; ++k) out[3 * i + size_t(k)] = static_cast<int32_t>(m.tris[i][k]);
    return a;
}

}  // namespace

void add_mesh(py::module_& m) {
    const float inf = infinity;
    py::class_<MeshHandle, std::shared_ptr<MeshHandle>>(
        m, "Mesh",
        "A triangle mesh and its BVHs, for ray queries on the packet path (or the scalar path, "
        "the reference).")
        .def(py::init(&mesh_from_arrays), py::arg("vertices"), py::arg("triangles"),
             "Builds a mesh from an (N, 3) float32 array of vertices and an (M, 3) integer "
             "array of vertex indices (copied once; any strides).")
        .def("intersect", &intersect, py::arg("origins"), py::arg("directions") = py::none(),
             py::arg("tmax") = inf, py::kw_only(), py::arg("path") = "packet",
             py::arg("coherent") = py::none(), py::arg("threads") = 0,
             "Closest hits in (0, tmax) of rays given as (N, 3) origins and directions, or one "
             "(N, 6) array. Returns a dict of arrays: t (float32, inf on a miss), prim (int32 "
             "triangle index, -1 on a miss), u, v (barycentrics of the second and third "
             "corners), normal ((N, 3) unit geometric normal, 0 on a miss).")
        .def("occluded", &occluded, py::arg("origins"), py::arg("directions") = py::none(),
             py::arg("tmax") = inf, py::kw_only(), py::arg("path") = "packet",
             py::arg("coherent") = py::none(), py::arg("threads") = 0,
             "Whether each ray hits anything in (0, tmax): a bool array.")
        .def_property_readonly("vertices", &vertex_array, "(N, 3) float32 copy of the vertices")
        .def_property_readonly("triangles", &triangle_array, "(M, 3) int32 copy of the indices")
        .def_property_readonly("triangle_count",
                               [](const MeshHandle& h) { return h.scene.meshes[0].tris.size(); })
        .def_property_readonly(
            "build_ms", [](const MeshHandle& h) { return h.build_ms; },
            "milliseconds taken to build the BVHs")
        .def("__repr__", [](const MeshHandle& h) {
            std::string r = "<raylane.Mesh ";
            r.append(std::to_string(h.scene.meshes[0].positions.size())).append(" vertices, ");
            return r.append(std::to_string(h.scene.meshes[0].tris.size())).append(" triangles>");
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
