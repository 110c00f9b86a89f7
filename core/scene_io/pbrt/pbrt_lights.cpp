// pbrt-v4's light sources: point, spot, distant, goniometric, projection and the infinite
// (environment) light, as its lights.cpp creates them.
#include <algorithm>
#include <array>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/film/color_space.h"
#include "core/scene_io/image_decode.h"
#include "core/scene_io/pbrt/pbrt_scene_builder.h"

namespace pf::pbrt {
namespace {

// World directions into a light's frame: the inverse of `ctm`'s linear part, which must be a
// rotation (a reflection allowed) up to a uniform scale; nullopt where it is not.
std::optional<std::array<float, 9>> LightFrame(const Transform& ctm) {
    std::optional<Transform> inverse = ctm.Inverse();
    if (!inverse) return std::nullopt;
    double norms[3] = {0, 0, 0};
    for (int row = 0; row < 3; ++row)
        norms[row] = std::sqrt(inverse->m[row][0] * inverse->m[row][0] +
                               inverse->m[row][1] * inverse->m[row][1] +
                               inverse->m[row][2] * inverse->m[row][2]);
    if (!(norms[0] > 0)) return std::nullopt;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            double dot = 0;
            for (int k = 0; k < 3; ++k) dot += inverse->m[a][k] * inverse->m[b][k];
            const double expected = a == b ? norms[0] * norms[0] : 0.0;
            if (!(std::abs(dot - expected) <= 1e-6 * norms[0] * norms[0])) return std::nullopt;
        }
    std::array<float, 9> frame;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column)
            frame[3 * row + column] = static_cast<float>(inverse->m[row][column] / norms[0]);
    return frame;
}

}  // namespace

absl::Status PbrtSceneBuilder::LightSource(const std::string& type, ParameterList& parameters,
                                           const Location& where, bool lat_long_map) {
    if (!current_object_.empty())
        return ErrorAt(where, "LightSource inside ObjectBegin is not allowed");
    PunctualLight light;
    const float scale = static_cast<float>(parameters.Float("scale", 1.0));
    const double power = parameters.Float("power", 0.0);
    if (type == "point" || type == "spot") {
        const Rgb intensity =
            parameters.Color("I", SpectrumUse::kIlluminant).value_or(Rgb(1.0f)) * scale;
        const Vec3d from = parameters.Point3("from").value_or(Vec3d(0.0));
        light.position = Vec3(state_.ctm.ApplyPoint(from));
        light.intensity = intensity;
        double solid_angle = 4 * kPiD;
        if (type == "spot") {
            const Vec3d to = parameters.Point3("to").value_or(Vec3d(0, 0, 1));
            const double cone = parameters.Float("coneangle", 30.0),
                         delta = parameters.Float("conedeltaangle", 5.0);
            if (!(cone > 0 && cone <= 90 && delta >= 0 && delta <= cone))
                return ErrorAt(
                    where,
                    "LightSource \"spot\": needs 0 < coneangle <= 90 and 0 <= conedeltaangle "
                    "<= coneangle");
            light.type = LightType::kSpot;
            light.direction = Vec3(Normalize(state_.ctm.ApplyVector(to - from)));
            light.cos_outer = static_cast<float>(std::cos(cone * kPiD / 180));
            light.cos_inner = static_cast<float>(std::cos((cone - delta) * kPiD / 180));
            light.smooth_falloff = true;  // pbrt's smoothstep between the cones
            solid_angle =
                2 * kPiD * ((1 - light.cos_inner) + (light.cos_inner - light.cos_outer) / 2);
        }
        // As pbrt-v4: "power" scales I by power / (the cone's solid angle), whatever I's colour.
        if (power > 0) light.intensity *= static_cast<float>(power / solid_angle);
    } else if (type == "distant") {
        const Vec3d from = parameters.Point3("from").value_or(Vec3d(0.0));
        const Vec3d to = parameters.Point3("to").value_or(Vec3d(0, 0, 1));
        light.type = LightType::kDirectional;
        light.direction = Vec3(Normalize(state_.ctm.ApplyVector(to - from)));
        light.intensity =
            parameters.Color("L", SpectrumUse::kIlluminant).value_or(Rgb(1.0f)) * scale;
        const double illuminance = parameters.Float("illuminance", 0.0);
        if (illuminance > 0) light.intensity *= static_cast<float>(illuminance);
    } else if (type == "infinite") {
        return InfiniteLight(parameters, where, lat_long_map);
    } else if (type == "goniometric" || type == "projection") {
        return ImageLight(type, parameters, where);
    } else {
        return ErrorAt(where, absl::StrCat("LightSource \"", type, "\" is unknown"));
    }
    if (!parameters.status().ok()) return parameters.status();
    if (!IsFinite(light.intensity) || MinComponent(light.intensity) < 0 ||
        !IsFinite(light.position) || !IsFinite(light.direction) || power < 0)
        return ErrorAt(where, absl::StrCat("LightSource \"", type,
                                           "\": intensity, power and position must be finite and "
                                           "non-negative, from and to distinct"));
    light.name = where.ToString();
    if (!options_.references_only) scene_.lights.push_back(light);
    return absl::OkStatus();
}

