// A prepared scene: exactly what tracing a job's photons and camera samples needs of a loaded
// Scene (triangles, curves and instances, materials, the textures materials read, lights, camera,
// hints), in a versioned, checksummed binary form. The coordinator parses a job's bundle once
// and sends workers this, so that no worker links a scene parser or an image library.
// Encoding is lossless (every float as it was) and deterministic (the same scene gives the
// same bytes, so the blob's digest names it); decoding treats the bytes as hostile: the
// header, the checksum, every count against what remains, every index against what it
// indexes, every float for finiteness. Emitters, features and the texture filter are derived
// from the decoded scene, as from a loaded one.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"

namespace pf {

// 2: the environment light; 8: its portal; 9: coated materials and cut-outs; 10: Fresnel-mix
// coats, roughness and mix textures; 16: sheen, transmittance textures; 17: the pixel filter;
// 18: coats' samples (Material::coat_samples); 19: media outside surfaces
// (outside_absorption), vertex colours, surface flags (single-sided surfaces); 20: procedural
// textures; 21: curves.
inline constexpr uint32_t kPreparedSceneVersion = 21;

// Normals go only where a triangle is smooth, texture coordinates only where a material has a
// texture, textures only where a material reads them (others stay as empty placeholders, so
// indices hold); Scene::texture_filter is not encoded.
std::string EncodePreparedScene(const Scene& scene);

// INVALID_ARGUMENT naming what is wrong ("prepared scene: triangle 12 uses vertex 900 of
// 800"), never a crash or a wild read. `texture_filter`: give the scene MIP-mapped filtered
// lookups (the camera samples of sppm, path and pm want them; photons read texels at a point).
absl::StatusOr<Scene> DecodePreparedScene(std::string_view bytes, bool texture_filter);

}  // namespace pf
