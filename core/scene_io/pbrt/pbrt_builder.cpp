// pbrt-v4 cameras, integrator settings, shapes and lights onto the scene.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <set>

#include "absl/strings/str_cat.h"
#include "core/film/color_space.h"
#include "core/scene/curve_builder.h"
#include "core/scene/pixel_filter.h"
#include "core/scene_io/image_decode.h"
#include "core/scene_io/pbrt/loop_subdivision.h"
#include "core/scene_io/pbrt/pbrt_scene_builder.h"
#include "core/scene_io/pbrt/pbrt_shapes.h"
#include "core/scene_io/ply/ply_reader.h"

namespace pf::pbrt {
namespace {

// pbrt-v4 gives each triangle of a mesh without "uv" the coordinates (0, 0), (1, 0), (1, 1)
// at its corners (Triangle::InteractionFromIntersection): the corners are unshared for them.
TriangleMesh WithTriangleUvs(const TriangleMesh& mesh) {
    TriangleMesh out;
    static constexpr Point2 kCorners[3] = {{0, 0}, {1, 0}, {1, 1}};
    for (size_t i = 0; i < mesh.indices.size(); ++i) {
        out.positions.push_back(mesh.positions[mesh.indices[i]]);
        if (!mesh.normals.empty()) out.normals.push_back(mesh.normals[mesh.indices[i]]);
        out.uvs.push_back(kCorners[i % 3]);
        out.indices.push_back(static_cast<uint32_t>(i));
    }
    return out;
}

}  // namespace

absl::Status PbrtSceneBuilder::Camera(const std::string& type, ParameterList& parameters,
                                      const Location& where) {
    if (type != "perspective" && type != "orthographic" && type != "spherical")
        return ErrorAt(where, absl::StrCat("Camera \"", type,
                                           "\" is not supported (\"perspective\", "
                                           "\"orthographic\" and \"spherical\" are)"));
    if (camera_)
        return ErrorAt(
            where, absl::StrCat("a second Camera; the first is at ", camera_->where.ToString()));
    CameraSettings camera;
    camera.camera_from_world = state_.ctm;
    camera.projection = type == "orthographic" ? Projection::kOrthographic
                        : type == "spherical"  ? Projection::kSpherical
                                               : Projection::kPerspective;
    if (camera.projection == Projection::kPerspective)
        camera.fov_degrees = parameters.Float("fov", 90.0);
    if (camera.projection != Projection::kSpherical) {
        camera.lens_radius = parameters.Float("lensradius", 0.0);
        camera.focal_distance = parameters.Float("focaldistance", 1e6);
        camera.frame_aspect = parameters.Float("frameaspectratio", 0.0);
        camera.screen_window = parameters.Floats("screenwindow");
        if (!camera.screen_window.empty() &&
            (camera.screen_window.size() != 4 ||
             !(camera.screen_window[0] < camera.screen_window[1]) ||
             !(camera.screen_window[2] < camera.screen_window[3])))
            return ErrorAt(where,
                           "Camera: \"screenwindow\" needs 4 values, x_min < x_max and "
                           "y_min < y_max");
    } else {
        const std::string mapping = parameters.String("mapping", "equalarea");
        if (mapping != "equalarea" && mapping != "equirectangular")
            return ErrorAt(where, absl::StrCat("Camera \"spherical\": \"mapping\" \"", mapping,
                                               "\" is not \"equalarea\" or \"equirectangular\""));
        camera.equal_area = mapping == "equalarea";
    }
    if (camera.projection == Projection::kOrthographic && camera.lens_radius > 0) {
        Warn(where,
             "Camera \"orthographic\": \"lensradius\" is not rendered; the camera is "
             "in focus everywhere");
        camera.lens_radius = 0;
    }
    camera.exposure_time =
        parameters.Float("shutterclose", 1.0) - parameters.Float("shutteropen", 0.0);
    camera.where = where;
    if (!(camera.exposure_time > 0 && std::isfinite(camera.exposure_time)))
        return ErrorAt(where, "Camera: \"shutterclose\" must come after \"shutteropen\"");
    if (!(camera.fov_degrees > 0 && camera.fov_degrees < 180))
        return ErrorAt(where, "Camera: \"float fov\" must lie in (0, 180)");
    if (!(camera.lens_radius >= 0 && camera.focal_distance > 0))
        return ErrorAt(
            where,
            "Camera: \"float lensradius\" must be at least 0 and \"float focaldistance\" positive");
    if (const std::optional<Transform> world_from_camera = state_.ctm.Inverse())
        coordinate_systems_["camera"] = {*world_from_camera, *world_from_camera};
    else
        return ErrorAt(where, "Camera: the current transform is singular");
    camera_ = camera;
    return absl::OkStatus();
}

absl::Status PbrtSceneBuilder::FinishCamera() {
    if (camera_finished_) return absl::OkStatus();
    camera_finished_ = true;
    const CameraSettings camera =
        camera_.value_or(CameraSettings{});  // pbrt's default: at the origin, looking down +z
    const Transform world_from_camera = *camera.camera_from_world.Inverse();
    pf::Camera& out = scene_.camera;
    out.position = Vec3(world_from_camera.ApplyPoint(Vec3d(0.0)));
    // pbrt's image x runs along camera +x and y along camera +y: taking both from the
    // transform keeps the picture the right way round in pbrt's left-handed convention.
    out.forward = Vec3(Normalize(world_from_camera.ApplyVector(Vec3d(0, 0, 1))));
    out.right = Vec3(Normalize(world_from_camera.ApplyVector(Vec3d(1, 0, 0))));
    out.up = Vec3(Normalize(world_from_camera.ApplyVector(Vec3d(0, 1, 0))));
    if (!IsFinite(out.position) || !IsFinite(out.forward) || !IsFinite(out.right) ||
        !IsFinite(out.up))
        return ErrorAt(camera.where, "Camera: the transform is degenerate");
    const double aspect =
        camera.frame_aspect > 0 ? camera.frame_aspect : double(film_width_) / film_height_;
    // pbrt's fov spans the image's shorter side.
    const double half = 0.5 * camera.fov_degrees * kPiD / 180.0;
    out.y_fov = static_cast<float>(aspect >= 1 ? 2 * half : 2 * std::atan(std::tan(half) / aspect));
    out.aspect_ratio = static_cast<float>(aspect);
    out.projection = camera.projection;
    out.equal_area = camera.equal_area ? 1 : 0;
    if (camera.projection == Projection::kOrthographic || !camera.screen_window.empty()) {
        // pbrt's screen window, by default the shorter side from -1 to 1: for a perspective
        // camera at unit distance times tan(fov / 2), for an orthographic one in camera space
        // (whose scale the transform may change).
        std::vector<double> window = camera.screen_window;
        if (window.empty())
            window = aspect >= 1 ? std::vector<double>{-aspect, aspect, -1, 1}
                                 : std::vector<double>{-1, 1, -1 / aspect, 1 / aspect};
        double sx = std::tan(half), sy = sx;
        if (camera.projection == Projection::kOrthographic) {
            sx = Length(world_from_camera.ApplyVector(Vec3d(1, 0, 0)));
            sy = Length(world_from_camera.ApplyVector(Vec3d(0, 1, 0)));
        }
        out.window = {static_cast<float>(window[0] * sx), static_cast<float>(window[1] * sx),
                      static_cast<float>(window[2] * sy), static_cast<float>(window[3] * sy)};
    }
    out.filter = pixel_filter_;
    out.lens_radius = static_cast<float>(camera.lens_radius);
    out.focal_distance = static_cast<float>(camera.focal_distance);
    scene_.hints.width = film_width_;
    scene_.hints.height = film_height_;
    // pbrt-v4's imaging ratio: exposure time x ISO / 100 (1 by default), and its white balance.
    scene_.film = FilmResponse::Make(camera.exposure_time * film_iso_ / 100, film_white_balance_);
    return absl::OkStatus();
}

absl::Status PbrtSceneBuilder::Integrator(const std::string& type, ParameterList& parameters,
                                          const Location& where) {
    // pbrt-v4's integrators that estimate the same light transport as our path tracer.
    static const std::set<std::string> kPathLike = {
        "path", "volpath", "bdpt", "mlt", "lightpath", "simplepath", "simplevolpath", "randomwalk"};
    SceneRenderSettings& settings = scene_.render_settings;
    settings.integrator_source = absl::StrCat(where.ToString(), ": Integrator \"", type, "\"");
    if (type != "sppm" && !kPathLike.contains(type)) {
        parameters.ConsumeAll();
        Warn(where, absl::StrCat("Integrator \"", type,
                                 "\" is not a light transport photonfarm renders; the render's "
                                 "--integrator (default ppm) is used"));
        return absl::OkStatus();
    }
    // pbrt-v4's default depth, 5, where the directive gives none.
    const int max_depth = parameters.Integer("maxdepth", 5);
    if (max_depth < 1)
        return ErrorAt(where,
                       absl::StrCat("Integrator \"", type, "\": \"maxdepth\" must be at least 1"));
    settings.max_depth = max_depth;
    if (type != "sppm") {
        if (type != "path" && type != "volpath")
            Warn(where, absl::StrCat("Integrator \"", type,
                                     "\" renders as photonfarm's path tracer (the same light "
                                     "transport)"));
        settings.integrator = "path";
        parameters.Bool("regularize", false);
        parameters.String("lightsampler", "");
        return absl::OkStatus();
    }
    settings.integrator = "sppm";
    // SPPM's radius is R0 (where the render gives no --radius); pbrt's defaults: 64 iterations,
    // as many photons an iteration as the film has pixels (photonfarm's layout where absent).
    const double radius = parameters.Float("radius", 0.0);
    const int iterations = parameters.Integer("iterations", 64);
    const int photons_per_iteration = parameters.Integer("photonsperiteration", -1);
    parameters.Integer("seed", 0);
    if (radius < 0 || iterations < 1)
        return ErrorAt(where,
                       "Integrator \"sppm\": \"radius\" must not be negative and "
                       "\"iterations\" must be at least 1");
    scene_.hints.initial_radius = radius;
    settings.iterations = static_cast<uint64_t>(iterations);
    if (photons_per_iteration > 0)
        settings.photons_per_iteration = static_cast<uint64_t>(photons_per_iteration);
    return absl::OkStatus();
}

absl::Status PbrtSceneBuilder::Sampler(const std::string& type, ParameterList& parameters,
                                       const Location& where) {
    // pbrt-v4's samplers (pbrt-v3's names are upgraded to theirs before this), as pbrt-v4
    // refuses any other: photonfarm's sequence is its own, but a misspelt name is an error.
    static const std::set<std::string> kSamplers = {
        "halton", "independent", "paddedsobol", "pmj02bn", "sobol", "stratified", "zsobol"};
    if (!kSamplers.contains(type))
        return ErrorAt(where, absl::StrCat("Sampler \"", type,
                                           "\" is not one of pbrt-v4's (halton, independent, "
                                           "paddedsobol, pmj02bn, sobol, stratified, zsobol)"));
    const int pixel_samples = parameters.Integer("pixelsamples", 16);  // pbrt-v4's default
    if (pixel_samples < 1) return ErrorAt(where, "Sampler: \"pixelsamples\" must be at least 1");
    scene_.render_settings.pixel_samples = pixel_samples;
    scene_.render_settings.sampler_source =
        absl::StrCat(where.ToString(), ": Sampler \"", type, "\"");
    parameters.ConsumeAll();  // the sequence is photonfarm's own
    return absl::OkStatus();
}

absl::Status PbrtSceneBuilder::Shape(const std::string& type, ParameterList& parameters,
                                     const Location& where) {
    const std::string element = absl::StrCat(where.ToString(), ": Shape \"", type, "\"");
    // "alpha" (a number, or a float texture): where the shape is absent (cut-outs).
    GraphicsState state = state_;
    const absl::StatusOr<FloatInput> alpha =
        FloatParameter(parameters, "alpha", 1.0, "Shape: \"alpha\"", where, 1, TextureUse::kCutOut);
    if (!alpha.ok()) return alpha.status();
    if (!(alpha->value >= 0 && alpha->value <= 1))
        return ErrorAt(where, "Shape: \"alpha\" must lie in [0, 1]");
    state.alpha = *alpha;
    absl::StatusOr<TriangleMesh> mesh;
    FrontFace front = FrontFace::kObjectWinding;
    if (type == "trianglemesh") {
        mesh = TriangleMeshShape(parameters, where);
    } else if (type == "loopsubdiv") {
        const int levels = parameters.Integer("levels", 3);  // pbrt-v4's default
        mesh = TriangleMeshShape(parameters, where);
        if (mesh.ok()) mesh = LoopSubdivide(*mesh, levels, options_.limits.max_triangles);
        if (!mesh.ok()) return ErrorAt(where, std::string(mesh.status().message()));
    } else if (type == "bilinearmesh") {
        mesh = BilinearMeshShape(parameters, where);
    } else if (type == "sphere") {
        mesh = SphereShape(parameters, where);
        front = FrontFace::kWorldWinding;
    } else if (type == "disk") {
        mesh = DiskShape(parameters, where);
        front = FrontFace::kWorldWinding;
    } else if (type == "cylinder") {
        mesh = CylinderShape(parameters, where);
        front = FrontFace::kWorldWinding;
    } else if (type == "plymesh") {
        const std::string filename = parameters.String("filename", "");
        if (filename.empty()) return ErrorAt(where, "Shape \"plymesh\" needs \"string filename\"");
        absl::StatusOr<std::string> path = ResolveReference(filename, base_folder_);
        if (!path.ok())
            return ErrorAt(where, absl::StrCat("Shape \"plymesh\": ", path.status().message()));
        if (options_.references_only) {  // packing: the file itself, still compressed
            absl::StatusOr<std::string_view> bytes = files_.Read(*path);
            if (!bytes.ok())
                return absl::Status(bytes.status().code(),
                                    absl::StrCat(element, ": ", bytes.status().message()));
            return absl::OkStatus();
        }
        absl::StatusOr<std::string_view> bytes = ReadFile(*path);
        if (!bytes.ok())
            return absl::Status(bytes.status().code(),
                                absl::StrCat(element, ": ", bytes.status().message()));
        mesh = ReadPly(*bytes, *path, options_.limits);
        if (!mesh.ok())
            return absl::Status(mesh.status().code(),
                                absl::StrCat(element, ": ", mesh.status().message()));
    } else if (type == "curve") {
        bool ignored_normals = false;
        absl::StatusOr<std::vector<Curve>> curves = CurveShape(parameters, where, &ignored_normals);
        if (!curves.ok()) return curves.status();
        if (ignored_normals)
            Warn(where,
                 "Shape \"curve\": \"normal N\" is read by \"ribbon\" curves only; "
                 "ignored (as pbrt-v4 ignores it)");
        WarnCurveState(state, where);
        if (!current_object_.empty()) {
            objects_[current_object_].push_back({TriangleMesh{}, state.ctm,
                                                 FrontFace::kObjectWinding, state, element,
                                                 std::move(*curves)});
            return absl::OkStatus();
        }
        return AddCurves(*curves, state.ctm, state, element);
    } else if (type == "hyperboloid" || type == "paraboloid" || type == "cone") {
        parameters.ConsumeAll();
        Warn(where, absl::StrCat("Shape \"", type, "\" is not supported; the shape is left out"));
        return absl::OkStatus();
    } else {
        return ErrorAt(where, absl::StrCat("Shape \"", type, "\" is unknown"));
    }
    if (!mesh.ok()) return mesh.status();
    if (!parameters.status().ok()) return parameters.status();
    if (front == FrontFace::kObjectWinding && !mesh->normals.empty())
        front = FrontFace::kVertexNormals;
    if (!current_object_.empty()) {
        objects_[current_object_].push_back({std::move(*mesh), state.ctm, front, state, element});
        return absl::OkStatus();
    }
    return AddShape(*mesh, state.ctm, front, state, element);
}

absl::Status PbrtSceneBuilder::ObjectInstance(const std::string& name,
                                              const std::vector<ObjectShape>& shapes,
                                              const Location& where) {
    const std::string element = absl::StrCat(where.ToString(), ": ObjectInstance \"", name, "\"");
    // The object's shapes are stored once, as a prototype in the space of the CTM where each was
    // defined (so a quadric's front is settled there, as pbrt-v4 does), at its first instance.
    auto [prototype, first] = object_prototypes_.try_emplace(name, 0);
    if (first) {
        // pbrt-v4 places such an instance as nothing, and so do we (AddInstance skips it).
        if (shapes.empty() && !options_.references_only)
            spdlog::info("{}: the object holds no shapes; its instances add nothing", element);
        prototype->second = BeginPrototype(&scene_);
        for (const ObjectShape& shape : shapes) {
            const std::string shape_element = absl::StrCat(element, ": ", shape.element);
            absl::Status status;
            if (!shape.curves.empty())  // curves never emit: all go to the prototype
                status = AddCurves(shape.curves, shape.world, shape.state, shape_element,
                                   prototype->second);
            else if (!shape.state.area_light)
                status = AddShape(shape.mesh, shape.world, shape.front, shape.state, shape_element,
                                  prototype->second);
            if (!status.ok()) return status;
        }
    }
    // Emitting shapes are lights, which are sampled in world space: each instance places them as
    // world triangles (pbrt-v4 refuses area lights in instances).
    for (const ObjectShape& shape : shapes)
        if (shape.state.area_light && shape.curves.empty())
            if (absl::Status status =
                    AddShape(shape.mesh, state_.ctm * shape.world, shape.front, shape.state,
                             absl::StrCat(element, ": ", shape.element));
                !status.ok())
                return status;
    if (options_.references_only) return absl::OkStatus();
    return AddInstance(prototype->second, state_.ctm, options_.limits, element, &scene_);
}

absl::Status PbrtSceneBuilder::AddShape(const TriangleMesh& mesh, const Transform& world,
                                        FrontFace front, const GraphicsState& state,
                                        const std::string& element,
                                        std::optional<uint32_t> prototype) {
    int32_t emission_texture = kNoTexture;
    if (state.area_light) {  // read (and packed) before anything else
        absl::StatusOr<int32_t> image = ImageIndex(state.area_light->image);
        if (!image.ok()) return image.status();
        emission_texture = *image;
    }
    if (options_.references_only) return absl::OkStatus();
    const MaterialRef& material =
        state.material >= 0 ? materials_[state.material] : DefaultMaterial();
    if (material.interface) {
        if (state.area_light)
            Warn(Location{},
                 absl::StrCat(element, ": an emitting \"interface\" shape is left out"));
        // Media are read at the surfaces that bound them: one bounded by nothing else is lost.
        for (const std::string& medium : {state.inside_medium, state.outside_medium})
            if (!medium.empty() && !IsBlack(media_.at(medium).absorption))
                Warn(Location{}, absl::StrCat("MediumInterface: the medium \"", medium,
                                              "\" of \"interface\" shapes (no surface) is left "
                                              "out; media are rendered at surfaces that bound "
                                              "them"));
        return absl::OkStatus();
    }
    Rgb emission(0.0f);
    TextureMapping mapping = material.mapping;
    if (state.alpha.texture != kNoTexture) {
        // One texture mapping a shape: the alpha texture's, unless the material's texture
        // reads another.
        if (material.material.base_color_texture == kNoTexture)
            mapping = state.alpha.mapping;
        else if (!(mapping == state.alpha.mapping))
            Warn(Location{}, absl::StrCat(element,
                                          ": the alpha texture is read with the material "
                                          "texture's mapping, not its own"));
    }
    if (emission_texture != kNoTexture) {
        // The light's image reads the shape's own (u, v); a base colour texture of the
        // material, which another mapping of them, reads the same.
        mapping = state.area_light->image.mapping;
        if (material.material.base_color_texture != kNoTexture && !(mapping == material.mapping))
            Warn(Location{}, absl::StrCat(element,
                                          ": the material's texture is read with the area "
                                          "light image's (u, v), not its own mapping"));
    }
    if (state.area_light) {
        emission = state.area_light->radiance;
        if (state.area_light->power > 0) {
            // "power": the shape emits that many watts, pi x area x L from each emitting side.
            double area = 0;
            for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
                const Vec3d a = world.ApplyPoint(Vec3d(mesh.positions[mesh.indices[i]]));
                const Vec3d b = world.ApplyPoint(Vec3d(mesh.positions[mesh.indices[i + 1]]));
                const Vec3d c = world.ApplyPoint(Vec3d(mesh.positions[mesh.indices[i + 2]]));
                area += 0.5 * Length(Cross(b - a, c - a));
            }
            // pbrt-v4 scales by power / (pi x area) whatever L's colour (for rgb L, the spectrum
            // it normalises by is the colour space's illuminant, of luminance 1).
            if (state.area_light->two_sided) area *= 2;
            // With an image, its mean luminance counts too (pbrt-v4 averages it over the
            // texels, whatever of it the shape's (u, v) cover).
            if (emission_texture != kNoTexture) {
                double luminance = 0;
                const pf::Texture& image = *scene_.textures[emission_texture];
                for (const Rgb& texel : image.texels) luminance += SrgbLuminance(Vec3d(texel));
                area *= luminance / static_cast<double>(image.texels.size());
            }
            if (area > 0) emission *= static_cast<float>(state.area_light->power / (kPiD * area));
        }
        // pbrt-v4 masks an area light's radiance where its alpha test fails (AlphaMasked, by a
        // hash of the point): alpha x L in expectation, which an emission texture of the alpha
        // gives texel by texel, photons and light samples included. Alpha 0 is pbrt-v4's
        // invisible light, which emits in full.
        if (state.alpha.texture != kNoTexture || state.alpha.value > 0) {
            emission *= state.alpha.value;  // the alpha, or its texture's scale
            if (state.alpha.texture != kNoTexture && emission_texture == kNoTexture)
                emission_texture = state.alpha.texture;
            else if (state.alpha.texture != kNoTexture)
                Warn(Location{}, absl::StrCat(element,
                                              ": an area light's image is not masked by its "
                                              "alpha texture (the alpha's scale is applied)"));
        }
    }
    const Absorption absorption = MediumAbsorption(state);
    absl::StatusOr<uint32_t> index =
        SceneMaterial(state.material, emission, state.area_light && state.area_light->two_sided,
                      state.alpha, emission_texture, absorption.inside, absorption.outside);
    if (!index.ok()) return index.status();
    // Light is sampled from a surface that is not glass, and its shadow ray crosses the medium
    // unattenuated (docs/scenes.md): said once.
    if (const MaterialType type = scene_.materials[*index].type;
        !warned_sampled_media_ && scene_.materials[*index].HasVolume() &&
        type != MaterialType::kDielectric && type != MaterialType::kThinDielectric &&
        type != MaterialType::kMirror) {
        warned_sampled_media_ = true;
        Warn(Location{}, absl::StrCat(element,
                                      ": a medium borders a surface lit by light sampling; light "
                                      "sampled from it is not attenuated by the medium, so "
                                      "directly lit surfaces in it read brighter"));
    }
    MeshPlacement placement{world, *index, front, state.reverse_orientation, mapping.uv};
    if (!scene_.MaterialReadsUv(*index))
        return AppendMesh(mesh, placement, options_.limits, element, &scene_, prototype);
    // Planar, spherical and cylindrical mappings: (s, t) from where the vertices are in the
    // world (an object's shapes: where the object was defined, for all its instances).
    if (!mapping.FromMesh())
        return AppendMesh(MapTextureCoordinates(mesh, world, mapping), placement, options_.limits,
                          element, &scene_, prototype);
    if (mesh.uvs.empty())
        return AppendMesh(WithTriangleUvs(mesh), placement, options_.limits, element, &scene_,
                          prototype);
    return AppendMesh(mesh, placement, options_.limits, element, &scene_, prototype);
}