// pbrt-v4's "infinite" light (lights.cpp, Light::Create): a uniform L (the colour space's
// illuminant, white, by default) or an equal-area octahedral image, times "scale"; with
// "illuminance" E_v, scaled as pbrt-v4 scales it: a uniform L by E_v / pi, a map by E_v over
// its upper hemisphere's illuminance as pbrt-v4 sums it (below).
absl::Status PbrtSceneBuilder::InfiniteLight(ParameterList& parameters, const Location& where,
                                             bool lat_long_map) {
    const double scale = parameters.Float("scale", 1.0);
    const double illuminance = parameters.Float("illuminance", -1.0);
    const std::optional<Rgb> radiance = parameters.Color("L", SpectrumUse::kIlluminant);
    const std::string filename = parameters.String("filename", "");
    const std::vector<Vec3d> portal = parameters.Point3s("portal");
    if (!parameters.status().ok()) return parameters.status();
    if (parameters.Has("power"))
        return ErrorAt(where,
                       "LightSource \"infinite\": pbrt-v4 takes no \"power\" for an infinite "
                       "light; give \"scale\" or \"illuminance\"");
    if (radiance && !filename.empty())
        return ErrorAt(where,
                       "LightSource \"infinite\": give either \"L\" or \"filename\", not both");
    if (!std::isfinite(scale) || scale < 0 || !std::isfinite(illuminance) ||
        (radiance && (!IsFinite(*radiance) || MinComponent(*radiance) < 0)))
        return ErrorAt(where,
                       "LightSource \"infinite\": L, scale and illuminance must be finite and "
                       "non-negative");
    Environment environment;
    environment.name = where.ToString();
    const std::optional<std::array<float, 9>> to_light = LightFrame(state_.ctm);
    if (!to_light)
        return ErrorAt(where,
                       "LightSource \"infinite\": its transform must be a rotation (and uniform "
                       "scale), not a shear, a non-uniform scale or singular");
    environment.to_map = *to_light;
    double factor = scale;
    if (filename.empty()) {
        const Rgb l = radiance.value_or(Rgb(1.0f));
        if (illuminance > 0) factor *= illuminance / kPiD;
        environment.scale = l * static_cast<float>(factor);
    } else {
        absl::StatusOr<std::string> path = ResolveReference(filename, base_folder_);
        if (!path.ok())
            return ErrorAt(where,
                           absl::StrCat("LightSource \"infinite\": ", path.status().message()));
        absl::StatusOr<std::string_view> bytes = files_.Read(*path);
        if (!bytes.ok())
            return absl::Status(bytes.status().code(),
                                absl::StrCat(where.ToString(), ": ", bytes.status().message()));
        if (options_.references_only) return absl::OkStatus();
        absl::StatusOr<pf::Texture> image =
            DecodeImage(*bytes, *path, options_.limits, {ImageEncoding::kAuto, 2.2});
        if (!image.ok())
            return absl::Status(image.status().code(),
                                absl::StrCat(where.ToString(), ": ", image.status().message()));
        if (lat_long_map) {
            // pbrt-v3's map: u = phi / 2 pi, v = theta / pi about the light's +z. The lat-long
            // frame has u = 1/2 + atan2(x, -z) / 2 pi and v = acos(y) / pi: map (x, y, z) =
            // light (-y, z, x), a reflection, before the light's own transform.
            const std::array<float, 9> light = environment.to_map;
            for (int column = 0; column < 3; ++column) {
                environment.to_map[column] = -light[3 + column];
                environment.to_map[3 + column] = light[6 + column];
                environment.to_map[6 + column] = light[column];
            }
        } else if (image->width != image->height) {
            return ErrorAt(where, absl::StrCat("LightSource \"infinite\": ", *path, " is ",
                                               image->width, "x", image->height,
                                               "; pbrt-v4 maps are equal-area octahedral squares "
                                               "(convert with pbrt's imgtool makeequiarea)"));
        }
        for (const Rgb& texel : image->texels)
            if (!IsFinite(texel))
                return ErrorAt(where, absl::StrCat("LightSource \"infinite\": ", *path,
                                                   " holds infinite or NaN values"));
        if (illuminance > 0 && !lat_long_map) {
            // The map's illuminance on a surface facing +z exactly as pbrt-v4 sums it:
            // luminance x cosine over the texels of the upper hemisphere, times 2 pi / texels
            // (a texel spans 4 pi / texels: pbrt-v4's maps come out twice as bright as the
            // plain reading of "illuminance", and its pictures are what authors saw).
            double sum = 0;
            for (int y = 0; y < image->height; ++y)
                for (int x = 0; x < image->width; ++x) {
                    const Vec3 w = EqualAreaSquareToSphere(
                        {(x + 0.5f) / image->width, (y + 0.5f) / image->height});
                    if (w.z <= 0) continue;
                    const Rgb& t = image->texels[size_t(y) * image->width + x];
                    sum += SrgbLuminance(Vec3d(t)) * w.z;
                }
            sum *= 2 * kPiD / (double(image->width) * image->height);
            if (sum > 0) factor *= illuminance / sum;
        }
        environment.mapping =
            lat_long_map ? EnvironmentMapping::kLatLong : EnvironmentMapping::kEqualArea;
        environment.image = std::move(*image);
        environment.scale = Rgb(static_cast<float>(factor));
    }
    if (!portal.empty()) {
        // World-space corners, as pbrt-v4 takes them (the light's transform does not move it).
        if (portal.size() != 4)
            return ErrorAt(where, absl::StrCat("LightSource \"infinite\": \"portal\" takes the "
                                               "4 corners of a rectangle, not ",
                                               portal.size()));
        std::array<Vec3, 4> corners;
        for (int i = 0; i < 4; ++i) corners[i] = Vec3(portal[i]);
        absl::StatusOr<EnvironmentPortal> window = EnvironmentPortal::FromCorners(corners);
        if (!window.ok())
            return ErrorAt(where, absl::StrCat("LightSource \"infinite\": \"portal\": ",
                                               window.status().message()));
        environment.portal = *window;
    }
    if (!IsFinite(environment.scale))
        return ErrorAt(where, "LightSource \"infinite\": scale x illuminance overflows");
    if (options_.references_only) return absl::OkStatus();
    if (scene_.environment) {
        if (scene_.environment->mapping == EnvironmentMapping::kUniform &&
            environment.mapping == EnvironmentMapping::kUniform && !scene_.environment->portal &&
            !environment.portal) {
            scene_.environment->scale += environment.scale;  // two uniform lights are one
            return absl::OkStatus();
        }
        Warn(where,
             "LightSource \"infinite\": a second infinite light with an image or a portal, or "
             "beside one, is left out (uniform ones add up)");
        return absl::OkStatus();
    }
    scene_.environment = std::move(environment);
    return absl::OkStatus();
}

