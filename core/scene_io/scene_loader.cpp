// The scene formats behind one door, and packing a scene's files into a bundle.
#include "core/scene_io/scene_loader.h"

#include <spdlog/spdlog.h>
#include <tiny_gltf.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/scene/texture_filter.h"
#include "core/scene_io/gltf/gltf_draco.h"
#include "core/scene_io/gltf/gltf_loader.h"
#include "core/scene_io/gltf/gltf_materials.h"
#include "core/scene_io/gltf/gltf_meshopt.h"
#include "core/scene_io/image_decode.h"
#include "core/scene_io/pbrt/pbrt_loader.h"
#include "core/scene_io/scene_files.h"

namespace pf {
namespace {

enum class SceneFormat { kGltf, kGlb, kPbrt, kUnknown };

SceneFormat FormatOf(const std::string& path) {
    if (absl::EndsWithIgnoreCase(path, ".gltf")) return SceneFormat::kGltf;
    if (absl::EndsWithIgnoreCase(path, ".glb")) return SceneFormat::kGlb;
    if (absl::EndsWithIgnoreCase(path, ".pbrt")) return SceneFormat::kPbrt;
    return SceneFormat::kUnknown;
}

absl::Status UnknownFormat(const std::string& name) {
    return absl::InvalidArgumentError(absl::StrCat(
        name, ": unknown scene format (photonfarm reads .gltf, .glb and .pbrt files)"));
}

// The folder part of the name the user gave, so pbrt messages name files as the user sees them.
std::string DisplayRoot(const std::string& name, const std::string& main_file) {
    if (!absl::EndsWith(name, main_file)) return "";
    std::string root = name.substr(0, name.size() - main_file.size());
    while (!root.empty() && root.back() == '/') root.pop_back();
    return root;
}

// tinygltf's file callbacks while packing: files are read through PackingFiles, which
// records them; a path that would leave the folder is refused and remembered as the error.
struct PackState {
    PackingFiles* files;
    absl::Status error;
};

bool PackFileExists(const std::string& path, void* user) {
    auto* state = static_cast<PackState*>(user);
    if (absl::Status status = ResolveReference(path).status(); !status.ok()) {
        if (state->error.ok()) state->error = status;
        return false;
    }
    return true;
}

// tinygltf joins a reference to the main file's folder: ".." resolved within the bundle (a
// path that leaves it stays as it is, and PackFileExists refuses it).
std::string PackExpandFilePath(const std::string& path, void*) {
    return ResolveReference(path).value_or(path);
}

bool PackReadWholeFile(std::vector<unsigned char>* out, std::string* error, const std::string& path,
                       void* user) {
    auto* state = static_cast<PackState*>(user);
    if (!PackFileExists(path, user)) return false;
    absl::StatusOr<std::string_view> contents = state->files->Read(path);
    if (!contents.ok()) {
        if (error) *error = std::string(contents.status().message());
        if (contents.status().code() == absl::StatusCode::kResourceExhausted && state->error.ok())
            state->error = contents.status();
        return false;
    }
    out->assign(contents->begin(), contents->end());
    return true;
}

bool NoWrite(std::string*, const std::string&, const std::vector<unsigned char>&, void*) {
    return false;
}

// Packing only needs to know which files the scene reads; images are decoded once, by the load.
bool SkipImageDecoding(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                       const unsigned char*, int, void*) {
    return true;
}

// Image files no material reads (normal, occlusion maps...: GltfTexturesRead): left out of the
// bundle, so they are neither uploaded nor sent to workers. Files that also hold a buffer or a
// used image stay.
void LeaveOutUnusedImages(const std::string& scene_path, const tinygltf::Model& model,
                          SceneBundle* bundle) {
    std::set<int> used;
    for (const tinygltf::Material& material : model.materials)
        for (const int texture : GltfTexturesRead(material))
            if (texture < static_cast<int>(model.textures.size()))
                used.insert(GltfTextureImage(model.textures[texture]));
    std::set<std::string> kept;
    for (const tinygltf::Buffer& buffer : model.buffers) kept.insert(buffer.uri);
    for (int i : used)
        if (i >= 0 && i < static_cast<int>(model.images.size())) kept.insert(model.images[i].uri);
    std::vector<std::string> left_out;
    for (int i = 0; i < static_cast<int>(model.images.size()); ++i) {
        const std::string& uri = model.images[i].uri;
        if (used.contains(i) || kept.contains(uri) || !bundle->files.contains(uri)) continue;
        bundle->files.erase(uri);
        left_out.push_back(uri);
    }
    if (!left_out.empty())
        spdlog::info("{}: left out {} image file(s) no material reads ({}{})", scene_path,
                     left_out.size(), left_out.front(), left_out.size() > 1 ? ", ..." : "");
}

absl::Status PackGltf(const std::string& scene_path, const std::string& file, bool binary,
                      PackingFiles* files, SceneBundle* bundle) {
    const std::string base_dir = BundleFolder(bundle->main_file);
    // Meshopt streams are decoded as the load decodes them, which reads (and packs) the files
    // that hold them.
    absl::StatusOr<std::string> decoded = DecodeMeshoptBuffers(
        file, binary, base_dir, [files](const std::string& path) { return files->Read(path); });
    if (!decoded.ok())
        return absl::Status(decoded.status().code(),
                            absl::StrCat(scene_path, ": ", decoded.status().message()));
    const std::string main = WithoutDracoIndices(*decoded, binary);
    PackState state{files, absl::OkStatus()};
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({PackFileExists, PackExpandFilePath, PackReadWholeFile, NoWrite, &state});
    loader.SetImageLoader(SkipImageDecoding, nullptr);
    tinygltf::Model model;
    std::string error, warning;
    const auto* bytes = reinterpret_cast<const unsigned char*>(main.data());
    const bool loaded =
        binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, bytes, main.size(), base_dir)
               : loader.LoadASCIIFromString(&model, &error, &warning, main.data(), main.size(),
                                            base_dir);
    if (!state.error.ok())
        return absl::Status(state.error.code(),
                            absl::StrCat(scene_path, ": ", state.error.message()));
    if (!loaded) {
        const std::string first_line = error.substr(0, error.find('\n'));
        return absl::InvalidArgumentError(absl::StrCat(
            scene_path,
            ": not a valid glTF file: ", first_line.empty() ? "parse failed" : first_line));
    }
    LeaveOutUnusedImages(scene_path, model, bundle);
    return absl::OkStatus();
}

}  // namespace

