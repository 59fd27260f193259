// graftal.Scene and graftal.Mesh: what the turtle draws of a derived string (the pipeline's
// shownString() and drawn()) and its mesh (meshSetup() and meshed(), as 3D files are
// meshed), as NumPy arrays. A scene's segments are structures of mixed fields in the
// library, so their arrays are filled once when the scene is made into Python's.
#include "bindings.hpp"
#include "graftal/pipeline/stages.hpp"

namespace graftal::python {

namespace {

template <class T>
py::array_t<T> filled(std::vector<py::ssize_t> shape) {
    return py::array_t<T>(std::move(shape));
}

py::array_t<double> segmentPoints(const Scene& s) {
    auto a = filled<double>({py::ssize_t(s.segments.size()), 2, 3});
    double* p = a.mutable_data();
    for (const Segment& seg : s.segments)
        for (const Vec3& v : {seg.a, seg.b}) *p++ = v.x, *p++ = v.y, *p++ = v.z;
    return a;
}

py::array_t<float> paletteArray(const std::vector<Rgb>& palette) {
    auto a = filled<float>({py::ssize_t(palette.size()), 3});
    float* p = a.mutable_data();
    for (const Rgb& c : palette) *p++ = c.r, *p++ = c.g, *p++ = c.b;
    return a;
}

py::array_t<float> vec3fArray(const std::vector<Vec3f>& v) {
    auto a = filled<float>({py::ssize_t(v.size()), 3});
    float* p = a.mutable_data();
    for (const Vec3f& x : v) *p++ = x.x, *p++ = x.y, *p++ = x.z;
    return a;
}

}  // namespace

SceneHandle sceneOf(const DerivedString& d) {
    SceneHandle s;
    s.model = d.model;
    s.source = d.source;
    s.settings = d.settings;
    s.steps = d.steps;
    CancellationToken cancel;
    RenderRequest request;
    static_cast<DeriveRequest&>(request) = deriveRequest(d.settings, cancel);
    Derived derivedModel{d.steps, d.modules, d.modules.size(), {}};
    s.scene = interruptible(cancel, [&] {
        ModuleString shown = shownString(*d.model, derivedModel, request);
        return drawn(*d.model, std::move(shown), request);
    });
    return s;
}

MeshHandle meshOf(const SceneHandle& s, int tubeSides) {
    CancellationToken cancel;
    RenderRequest request;
    static_cast<DeriveRequest&>(request) = deriveRequest(s.settings, cancel);
    request.tubeSides = tubeSides;
    MeshHandle h;
    std::vector<Diagnostic> notes;
    h.mesh = interruptible(cancel, [&] {
        const MeshSetup setup = meshSetup(*s.model, request, MeshPurpose::File);
        return meshed(*s.model, s.scene, setup, notes).flattened();
    });
    return h;
}

void bindGeometry(py::module_& m) {
    py::class_<SceneHandle>(m, "Scene",
                            "What the turtle drew (ModuleString.scene()): segments with their "
                            "widths and colours, filled polygons, and a palette, as NumPy "
                            "arrays in model units.")
        .def_property_readonly(
            "segments", [](const SceneHandle& s) { return segmentPoints(s.scene); },
            "float64 (n, 2, 3): each segment's two end points")
        .def_property_readonly(
            "widths",
            [](const SceneHandle& s) {
                auto a = filled<float>({py::ssize_t(s.scene.segments.size())});
                float* p = a.mutable_data();
                for (const Segment& seg : s.scene.segments) *p++ = seg.width;
                return a;
            },
            "float32 (n,): each segment's width (the stem's diameter in 3D)")
        .def_property_readonly(
            "colors",
            [](const SceneHandle& s) {
                auto a = filled<std::uint16_t>({py::ssize_t(s.scene.segments.size())});
                std::uint16_t* p = a.mutable_data();
                for (const Segment& seg : s.scene.segments) *p++ = seg.color;
                return a;
            },
            "uint16 (n,): each segment's colour index into palette (wrapping around)")
        .def_property_readonly(
            "segment_rgb",
            [](const SceneHandle& s) {
                auto a = filled<float>({py::ssize_t(s.scene.segments.size()), 3});
                float* p = a.mutable_data();
                for (const Segment& seg : s.scene.segments) {
                    const Rgb c = s.scene.colorOf(seg.color);
                    *p++ = c.r, *p++ = c.g, *p++ = c.b;
                }
                return a;
            },
            "float32 (n, 3): each segment's colour, red, green, blue from 0 to 1")
        .def_property_readonly(
            "polygon_vertices",
            [](const SceneHandle& s) {
                auto a = filled<double>({py::ssize_t(s.scene.polygonVertices.size()), 3});
                double* p = a.mutable_data();
                for (const Vec3& v : s.scene.polygonVertices) *p++ = v.x, *p++ = v.y, *p++ = v.z;
                return a;
            },
            "float64 (m, 3): every polygon's vertices, one after the other")
        .def_property_readonly(
            "polygon_offsets",
            [](const SceneHandle& s) {
                const auto& v = s.scene.polygonStart;
                auto a = filled<std::uint32_t>({py::ssize_t(v.size())});
                std::copy(v.begin(), v.end(), a.mutable_data());
                return a;
            },
            "uint32 (k+1,): polygon i is polygon_vertices[offsets[i]:offsets[i+1]]")
        .def_property_readonly(
            "polygon_colors",
            [](const SceneHandle& s) {
                const auto& v = s.scene.polygonColor;
                auto a = filled<std::uint16_t>({py::ssize_t(v.size())});
                std::copy(v.begin(), v.end(), a.mutable_data());
                return a;
            },
            "uint16 (k,): each polygon's colour index")
        .def_property_readonly(
            "palette", [](const SceneHandle& s) { return paletteArray(s.scene.palette); },
            "float32 (c, 3): the colours indices refer to")
        .def_property_readonly(
            "is_3d", [](const SceneHandle& s) { return s.scene.is3D; },
            "whether anything left the z = 0 plane")
        .def_property_readonly(
            "bounds",
            [](const SceneHandle& s) -> py::object {
                const Bounds b = s.scene.bounds();
                if (b.empty()) return py::none();
                return py::make_tuple(py::make_tuple(b.min.x, b.min.y, b.min.z),
                                      py::make_tuple(b.max.x, b.max.y, b.max.z));
            },
            "((min x, y, z), (max x, y, z)) of everything drawn; None when nothing is")
        .def_property_readonly(
            "steps", [](const SceneHandle& s) { return s.steps; }, "the steps derived")
        .def_property_readonly(
            "derive_keywords",
            [](const SceneHandle& s) { return deriveKeywords(s.settings, s.steps); },
            "the derivation's keywords, as ModuleString.derive_keywords")
        .def_property_readonly(
            "model",
            [](const SceneHandle& s) {
                return ModelHandle{s.model, {}, s.source};
            },
            "the Model it was drawn from")
        .def_property_readonly(
            "surfaces", [](const SceneHandle& s) { return s.scene.surfaces.size(); },
            "how many predefined surfaces (~name) it places")
        .def("mesh", &meshOf, py::arg("tube_sides") = 8,
             "The scene as one triangle mesh (graftal.Mesh), meshed as for a 3D file: stems "
             "as tubes of tube_sides sides, polygons, surfaces, repeated organs copied in.")
        .def("__repr__", [](const SceneHandle& s) {
            return "<graftal.Scene segments=" + std::to_string(s.scene.segments.size()) +
                   " polygons=" + std::to_string(s.scene.polygonCount()) +
                   (s.scene.is3D ? " 3D>" : " 2D>");
        });

    py::class_<MeshHandle>(m, "Mesh",
                           "A triangle mesh (Scene.mesh()): vertices, normals, triangles as "
                           "vertex indices, and a colour per triangle.")
        .def_property_readonly(
            "vertices", [](const MeshHandle& h) { return vec3fArray(h.mesh.positions); },
            "float32 (v, 3)")
        .def_property_readonly(
            "normals", [](const MeshHandle& h) { return vec3fArray(h.mesh.normals); },
            "float32 (v, 3): unit normals, one per vertex")
        .def_property_readonly(
            "indices",
            [](const MeshHandle& h) {
                auto a = filled<std::uint32_t>({py::ssize_t(h.mesh.indices.size() / 3), 3});
                std::copy(h.mesh.indices.begin(), h.mesh.indices.end(), a.mutable_data());
                return a;
            },
            "uint32 (t, 3): each triangle's vertices, counter-clockwise seen from its front")
        .def_property_readonly(
            "triangles",
            [](const MeshHandle& h) {
                auto a = filled<float>({py::ssize_t(h.mesh.indices.size() / 3), 3, 3});
                float* p = a.mutable_data();
                for (std::uint32_t i : h.mesh.indices) {
                    const Vec3f& v = h.mesh.positions[i];
                    *p++ = v.x, *p++ = v.y, *p++ = v.z;
                }
                return a;
            },
            "float32 (t, 3, 3): each triangle's corners")
        .def_property_readonly(
            "triangle_colors",
            [](const MeshHandle& h) {
                auto a = filled<std::uint16_t>({py::ssize_t(h.mesh.triangleColor.size())});
                std::copy(h.mesh.triangleColor.begin(), h.mesh.triangleColor.end(),
                          a.mutable_data());
                return a;
            },
            "uint16 (t,): each triangle's colour index into palette")
        .def_property_readonly(
            "palette", [](const MeshHandle& h) { return paletteArray(h.mesh.palette); },
            "float32 (c, 3)")
        .def("__repr__", [](const MeshHandle& h) {
            return "<graftal.Mesh vertices=" + std::to_string(h.mesh.positions.size()) +
                   " triangles=" + std::to_string(h.mesh.triangleCount()) + ">";
        });
}

}  // namespace graftal::python
