// The state of loading one pbrt-v4 scene: graphics state, named things, and the scene built
// so far. pbrt_loader.cpp parses directives; pbrt_materials.cpp and pbrt_builder.cpp make
// materials, textures, shapes, lights and the camera.
#pragma once

#include <deque>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/mesh_builder.h"
#include "core/scene/scene.h"
#include "core/scene_io/image_decode.h"
#include "core/scene_io/pbrt/pbrt_lexer.h"
#include "core/scene_io/pbrt/pbrt_loader.h"
#include "core/scene_io/pbrt/pbrt_mapping.h"
#include "core/scene_io/pbrt/pbrt_parameters.h"
#include "core/scene_io/pbrt/pbrt_upgrade.h"

namespace pf::pbrt {

// "file:line:column: what", INVALID_ARGUMENT.
absl::Status ErrorAt(const Location& where, const std::string& what);

struct TextureRef;

// A procedural texture's program (core/shared/procedural_texture.h) before it is a scene
// texture: its image operands are not yet scene textures but the texture each instruction's
// header word reads, and each UV transform maps the coordinates of its texture's `mapping`.
struct ProgramRef {
    std::vector<gpu::vec4> words;
    std::vector<std::pair<size_t, std::shared_ptr<const TextureRef>>> images;
    bool reads_uv = false;  // some operand reads (s, t): its texture's mapping is theirs
};

// A texture as materials see it: an image (or none, for a constant) times a colour, or a
// procedural texture's program. The image is read and decoded when a material first uses it,
// so unused textures cost nothing and are not packed.
struct TextureRef {
    std::string path;  // the image's bundle path; empty for a constant
    ImageDecodeOptions decode;
    std::string element;  // "file:line:column: Texture "name"", for errors
    Rgb scale{1.0f};
    TextureMapping mapping;
    // Non-empty: what photonfarm cannot evaluate, the texture's class ("ptex") or, for one
    // combining others, the operand's ("scale of Texture "p" (ptex) at ...").
    std::string unsupported;
    // A procedural texture baked into linear texels (checkerboard, bilerp), in place of a file.
    std::shared_ptr<const pf::Texture> baked;
    // A procedural texture evaluated at each point (noise, dots, 3D checkerboard, directionmix,
    // and scale, mix or checkerboard of those); its scale is 1.
    std::shared_ptr<const ProgramRef> program;
    // "Texture "name" (class) at file:line:column", for the notes on what it is not, and its
    // class.
    std::string described, type;
};

// "Texture "w" (wrinkled) at f:3:1 is not evaluated by photonfarm", naming the operand that is
// not where it is one of a scale or mix ("...: scale of Texture "p" (ptex) at f:2:1").
std::string UnsupportedNote(const TextureRef& texture);
// "0.5" for a grey, "(0.1 0.2 0.3)" otherwise.
std::string FormatRgb(const Rgb& value);

struct MaterialRef {
    Material material;       // emission left zero: it comes from the shape's area light
    TextureMapping mapping;  // of its base colour texture
    bool interface = false;  // "interface": a medium boundary, not a surface
    // "mix": the two materials (into materials_) it is one of, the second with probability
    // material.mix_amount; -1 for any other material.
    int mix[2] = {-1, -1};
};

struct AreaLight {
    Rgb radiance;      // L x scale, W/(m^2 sr)
    double power = 0;  // "power": total watts wanted from the shape, 0 if not given
    bool two_sided = false;
    TextureRef image;  // "filename": the radiance is times this image (empty path: none)
};

// A shape's "alpha" (a Shape parameter): a constant, or a float texture times it.
// A float parameter given as a number or as a float texture: its value (a constant
// texture's; an image texture's scale), times the image where there is one.
struct FloatInput {
    float value = 1.0f;
    int32_t texture = kNoTexture;  // into Scene::textures
    TextureMapping mapping;        // of the texture
};

struct GraphicsState {
    Transform ctm;  // at the start time (ActiveTransform StartTime or All): what is rendered
    // At the end time (ActiveTransform EndTime or All): motion blur is not rendered; kept only
    // to say where something moves (PbrtSceneBuilder::WarnIfMoving).
    Transform ctm_end;
    bool reverse_orientation = false;
    int material = -1;  // into materials_; -1: pbrt's default, diffuse 0.5
    std::optional<AreaLight> area_light;
    FloatInput alpha;  // not state pbrt keeps: Shape sets it for the one shape it makes
    // MediumInterface's media: inside, the side a shape's normals face away from, and
    // outside; empty: none (vacuum).
    std::string inside_medium, outside_medium;
};

// A named medium, as far as it is rendered (pbrt_media.cpp): its absorption coefficient.
struct Medium {
    Rgb absorption{0.0f};
};

// A shape inside ObjectBegin/ObjectEnd, kept in the object's space until instanced: a mesh,
// or curves (then the mesh is empty).
struct ObjectShape {
    TriangleMesh mesh;
    Transform world;  // the CTM where it was defined
    FrontFace front;
    GraphicsState state;
    std::string element;
    std::vector<Curve> curves;
};

struct CameraSettings {
    Transform camera_from_world;
    Projection projection = Projection::kPerspective;
    double fov_degrees = 90, lens_radius = 0, focal_distance = 1e6, frame_aspect = 0;
    std::vector<double> screen_window;  // pbrt's x_min x_max y_min y_max; empty: the default
    bool equal_area = true;             // spherical: its mapping
    double exposure_time = 1;           // shutterclose - shutteropen, the film's exposure
    Location where;
};

class PbrtSceneBuilder {
public:
    PbrtSceneBuilder(SceneFiles& files, std::string display_root, const PbrtLoadOptions& options)
        : files_(files), display_root_(std::move(display_root)), options_(options) {}