void PbrtSceneBuilder::WarnCurveState(const GraphicsState& state, const Location& where) {
    const MaterialRef& material =
        state.material >= 0 ? materials_[state.material] : DefaultMaterial();
    // pbrt-v4 cannot sample a point on a curve (Curve::Sample is not implemented): it stops.
    if (state.area_light)
        Warn(where,
             "Shape \"curve\": an area light on a curve; the curve is drawn, emitting "
             "nothing (pbrt-v4 cannot render it)");
    const Material& m = material.material;
    if (m.IsTranslucent() || m.type == MaterialType::kDielectric ||
        m.type == MaterialType::kThinDielectric || m.type == MaterialType::kRoughDielectric)
        Warn(where,
             "Shape \"curve\": light through a curve is not followed (a curve is a band "
             "seen from the side the light comes from)");
    const bool textured = m.ReadsUv() || state.alpha.texture != kNoTexture;
    if (textured &&
        (!(material.mapping == TextureMapping{}) ||
         (state.alpha.texture != kNoTexture && !(state.alpha.mapping == TextureMapping{}))))
        Warn(where,
             "Shape \"curve\": a texture on a curve is read at the curve's own (u, v), "
             "without the texture's mapping");
}

absl::Status PbrtSceneBuilder::AddCurves(const std::vector<Curve>& curves, const Transform& world,
                                         const GraphicsState& state, const std::string& element,
                                         std::optional<uint32_t> prototype) {
    if (options_.references_only) return absl::OkStatus();
    const MaterialRef& material =
        state.material >= 0 ? materials_[state.material] : DefaultMaterial();
    if (material.interface) return absl::OkStatus();
    // Curves never emit (WarnCurveState notes an area light on one).
    const Absorption absorption = MediumAbsorption(state);
    absl::StatusOr<uint32_t> index =
        SceneMaterial(state.material, Rgb(0.0f), false, state.alpha, kNoTexture, absorption.inside,
                      absorption.outside);
    if (!index.ok()) return index.status();
    std::vector<Curve> placed = curves;
    for (Curve& curve : placed) curve.material = *index;
    return AppendCurves(placed, world, state.reverse_orientation, options_.limits, element, &scene_,
                        prototype);
}

