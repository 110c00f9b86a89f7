// A pbrt-v4 directive's parameter list ("float fov" 45 "rgb L" [1 1 1] ...), read with typed
// lookups. A lookup of the wrong type or size records an error; parameters no lookup asked
// for are reported as unused, each at its file:line:column.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/film/spectrum.h"
#include "core/math/vec3.h"
#include "core/scene_io/pbrt/pbrt_lexer.h"

namespace pf::pbrt {

struct Parameter {
    std::string type;  // canonical: float integer bool string texture rgb blackbody spectrum
                       // point2 vector2 point3 vector3 normal3
    std::string name;
    Location where;
    std::vector<double> numbers;
    std::vector<std::string> strings;
    std::vector<bool> bools;
    bool used = false;
};

class ParameterList {
public:
    ParameterList() = default;
    explicit ParameterList(std::vector<Parameter> parameters)
        : parameters_(std::move(parameters)) {}

    // Single values; `fallback` when absent. Wrong type or count: an error, and `fallback`.
    double Float(std::string_view name, double fallback);
    int Integer(std::string_view name, int fallback);
    bool Bool(std::string_view name, bool fallback);
    std::string String(std::string_view name, std::string_view fallback);
    std::optional<Vec3d> Point3(std::string_view name);
    std::optional<Vec3d> Vector3(std::string_view name);
    // Arrays, empty when absent.
    std::vector<double> Floats(std::string_view name);
    std::vector<int> Integers(std::string_view name);
    std::vector<Vec3d> Point3s(std::string_view name);   // point3 (and point)
    std::vector<Vec3d> Normals(std::string_view name);   // normal3 (and normal)
    std::vector<double> Point2s(std::string_view name);  // point2, flattened (u0 v0 u1 v1 ...)

    // A colour parameter (rgb, blackbody, spectrum or float) as linear sRGB: rgb as given;
    // blackbody T as a black body's colour at luminance 1 (pbrt-v4 normalises light spectra so);
    // a named spectrum (NamedSpectrum); (wavelength, value) pairs as SpectrumToRgb makes them
    // for `use`; a float as grey. Absent: nullopt.
    std::optional<Rgb> Color(std::string_view name, SpectrumUse use = SpectrumUse::kReflectance);
    // A parameter of type "texture": the texture's name; absent: nullopt.
    std::optional<std::string> TextureName(std::string_view name);
    // Marks the parameter of this name read, whatever its type, and returns it (null if absent):
    // for parameters a directive notes as a whole rather than reads.
    const Parameter* Consume(std::string_view name);
    // Marks every parameter read: for directives mapped as a whole, with one note.
    void ConsumeAll();
    // Whether a parameter of this name exists (any type); does not mark it used.
    bool Has(std::string_view name) const;
    const Parameter* Find(std::string_view name) const;
    Parameter* Find(std::string_view name);
    // Edits, for reading pbrt-v3 files as pbrt-v4's (pbrt_upgrade.h).
    void Remove(std::string_view name);
    void Rename(std::string_view name, std::string_view new_name);
    void Add(Parameter parameter) { parameters_.push_back(std::move(parameter)); }

    // The first error a lookup recorded, or OK.
    const absl::Status& status() const { return status_; }
    // The parameters nobody looked up.
    std::vector<const Parameter*> Unused() const;

private:
    Parameter* Lookup(std::string_view name, std::initializer_list<std::string_view> types,
                      size_t min_count);
    void Fail(const Parameter& parameter, const std::string& what);

    std::vector<Parameter> parameters_;
    absl::Status status_;
};

// The index of refraction of a named glass spectrum at 550 nm, or nullopt.
std::optional<double> NamedGlassIor(std::string_view name);
// Normal-incidence reflectance (linear sRGB) of a named metal ("metal-Cu-eta" or its "-k"
// twin), or nullopt.
std::optional<Rgb> NamedMetalReflectance(std::string_view name);
// A named metal's complex index eta + i k per channel (from "metal-Cu-eta" or "metal-Cu-k"),
// with the normal-incidence reflectance of NamedMetalReflectance; nullopt for other names.
struct ComplexIndex {
    Rgb eta{1.0f}, k{0.0f};
};
std::optional<ComplexIndex> NamedMetalIndex(std::string_view name);
// A named spectrum pbrt-v4 knows, as linear sRGB: a metal's reflectance ("metal-Cu-eta"),
// a glass's index (grey), a light's colour ("stdillum-D65"); nullopt for any other name.
std::optional<Rgb> NamedSpectrum(std::string_view name);

// A spectrum file (.spd): whitespace-separated (wavelength, value) numbers, '#' comments.
// Errors name file:line.
inline constexpr size_t kMaxSpectrumSamples = 1 << 16;
absl::StatusOr<std::vector<double>> ParseSpectrumFile(std::string_view contents,
                                                      std::string_view file);

}  // namespace pf::pbrt