// pbrt-v4's goniometric and projection lights (lights.cpp): a point light at the origin of
// the light's frame whose intensity is I x scale x an image's nearest texel toward each
// direction. Goniometric: an equal-area square over the sphere, pbrt's y and z swapped, its
// RGB averaged to grey as pbrt-v4 does; "power" over 4 pi x its mean. Projection: the image
// through a frustum of "fov" (default 90) along +z, y flipped as pbrt-v4 flips it; "power"
// over its texels' luminance x the solid angle each spans, as pbrt-v4 sums it.
absl::Status PbrtSceneBuilder::ImageLight(const std::string& type, ParameterList& parameters,
                                          const Location& where) {
    const std::string element = absl::StrCat("LightSource \"", type, "\"");
    const bool goniometric = type == "goniometric";
    PunctualLight light;
    light.type = goniometric ? LightType::kGoniometric : LightType::kProjection;
    // pbrt-v4's projection light has no "I": its image is the colour.
    light.intensity =
        (goniometric ? parameters.Color("I", SpectrumUse::kIlluminant).value_or(Rgb(1.0f))
                     : Rgb(1.0f)) *
        static_cast<float>(parameters.Float("scale", 1.0));
    const double power = parameters.Float("power", 0.0);
    const double fov = goniometric ? 90.0 : parameters.Float("fov", 90.0);
    const std::string filename = parameters.String("filename", "");
    if (!parameters.status().ok()) return parameters.status();
    if (filename.empty())
        return ErrorAt(where, absl::StrCat(element, " needs \"string filename\" (its image)"));
    if (!IsFinite(light.intensity) || MinComponent(light.intensity) < 0 || !(power >= 0) ||
        !std::isfinite(power) || !(fov > 0 && fov < 180))
        return ErrorAt(where, absl::StrCat(element,
                                           ": I, scale and power must be finite and "
                                           "non-negative, fov in (0, 180)"));
    std::optional<std::array<float, 9>> frame = LightFrame(state_.ctm);
    if (!frame)
        return ErrorAt(where, absl::StrCat(element,
                                           ": its transform must be a rotation (and "
                                           "uniform scale)"));
    // pbrt-v4's extra turn of the light's frame: y and z swapped (goniometric), y flipped
    // (projection).
    std::array<float, 9>& m = *frame;
    for (int column = 0; column < 3; ++column) {
        if (goniometric)
            std::swap(m[3 + column], m[6 + column]);
        else
            m[3 + column] = -m[3 + column];
    }
    light.to_light = m;
    light.position = Vec3(state_.ctm.ApplyPoint(Vec3d(0.0)));
    light.tan_half_fov = static_cast<float>(std::tan(fov * kPiD / 360));
    absl::StatusOr<std::string> path = ResolveReference(filename, base_folder_);
    if (!path.ok()) return ErrorAt(where, absl::StrCat(element, ": ", path.status().message()));
    absl::StatusOr<std::string_view> bytes = files_.Read(*path);
    if (!bytes.ok())
        return absl::Status(bytes.status().code(),
                            absl::StrCat(where.ToString(), ": ", bytes.status().message()));
    if (options_.references_only) return absl::OkStatus();
    absl::StatusOr<pf::Texture> image = DecodeImage(*bytes, *path, options_.limits, {});
    if (!image.ok())
        return absl::Status(image.status().code(),
                            absl::StrCat(where.ToString(), ": ", image.status().message()));
    for (const Rgb& texel : image->texels)
        if (!IsFinite(texel) || MinComponent(texel) < 0)
            return ErrorAt(where, absl::StrCat(element, ": ", *path,
                                               " holds negative, infinite or NaN values"));
    if (goniometric && image->width != image->height)
        return ErrorAt(where,
                       absl::StrCat(element, ": ", *path, " is ", image->width, "x", image->height,
                                    "; pbrt-v4's goniometric images are equal-area "
                                    "squares"));
    if (goniometric)
        for (Rgb& texel : image->texels) texel = Rgb(Average(texel));
    light.image = std::make_shared<const pf::Texture>(std::move(*image));
    if (power > 0) {
        // The light's own measure of its power, for I = 1: pbrt-v4's k_e.
        const pf::Texture& texels = *light.image;
        double sum = 0;
        for (int y = 0; y < texels.height; ++y)
            for (int x = 0; x < texels.width; ++x) {
                const Vec3d texel(texels.texels[size_t(y) * texels.width + x]);
                if (goniometric) {
                    sum += texel.x;
                    continue;
                }
                const double cosine =
                    1 / Length(Vec3d(light.ProjectionPlanePoint(x + 0.5f, y + 0.5f)));
                sum += SrgbLuminance(texel) * cosine * cosine * cosine;
            }
        const Point2 extent = goniometric ? Point2{} : light.ProjectionExtent();
        const double k_e = (goniometric ? 4 * kPiD : 4.0 * extent.x * extent.y) * sum /
                           (double(texels.width) * texels.height);
        if (k_e > 0) light.intensity *= static_cast<float>(power / k_e);
    }
    light.name = where.ToString();
    scene_.lights.push_back(std::move(light));
    return absl::OkStatus();
}

}  // namespace pf::pbrt