    absl::StatusOr<Scene> Load(const std::string& main_file);

private:
    // Parsing.
    absl::Status ParseFile(const std::string& path);
    // The tokens of the file an Include or Import names (TokenStream's opener).
    absl::StatusOr<std::vector<Token>> IncludedTokens(const Token& include, const Token& file,
                                                      int depth);
    absl::Status Directive(TokenStream& in);
    absl::Status TypedDirective(const Token& directive, TokenStream& in);
    // Rewrites a pbrt-v3 directive as pbrt-v4's (pbrt_upgrade.h), noting the first such.
    absl::StatusOr<UpgradeResult> Upgrade(const std::string& directive, std::string* type,
                                          std::string* texture_class, ParameterList* parameters,
                                          const Location& where);
    std::optional<absl::Status> TransformDirective(const Token& directive, TokenStream& in);
    std::optional<absl::Status> StateDirective(const Token& directive, TokenStream& in);
    absl::StatusOr<std::string> ReadString(TokenStream& in, const Token& directive);
    absl::StatusOr<std::vector<double>> ReadNumbers(TokenStream& in, const Token& directive,
                                                    size_t count);
    absl::StatusOr<ParameterList> ReadParameters(TokenStream& in);
    // The values of spectrum file `name`, named by a parameter's `declaration`.
    absl::StatusOr<std::vector<double>> SpectrumFile(const std::string& name,
                                                     const Token& declaration);

