// The scene's features as the light transport in core/shared reads them: in GLSL the kernels'
// specialisation constants (worker/backends/vulkan/kernels.cpp sets them from SceneFeatures),
// so that code for materials and lights a scene does not use is compiled out; in C++ every one
// is on, the CPU backend choosing its variants per pass instead (SceneFeatures, the photon
// pass's templates). One list for both languages and for the kernels' specialisation.
#ifndef PF_CORE_SHARED_FEATURES_H
#define PF_CORE_SHARED_FEATURES_H

#include "core/shared/gpu_types.h"

// Each feature: its name in the shared code, its specialisation constant's id
// (core/shared/gpu_types.h), and the SceneFeatures member that sets it
// (worker/backends/vulkan/gpu_scene.cpp expands this list too).
#define PF_SCENE_FEATURES(X)                                                   \
    X(kHasMirror, kSpecHasMirror, mirror)                                      \
    X(kHasDielectric, kSpecHasDielectric, dielectric)                          \
    X(kHasThinDielectric, kSpecHasThinDielectric, thin_dielectric)             \
    X(kHasRoughConductor, kSpecHasRoughConductor, rough_conductor)             \
    X(kHasRoughDielectric, kSpecHasRoughDielectric, rough_dielectric)          \
    X(kHasTextures, kSpecHasTextures, textures)                                \
    X(kHasSmoothNormals, kSpecHasSmoothNormals, smooth_normals)                \
    X(kHasTriangleLights, kSpecHasTriangleLights, triangle_lights)             \
    X(kHasPointLights, kSpecHasPointLights, point_lights)                      \
    X(kHasSpotLights, kSpecHasSpotLights, spot_lights)                         \
    X(kHasDirectionalLights, kSpecHasDirectionalLights, directional_lights)    \
    X(kHasEnvironment, kSpecHasEnvironment, environment)                       \
    X(kHasTexturedLights, kSpecHasTexturedLights, textured_lights)             \
    X(kHasImageLights, kSpecHasImageLights, image_lights)                      \
    X(kHasCoats, kSpecHasCoats, coats)                                         \
    X(kHasCutOuts, kSpecHasCutOuts, cut_outs)                                  \
    X(kHasMixes, kSpecHasMixes, mixes)                                         \
    X(kHasRoughnessTextures, kSpecHasRoughnessTextures, roughness_textures)    \
    X(kHasMixTextures, kSpecHasMixTextures, mix_textures)                      \
    X(kHasConductorFresnel, kSpecHasConductorFresnel, conductor_fresnel)       \
    X(kHasAbsorption, kSpecHasAbsorption, absorption)                          \
    X(kHasShadingDetail, kSpecHasShadingDetail, shading_detail)                \
    X(kHasTranslucency, kSpecHasTranslucency, translucent)                     \
    X(kHasSheen, kSpecHasSheen, sheen)                                         \
    X(kHasVertexColors, kSpecHasVertexColors, vertex_colors)                   \
    X(kHasProceduralTextures, kSpecHasProceduralTextures, procedural_textures) \
    X(kHasCurves, kSpecHasCurves, curves)

#ifdef __cplusplus
#define PF_DECLARE_FEATURE(name, id, member) PF_CONST(bool) name = true;
#else
#define PF_DECLARE_FEATURE(name, id, member) layout(constant_id = id) const bool name = true;
#endif

PF_GPU_BEGIN

PF_SCENE_FEATURES(PF_DECLARE_FEATURE)
// The job's hit points gather kinds of photon of their own (rpm's), direct light's among them:
// the job's, not the scene's (worker/backends/vulkan/vulkan_backend.cpp sets it).
#ifdef __cplusplus
PF_CONST(bool) kPhotonKinds = true;
#else
layout(constant_id = kSpecPhotonKinds) const bool kPhotonKinds = true;
#endif

// Some shading normal differs from its surface's (SceneFeatures::ShadingNormals).
PF_CONST(bool) kShadingNormals = kHasSmoothNormals || kHasShadingDetail || kHasCurves;
// Lights that are deltas (SceneFeatures::PunctualLights).
PF_CONST(bool)
kHasPunctualLights = kHasPointLights || kHasSpotLights || kHasDirectionalLights || kHasImageLights;

PF_GPU_END

#undef PF_DECLARE_FEATURE

#endif  // PF_CORE_SHARED_FEATURES_H