absl::StatusOr<uint32_t> PbrtSceneBuilder::SceneMaterial(int material, Rgb emission, bool two_sided,
                                                         const FloatInput& alpha,
                                                         int32_t emission_texture, Rgb absorption,
                                                         Rgb outside_absorption) {
    const auto key =
        std::make_tuple(material, emission.x, emission.y, emission.z, two_sided, emission_texture,
                        alpha.value, alpha.texture, absorption.x, absorption.y, absorption.z,
                        outside_absorption.x, outside_absorption.y, outside_absorption.z);
    if (const auto it = scene_materials_.find(key); it != scene_materials_.end()) return it->second;
    Material out = material >= 0 ? materials_[material].material : DefaultMaterial().material;
    if (material >= 0 && materials_[material].mix[0] >= 0) {
        // A mix: its two materials first (each emitting as the shape does, so that whichever a
        // point is, it emits), then the mix, which comes after them.
        uint32_t parts[2];
        for (int i = 0; i < 2; ++i) {
            absl::StatusOr<uint32_t> part =
                SceneMaterial(materials_[material].mix[i], emission, two_sided, FloatInput{},
                              emission_texture, absorption, outside_absorption);
            if (!part.ok()) return part.status();
            parts[i] = *part;
        }
        out.mix_first = parts[0], out.mix_second = parts[1];
    }
    out.emission = emission;
    out.two_sided = two_sided && out.IsEmissive() ? 1 : 0;
    out.emission_texture = out.IsEmissive() ? emission_texture : kNoTexture;
    out.alpha = alpha.value;
    out.alpha_texture = alpha.texture;
    out.absorption = absorption;
    out.outside_absorption = outside_absorption;
    const auto index = static_cast<uint32_t>(scene_.materials.size());
    scene_.materials.push_back(out);
    scene_materials_[key] = index;
    return index;
}

const MaterialRef& PbrtSceneBuilder::DefaultMaterial() {
    static const MaterialRef kDefault{Material{MaterialType::kDiffuse, Rgb(0.5f)}, {}, false};
    return kDefault;
}

// pbrt-v3's directives, rewritten by pbrt_upgrade.h before the rest of the builder sees them.
absl::StatusOr<UpgradeResult> PbrtSceneBuilder::Upgrade(const std::string& directive,
                                                        std::string* type,
                                                        std::string* texture_class,
                                                        ParameterList* parameters,
                                                        const Location& where) {
    UpgradeResult result;
    const std::string written = *type;
    if (absl::Status status = UpgradeDirective(directive, type, texture_class, parameters, &result);
        !status.ok())
        return ErrorAt(where, absl::StrCat(directive, ": ", status.message()));
    if (!result.change.empty() && !upgraded_) {
        upgraded_ = true;
        Warn(where, absl::StrCat("read as a pbrt-v3 file, rewritten as pbrt-v4's --upgrade "
                                 "rewrites it (here: ",
                                 result.change, ")"));
    }
    for (const std::string& warning : result.warnings)
        Warn(where, absl::StrCat(directive, " \"", written, "\": ", warning));
    return result;
}

}  // namespace pf::pbrt
