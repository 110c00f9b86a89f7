// Typed lookups over a pbrt-v4 parameter list, and the named spectra pbrt scenes use.
#include "core/scene_io/pbrt/pbrt_parameters.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"

namespace pf::pbrt {
Parameter* ParameterList::Lookup(std::string_view name,
                                 std::initializer_list<std::string_view> types, size_t min_count) {
    for (Parameter& parameter : parameters_) {
        if (parameter.name != name) continue;
        parameter.used = true;
        if (std::find(types.begin(), types.end(), parameter.type) == types.end()) {
            std::string expected;
            for (std::string_view type : types)
                absl::StrAppend(&expected, expected.empty() ? "" : " or ", std::string(type));
            Fail(parameter, absl::StrCat("has type '", parameter.type, "', expected ", expected));
            return nullptr;
        }
        const size_t count =
            std::max({parameter.numbers.size(), parameter.strings.size(), parameter.bools.size()});
        if (count < min_count) {
            Fail(parameter, absl::StrCat("needs at least ", min_count, " values, has ", count));
            return nullptr;
        }
        return &parameter;
    }
    return nullptr;
}

void ParameterList::Fail(const Parameter& parameter, const std::string& what) {
    if (status_.ok())
        status_ = absl::InvalidArgumentError(absl::StrCat(parameter.where.ToString(),
                                                          ": parameter \"", parameter.type, " ",
                                                          parameter.name, "\" ", what));
}

double ParameterList::Float(std::string_view name, double fallback) {
    const Parameter* p = Lookup(name, {"float"}, 1);
    return p ? p->numbers[0] : fallback;
}

int ParameterList::Integer(std::string_view name, int fallback) {
    const Parameter* p = Lookup(name, {"integer"}, 1);
    return p ? static_cast<int>(p->numbers[0]) : fallback;
}

bool ParameterList::Bool(std::string_view name, bool fallback) {
    const Parameter* p = Lookup(name, {"bool"}, 1);
    return p ? bool(p->bools[0]) : fallback;
}

std::string ParameterList::String(std::string_view name, std::string_view fallback) {
    const Parameter* p = Lookup(name, {"string"}, 1);
    return p ? p->strings[0] : std::string(fallback);
}

std::optional<Vec3d> ParameterList::Point3(std::string_view name) {
    const Parameter* p = Lookup(name, {"point3"}, 3);
    if (!p) return std::nullopt;
    return Vec3d(p->numbers[0], p->numbers[1], p->numbers[2]);
}

std::optional<Vec3d> ParameterList::Vector3(std::string_view name) {
    const Parameter* p = Lookup(name, {"vector3"}, 3);
    if (!p) return std::nullopt;
    return Vec3d(p->numbers[0], p->numbers[1], p->numbers[2]);
}

std::vector<double> ParameterList::Floats(std::string_view name) {
    const Parameter* p = Lookup(name, {"float"}, 0);
    return p ? p->numbers : std::vector<double>{};
}

std::vector<int> ParameterList::Integers(std::string_view name) {
    const Parameter* p = Lookup(name, {"integer"}, 0);
    if (!p) return {};
    return std::vector<int>(p->numbers.begin(), p->numbers.end());
}

namespace {

std::vector<Vec3d> Triples(const Parameter* p) {
    std::vector<Vec3d> out;
    if (!p) return out;
    for (size_t i = 0; i + 2 < p->numbers.size(); i += 3)
        out.emplace_back(p->numbers[i], p->numbers[i + 1], p->numbers[i + 2]);
    return out;
}

}  // namespace

std::vector<Vec3d> ParameterList::Point3s(std::string_view name) {
    Parameter* p = Lookup(name, {"point3"}, 0);
    if (p && p->numbers.size() % 3 != 0) Fail(*p, "needs a multiple of 3 values");
    return Triples(p);
}

std::vector<Vec3d> ParameterList::Normals(std::string_view name) {
    Parameter* p = Lookup(name, {"normal3"}, 0);
    if (p && p->numbers.size() % 3 != 0) Fail(*p, "needs a multiple of 3 values");
    return Triples(p);
}

std::vector<double> ParameterList::Point2s(std::string_view name) {
    Parameter* p = Lookup(name, {"point2"}, 0);
    if (p && p->numbers.size() % 2 != 0) Fail(*p, "needs a multiple of 2 values");
    return p ? p->numbers : std::vector<double>{};
}

std::optional<Rgb> ParameterList::Color(std::string_view name, SpectrumUse use) {
    Parameter* p = Lookup(name, {"rgb", "blackbody", "spectrum", "float"}, 1);
    if (!p) return std::nullopt;
    if (p->type == "rgb") {
        if (p->numbers.size() != 3) {
            Fail(*p, "needs 3 values");
            return std::nullopt;
        }
        return Rgb(Vec3d(p->numbers[0], p->numbers[1], p->numbers[2]));
    }
    if (p->type == "float") return Rgb(static_cast<float>(p->numbers[0]));
    if (p->type == "blackbody") {
        if (!(p->numbers[0] > 0)) {
            Fail(*p, "needs a temperature above 0 K");
            return std::nullopt;
        }
        return BlackbodyRgb(p->numbers[0]);
    }
    // "spectrum": a named spectrum (a file's values are put in its place on reading), or
    // (wavelength, value) pairs.
    if (!p->strings.empty()) {
        if (std::optional<Rgb> named = NamedSpectrum(p->strings[0])) return named;
        Fail(*p,
             absl::StrCat("names spectrum '", p->strings[0], "', which photonfarm does not know"));
        return std::nullopt;
    }
    const absl::StatusOr<SampledSpectrum> spectrum = MakeSampledSpectrum(p->numbers, use);
    if (!spectrum.ok()) {
        Fail(*p, std::string(spectrum.status().message()));
        return std::nullopt;
    }
    return SpectrumToRgb(*spectrum, use);
}

std::optional<std::string> ParameterList::TextureName(std::string_view name) {
    for (const Parameter& parameter : parameters_)
        if (parameter.name == name && parameter.type != "texture") return std::nullopt;
    const Parameter* p = Lookup(name, {"texture"}, 1);
    if (!p) return std::nullopt;
    return p->strings[0];
}

const Parameter* ParameterList::Consume(std::string_view name) {
    for (Parameter& parameter : parameters_)
        if (parameter.name == name) {
            parameter.used = true;
            return &parameter;
        }
    return nullptr;
}

void ParameterList::ConsumeAll() {
    for (Parameter& parameter : parameters_) parameter.used = true;
}

bool ParameterList::Has(std::string_view name) const { return Find(name) != nullptr; }

const Parameter* ParameterList::Find(std::string_view name) const {
    for (const Parameter& parameter : parameters_)
        if (parameter.name == name) return &parameter;
    return nullptr;
}

Parameter* ParameterList::Find(std::string_view name) {
    for (Parameter& parameter : parameters_)
        if (parameter.name == name) return &parameter;
    return nullptr;
}

void ParameterList::Remove(std::string_view name) {
    std::erase_if(parameters_, [&](const Parameter& p) { return p.name == name; });
}

void ParameterList::Rename(std::string_view name, std::string_view new_name) {
    for (Parameter& parameter : parameters_)
        if (parameter.name == name) parameter.name = std::string(new_name);
}

std::vector<const Parameter*> ParameterList::Unused() const {
    std::vector<const Parameter*> unused;
    for (const Parameter& parameter : parameters_)
        if (!parameter.used) unused.push_back(&parameter);
    return unused;
}

std::optional<double> NamedGlassIor(std::string_view name) {
    // pbrt-v4's named glasses (Schott catalogue), index at 550 nm.
    static constexpr std::pair<std::string_view, double> kGlasses[] = {
        {"glass-BK7", 1.5185},   {"glass-BAF10", 1.6718}, {"glass-FK51A", 1.4875},
        {"glass-LASF9", 1.8550}, {"glass-F5", 1.6055},    {"glass-F10", 1.6259},
        {"glass-F11", 1.6242},
    };
    for (const auto& [glass, ior] : kGlasses)
        if (glass == name) return ior;
    return std::nullopt;
}

std::optional<Rgb> NamedMetalReflectance(std::string_view name) {
    // Normal-incidence reflectance ((n-1)^2 + k^2) / ((n+1)^2 + k^2) of pbrt-v4's measured
    // metals, integrated to linear sRGB.
    static constexpr std::pair<std::string_view, std::array<float, 3>> kMetals[] = {
        {"Ag", {0.972f, 0.960f, 0.915f}},   {"Al", {0.913f, 0.922f, 0.924f}},
        {"Au", {1.000f, 0.766f, 0.336f}},   {"Cu", {0.955f, 0.638f, 0.538f}},
        {"CuZn", {0.910f, 0.778f, 0.423f}}, {"MgO", {0.068f, 0.069f, 0.072f}},
        {"TiO2", {0.180f, 0.185f, 0.205f}},
    };
    for (const auto& [metal, f0] : kMetals)
        for (std::string_view suffix : {"-eta", "-k"})
            if (name == absl::StrCat("metal-", std::string(metal), std::string(suffix)))
                return Rgb(f0[0], f0[1], f0[2]);
    return std::nullopt;
}

std::optional<ComplexIndex> NamedMetalIndex(std::string_view name) {
    // pbrt-v4's measured eta at the sRGB primaries' dominant wavelengths (611, 549, 464 nm, as
    // SpectrumUse::kUnbounded samples any spectrum).
    static constexpr std::pair<std::string_view, std::array<float, 3>> kEta[] = {
        {"Ag", {0.1278f, 0.1252f, 0.1403f}},   {"Al", {1.2528f, 0.9543f, 0.6576f}},
        {"Au", {0.2048f, 0.3551f, 1.3816f}},   {"Cu", {0.3188f, 0.9656f, 1.1574f}},
        {"CuZn", {0.4517f, 0.5292f, 0.9564f}}, {"MgO", {1.7360f, 1.7405f, 1.7503f}},
        {"TiO2", {2.8890f, 2.9565f, 3.1201f}},
    };
    const std::optional<Rgb> reflectance = NamedMetalReflectance(name);
    if (!reflectance) return std::nullopt;
    const std::string_view metal = name.substr(6, name.rfind('-') - 6);  // "metal-X-eta"
    ComplexIndex index;
    for (const auto& [known, eta] : kEta)
        if (known == metal) index.eta = Rgb(eta[0], eta[1], eta[2]);
    // k such that the normal-incidence reflectance ((n-1)^2 + k^2) / ((n+1)^2 + k^2) is the
    // spectrum's (integrated, not sampled: the colour pbrt-v4 shows); where no k reaches it,
    // k = 0 and the dielectric index that does.
    for (int c = 0; c < 3; ++c) {
        const float r = std::min((*reflectance)[c], 0.999f), n = index.eta[c];
        const float k2 = (r * (n + 1) * (n + 1) - (n - 1) * (n - 1)) / (1 - r);
        if (k2 >= 0) {
            index.k[c] = std::sqrt(k2);
        } else {
            index.eta[c] = (1 + std::sqrt(r)) / (1 - std::sqrt(r));
            index.k[c] = 0;
        }
    }
    return index;
}

std::optional<Rgb> NamedSpectrum(std::string_view name) {
    if (std::optional<Rgb> metal = NamedMetalReflectance(name)) return metal;
    if (std::optional<double> ior = NamedGlassIor(name)) return Rgb(static_cast<float>(*ior));
    return NamedIlluminantRgb(name);
}

absl::StatusOr<std::vector<double>> ParseSpectrumFile(std::string_view contents,
                                                      std::string_view file) {
    std::vector<double> numbers;
    int line = 1;
    for (size_t i = 0; i < contents.size();) {
        const char c = contents[i];
        if (c == '\n') ++line;
        if (c == '#') {
            while (i < contents.size() && contents[i] != '\n') ++i;
            continue;
        }
        if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
            ++i;
            continue;
        }
        size_t end = i;
        while (end < contents.size() && !std::isspace(static_cast<unsigned char>(contents[end])) &&
               contents[end] != ',' && contents[end] != '#')
            ++end;
        double value;
        if (!absl::SimpleAtod(std::string(contents.substr(i, end - i)), &value) ||
            !std::isfinite(value))
            return absl::InvalidArgumentError(
                absl::StrCat(std::string(file), ":", line, ": '",
                             std::string(contents.substr(i, std::min<size_t>(end - i, 32))),
                             "' is not a finite number"));
        if (numbers.size() >= kMaxSpectrumSamples * 2)
            return absl::InvalidArgumentError(absl::StrCat(std::string(file), ": more than ",
                                                           kMaxSpectrumSamples,
                                                           " (wavelength, value) pairs"));
        numbers.push_back(value);
        i = end;
    }
    return numbers;
}

}  // namespace pf::pbrt