    // Directives.
    absl::Status Camera(const std::string& type, ParameterList& parameters, const Location& where);
    absl::Status Film(ParameterList& parameters, const Location& where);
    absl::Status PixelFilter(const std::string& type, ParameterList& parameters,
                             const Location& where);
    absl::Status Integrator(const std::string& type, ParameterList& parameters,
                            const Location& where);
    absl::Status Sampler(const std::string& type, ParameterList& parameters, const Location& where);
    absl::Status Shape(const std::string& type, ParameterList& parameters, const Location& where);
    // Adds a shape to the world or, given `prototype`, to that prototype.
    absl::Status AddShape(const TriangleMesh& mesh, const Transform& world, FrontFace front,
                          const GraphicsState& state, const std::string& element,
                          std::optional<uint32_t> prototype = std::nullopt);
    // Notes what a curve of `state` does not render as pbrt-v4 would: an area light, light
    // through it, a texture's mapping.
    void WarnCurveState(const GraphicsState& state, const Location& where);
    // Adds curves (pbrt_shapes.h's CurveShape) to the world or, given `prototype`, to it.
    absl::Status AddCurves(const std::vector<Curve>& curves, const Transform& world,
                           const GraphicsState& state, const std::string& element,
                           std::optional<uint32_t> prototype = std::nullopt);
    absl::Status ObjectInstance(const std::string& name, const std::vector<ObjectShape>& shapes,
                                const Location& where);
    absl::StatusOr<int> MakeMaterial(const std::string& type, ParameterList& parameters,
                                     const Location& where);
    absl::Status BaseColor(ParameterList& parameters, const std::string& name, Rgb fallback,
                           const Location& where, MaterialRef* material);
    // How a float parameter's texture is read: at the shading point; by a cut-out's test
    // (during traversal), an image's texels; as a displacement, whose values alone may be
    // negative (a bump pointing inwards).
    enum class TextureUse { kShading, kCutOut, kDisplacement };
    // Float parameter `name` (`fallback` where absent), a number or a float texture, its values
    // raised to `exponent`; `what` ("Shape: \"alpha\"") names it in messages. A texture
    // photonfarm cannot evaluate (or not for `use`) gives `fallback`, with a note.
    absl::StatusOr<FloatInput> FloatParameter(ParameterList& parameters, const std::string& name,
                                              double fallback, const std::string& what,
                                              const Location& where, double exponent = 1,
                                              TextureUse use = TextureUse::kShading);
    absl::Status Texture(const std::string& name, const std::string& kind, const std::string& type,
                         ParameterList& parameters, const Location& where);
    // An operand of pbrt-v4's scale and mix textures: a named texture of the kind asked for
    // (null for a constant one, whose value is `value`), or a value.
    struct Operand {
        Rgb value{1.0f};
        const TextureRef* texture = nullptr;
    };
    absl::StatusOr<Operand> TextureOperand(ParameterList& parameters, const std::string& name,
                                           bool scalar, Rgb fallback, const std::string& what,
                                           const Location& where);
    // The texels of an operand's image (null while packing, which only reads the file).
    absl::StatusOr<std::shared_ptr<const pf::Texture>> OperandImage(const TextureRef& texture);
    // pbrt-v4's scale, mix and directionmix textures: of constants, a constant; a texture
    // times constants, that texture scaled; of images under one mapping, baked into one image.
    absl::Status Combine(const std::string& name, const std::string& type, bool scalar,
                         ParameterList& parameters, const Location& where, TextureRef* texture);
    // The texture mapping of a Texture directive's parameters (pbrt_mapping.h).
    absl::StatusOr<TextureMapping> Mapping(ParameterList& parameters, const Location& where);
    // pbrt-v4's checkerboard (2D) and bilerp textures of constant operands, baked into an image
    // over one period of their (s, t) mapping; of texture operands, texture->unsupported.
    absl::Status BakeProcedural(const std::string& type, bool scalar, ParameterList& parameters,
                                const Location& where, TextureRef* texture);
    // pbrt-v4's diffusetransmission: "reflectance" (colour or texture), "transmittance" (a
    // colour; a texture's mean colour, with a note) and "scale".
    absl::Status DiffuseTransmission(ParameterList& parameters, const Location& where,
                                     MaterialRef* material);
    // The nearest surfaces of what photonfarm does not model: a subsurface material's albedo
    // ("reflectance", or the diffusion albedo of its coefficients) and a hair's colour
    // ("color", or the colour pbrt-v4 relates to its absorption or melanin).
    absl::Status SubsurfaceAlbedo(ParameterList& parameters, const Location& where,
                                  MaterialRef* material);
    absl::Status HairColour(ParameterList& parameters, const Location& where,
                            MaterialRef* material);
    // A material's "normalmap" image and "displacement" texture (pbrt-v3's "bumpmap").
    absl::Status ShadingDetail(ParameterList& parameters, const Location& where,
                               MaterialRef* material);
    // The scene texture of `texture`'s image, read and decoded on first use (kNoTexture while
    // packing, which only reads it).
    absl::StatusOr<int32_t> ImageIndex(const TextureRef& texture);
    // The scene texture of `texture`: its image, or its program with its images' scene textures
    // and each value raised to `exponent` and clamped to [0, bound], or left signed where
    // `signed_values` (a displacement: fbm and windy swing both ways) (kNoTexture while
    // packing).
    absl::StatusOr<int32_t> TextureIndex(const TextureRef& texture, double exponent = 1,
                                         float bound = std::numeric_limits<float>::max(),
                                         bool signed_values = false);
    // pbrt-v4's procedural textures evaluated at each point (Texture::program): fbm, wrinkled,
    // windy, marble, dots, checkerboard of dimension 3 or of textures.
    absl::Status MakeProgram(const std::string& name, const std::string& type, bool scalar,
                             ParameterList& parameters, const Location& where, TextureRef* texture);
    // The program of scale, mix or directionmix of `operands` (Combine's, as it reads them).
    absl::Status CombineProgram(const std::string& what, const std::string& type,
                                ParameterList& parameters, const std::vector<Operand>& operands,
                                const Location& where, TextureRef* texture);
    // lat_long_map: an "infinite" light's image is pbrt-v3's latitude-longitude map.
    absl::Status LightSource(const std::string& type, ParameterList& parameters,
                             const Location& where, bool lat_long_map = false);
    // files_.Read, with a gzip file (name ending in .gz) decompressed: pbrt's .pbrt.gz and
    // .ply.gz. Packing reads the compressed bytes only.
    absl::StatusOr<std::string_view> ReadFile(const std::string& path);
    absl::Status InfiniteLight(ParameterList& parameters, const Location& where, bool lat_long_map);
    absl::Status ImageLight(const std::string& type, ParameterList& parameters,
                            const Location& where);
    absl::Status ApplyTransform(const Transform& transform);
    absl::Status FinishCamera();