bool IsSceneFile(const std::string& path) { return FormatOf(path) != SceneFormat::kUnknown; }

absl::StatusOr<Scene> LoadScene(const SceneBundle& bundle, const std::string& name,
                                const SceneLoadOptions& options) {
    if (absl::Status status = CheckSceneBundle(bundle); !status.ok())
        return absl::Status(status.code(), absl::StrCat(name, ": ", status.message()));
    absl::StatusOr<Scene> scene = UnknownFormat(name);
    switch (FormatOf(bundle.main_file)) {
        case SceneFormat::kGltf:
        case SceneFormat::kGlb:
            scene = LoadGltf(bundle, name, options.limits, options.camera);
            break;
        case SceneFormat::kPbrt: {
            if (!options.camera.empty() && options.camera != "0")
                return absl::InvalidArgumentError(absl::StrCat(
                    "--camera ", options.camera, ": ", name, " is a pbrt scene, with one camera"));
            BundleFiles files(bundle);
            scene = LoadPbrt(files, bundle.main_file, DisplayRoot(name, bundle.main_file),
                             {options.limits, false, options.warnings});
            break;
        }
        case SceneFormat::kUnknown:
            break;
    }
    if (!scene.ok()) return scene;
    if (options.environment.Given()) {
        absl::StatusOr<Environment> environment =
            MakeEnvironment(options.environment, bundle, options.limits);
        if (!environment.ok()) return environment.status();
        scene->environment = std::move(*environment);
    }
    bool has_light = !scene->lights.empty() || scene->environment.has_value();
    for (const Triangle& t : scene->triangles)
        has_light |= scene->materials[t.material].IsEmissive();
    if (!has_light)
        return absl::InvalidArgumentError(absl::StrCat(
            name,
            ": scene has no light (no light source, emissive surface or environment); light it "
            "with --environment FILE or --environment-color R,G,B"));
    if (options.texture_filter && !scene->textures.empty())
        scene->texture_filter = MakeTextureFilter(scene->textures);
    return scene;
}

