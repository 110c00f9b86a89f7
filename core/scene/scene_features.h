// What a scene uses, analysed once per job, so that both backends run code instantiated for
// it (the CPU photon pass's template variants, the Vulkan kernels' specialisation constants)
// and a scene without glass pays nothing for glass.
#pragma once

#include <string>

#include "core/scene/emitters.h"
#include "core/scene/scene.h"

namespace pf {

struct SceneFeatures {
    // Materials on at least one triangle or curve.
    bool mirror = false, dielectric = false, thin_dielectric = false;
    bool rough_conductor = false, rough_dielectric = false;  // GGX
    bool coats = false;           // a dielectric coat over a diffuse or conductor base
    bool cut_outs = false;        // alpha: rays pass through parts of some surface
    bool alpha_textures = false;  // a used material's alpha has a texture
    bool mixes = false;           // a material that is one of two at each point
    bool textures = false;        // a used material has a base colour (or transmittance) texture
    bool vertex_colors = false;   // vertices carry colours (Scene::colors: glTF's COLOR_0)
    bool roughness_textures = false;  // a used material's roughness has a texture
    bool mix_textures = false;        // a used mix's amount has a texture
    bool fresnel_mixes = false;       // glTF's dielectric: specular over diffuse (kCoatFresnelMix)
    bool conductor_fresnel = false;   // a metal's reflectance varies with angle (conductor.h)
    bool absorption = false;          // media on either side of a surface absorb (HasVolume)
    bool translucent = false;         // diffuse transmission (Material::transmittance)
    bool sheen = false;               // a sheen over a coat (Material::sheen_color)
    bool sheen_textures = false;      // a used material's sheen has a texture
    // A used material has a procedural texture (Texture::program): pbrt-v4's noise, dots, ...
    bool procedural_textures = false;
    bool smooth_normals = false;  // a triangle interpolates vertex normals
    bool curves = false;          // curve shapes (core/shared/curve.h)
    bool shading_detail = false;  // a used material has a normal or bump map
    // Emitters with power.
    bool triangle_lights = false, point_lights = false, spot_lights = false,
         directional_lights = false, environment = false;
    bool textured_lights = false;  // an emitting triangle has an emission texture
    bool image_lights = false;     // goniometric or projection lights
    // Light reaches diffuse surfaces through specular chains (caustic paths). Not known from
    // the scene's contents alone: the coordinator probes light paths (core/ppm/caustic_probe.h)
    // for scenes with specular materials; false otherwise.
    bool caustics = false;

    // Surfaces that bend light into caustics: mirrors, glass, rough ones and coats.
    bool Specular() const { return mirror || dielectric || thin_dielectric || Rough() || coats; }
    // Anything but opaque diffuse surfaces in a vacuum: what the passes' general variants
    // handle (media absorb along the segments between surfaces, glass or not).
    bool GeneralSurfaces() const { return Specular() || translucent || absorption; }
    bool Rough() const { return rough_conductor || rough_dielectric; }
    // Lights that are deltas, which only light sampling finds (core/scene/glossy_lights.h).
    bool PunctualLights() const {
        return point_lights || spot_lights || directional_lights || image_lights;
    }
    // Whether the base colour varies over a surface: a texture or vertex colours (what the
    // passes' textured variants read, Scene::BaseColor).
    bool VaryingBaseColor() const { return textures || vertex_colors; }
    // Whether shading reads texture coordinates (light emission aside).
    bool ReadsUv() const {
        return textures || alpha_textures || roughness_textures || mix_textures || shading_detail ||
               sheen_textures;
    }
    // Whether some shading normal differs from its surface's (Veach's adjoint factors apply):
    // a cylinder curve's does.
    bool ShadingNormals() const { return smooth_normals || shading_detail || curves; }
    // Every feature on: the general code path, for comparison (bench/photon_bench).
    static SceneFeatures All();
    // "diffuse, glass, area lights, caustics": for logs, job metadata and EXR headers.
    std::string ToString() const;
};

SceneFeatures AnalyseFeatures(const Scene& scene, const Emitters& emitters);

}  // namespace pf