    void Warn(const Location& where, const std::string& what);
    // Warns (once per directive) where `directive`'s transform differs between the start and
    // end times: pbrt-v4 blurs it over the shutter; photonfarm renders it at the start time.
    void WarnIfMoving(const Location& where, const std::string& directive);
    void WarnUnused(const ParameterList& parameters, const std::string& directive);
    absl::StatusOr<uint32_t> SceneMaterial(int material, Rgb emission, bool two_sided,
                                           const FloatInput& alpha, int32_t emission_texture,
                                           Rgb absorption = Rgb(0.0f),
                                           Rgb outside_absorption = Rgb(0.0f));
    // Media (pbrt_media.cpp): MakeNamedMedium, MediumInterface's inside and outside media, and
    // the absorption a shape of `state` takes from them on either side.
    absl::Status MakeNamedMedium(const std::string& name, ParameterList& parameters,
                                 const Location& where);
    absl::Status SetMediumInterface(const std::string& inside, const std::string& outside,
                                    const Location& where);
    struct Absorption {
        Rgb inside{0.0f}, outside{0.0f};
    };
    Absorption MediumAbsorption(const GraphicsState& state) const;
    static const MaterialRef& DefaultMaterial();

    SceneFiles& files_;
    // Files read through ReadFile that were gzip-compressed, decompressed (views into them
    // stay valid while the builder lives).
    std::deque<std::string> decompressed_;
    std::string display_root_;
    PbrtLoadOptions options_;
    std::deque<std::string> file_names_;  // what tokens' locations point into
    bool upgraded_ = false;               // a pbrt-v3 directive was rewritten (and noted)
    std::string base_folder_;             // the main file's bundle folder: names are relative to it

    Scene scene_;
    GraphicsState state_;
    std::vector<GraphicsState> attribute_stack_;
    struct SavedTransform {
        Transform start, end;
        bool reverse_orientation = false;
    };
    std::vector<SavedTransform> transform_stack_;  // TransformBegin/End (pbrt-v3)
    std::map<std::string, std::pair<Transform, Transform>> coordinate_systems_;  // start, end
    std::optional<CameraSettings> camera_;
    bool in_world_ = false, transform_at_start_ = true, transform_at_end_ = true,
         camera_finished_ = false;
    int film_width_ = 1280, film_height_ = 720;
    double film_iso_ = 100, film_white_balance_ = 0;  // pbrt-v4's PixelSensor parameters
    // pbrt-v4's default: a Gaussian of radius 1.5 pixels and sigma 0.5.
    pf::PixelFilter pixel_filter_{FilterKind::kGaussian, 1.5f, 1.5f, 0.5f};

    std::vector<MaterialRef> materials_;
    std::map<std::string, int> named_materials_;
    std::map<std::string, TextureRef> textures_;
    std::map<std::string, TextureRef> float_textures_;  // their value in every channel
    std::map<std::tuple<std::string, ImageDecodeOptions>, int32_t>
        images_;  // (path, how it is decoded) -> Scene::textures
    // (a program's texture, exponent, bound) -> Scene::textures
    std::map<std::tuple<const ProgramRef*, double, float, bool>, int32_t> programs_;
    bool warned_sampled_media_ = false;  // a medium around a surface lit by light sampling
    std::map<std::string, Medium> media_;
    // (material, emission, two-sided, emission texture, alpha, its texture, absorption inside
    // and outside) -> Scene::materials
    std::map<std::tuple<int, float, float, float, bool, int32_t, float, int32_t, float, float,
                        float, float, float, float>,
             uint32_t>
        scene_materials_;

    std::map<std::string, std::vector<ObjectShape>> objects_;
    std::map<std::string, uint32_t>
        object_prototypes_;  // objects instanced so far -> Scene::prototypes
    std::string current_object_;
    std::map<std::string, int> warning_counts_;
};

}  // namespace pf::pbrt