absl::StatusOr<Environment> MakeEnvironment(const EnvironmentSettings& settings,
                                            const SceneBundle& bundle, const SceneLimits& limits) {
    if (!(settings.scale > 0 && settings.scale <= kMaxEnvironmentScale) ||
        !std::isfinite(settings.rotate_degrees))
        return absl::InvalidArgumentError(absl::StrCat("--environment-scale must lie in (0, ",
                                                       kMaxEnvironmentScale,
                                                       "] and --environment-rotate be finite"));
    Environment environment;
    environment.to_map = RotationAboutUp(settings.rotate_degrees);
    environment.scale = Rgb(static_cast<float>(settings.scale));
    if (settings.color) {
        if (!settings.file.empty())
            return absl::InvalidArgumentError(
                "--environment and --environment-color exclude each other");
        if (!IsFinite(*settings.color) || MinComponent(*settings.color) < 0)
            return absl::InvalidArgumentError(
                "--environment-color: each of R,G,B must be finite and non-negative");
        environment.scale = environment.scale * *settings.color;
        environment.name = "--environment-color";
        return environment;
    }
    const auto file = bundle.files.find(settings.file);
    if (file == bundle.files.end())
        return absl::NotFoundError(
            absl::StrCat("--environment ", settings.file, ": not in the scene's bundle"));
    absl::StatusOr<Texture> image = DecodeImage(file->second, settings.file, limits);
    if (!image.ok()) return image.status();
    for (const Rgb& texel : image->texels)
        if (!IsFinite(texel) || MinComponent(texel) < 0)
            return absl::InvalidArgumentError(
                absl::StrCat("--environment ", settings.file,
                             ": the image holds negative, infinite or NaN values; a light cannot"));
    environment.mapping = EnvironmentMapping::kLatLong;
    environment.image = std::move(*image);
    environment.name = settings.file;
    return environment;
}

absl::Status BundleEnvironment(EnvironmentSettings* environment, SceneBundle* bundle) {
    if (environment->file.empty()) return absl::OkStatus();
    const std::string& path = environment->file;
    const std::string name =
        absl::StrCat("photonfarm-environment", std::filesystem::path(path).extension().string());
    if (absl::Status status = CheckBundlePath(name); !status.ok())
        return absl::InvalidArgumentError(absl::StrCat(
            "--environment ", path, ": an unusable file name (", status.message(), ")"));
    if (bundle->files.contains(name))
        return absl::InvalidArgumentError(absl::StrCat(
            "--environment ", path, ": the scene's folder already holds a file named ", name));
    absl::StatusOr<std::string> contents = ReadWholeFile(path);
    if (!contents.ok())
        return absl::Status(contents.status().code(),
                            absl::StrCat("--environment ", contents.status().message()));
    bundle->files[name] = std::move(*contents);
    environment->file = name;
    return CheckSceneBundle(*bundle);
}

absl::StatusOr<Scene> LoadScene(const std::string& path, const SceneLoadOptions& options) {
    absl::StatusOr<SceneBundle> bundle = PackSceneBundle(path);
    if (!bundle.ok()) return bundle.status();
    return LoadScene(*bundle, path, options);
}

absl::StatusOr<SceneBundle> PackSceneBundle(const std::string& scene_path,
                                            SceneRenderSettings* render_settings,
                                            const std::string& scene_root) {
    const SceneFormat format = FormatOf(scene_path);
    if (format == SceneFormat::kUnknown) return UnknownFormat(scene_path);
    const std::filesystem::path path(scene_path);
    SceneBundle bundle;
    bundle.main_file = path.filename().string();
    std::filesystem::path root = path.parent_path();
    if (!scene_root.empty()) {
        // The bundle holds the root's files; the main file's path is its place within it.
        std::error_code error;
        root = std::filesystem::weakly_canonical(scene_root, error);
        const std::filesystem::path main = std::filesystem::weakly_canonical(path, error);
        const std::string relative = main.lexically_relative(root).generic_string();
        if (error || !std::filesystem::is_directory(root) || relative.empty() ||
            relative.starts_with("..") || !CheckBundlePath(relative).ok())
            return absl::InvalidArgumentError(absl::StrCat(
                "--scene-root ", scene_root, ": must be a folder that holds ", scene_path));
        bundle.main_file = relative;
    }
    PackingFiles files(root, &bundle);
    absl::Status status;
    if (format == SceneFormat::kPbrt) {
        if (!std::filesystem::is_regular_file(path))
            return absl::NotFoundError(absl::StrCat(scene_path, ": cannot open file"));
        absl::StatusOr<Scene> references =
            LoadPbrt(files, bundle.main_file, DisplayRoot(scene_path, bundle.main_file),
                     {SceneLimits{}, true, nullptr});
        status = references.status();
        if (references.ok() && render_settings != nullptr)
            *render_settings = references->render_settings;
    } else {
        absl::StatusOr<std::string> main = ReadWholeFile(path);
        if (!main.ok()) return main.status();
        status = PackGltf(scene_path, *main, format == SceneFormat::kGlb, &files, &bundle);
        bundle.files[bundle.main_file] = std::move(*main);
    }
    if (!status.ok()) return status;
    if (absl::Status checked = CheckSceneBundle(bundle); !checked.ok())
        return absl::Status(checked.code(), absl::StrCat(scene_path, ": ", checked.message()));
    return bundle;
}

}  // namespace pf
