// The scene's materials as the shared light transport scatters by them (core/shared/scatter.h,
// the CPU's BsdfOf in core/scene/material.h): GpuMaterial's lanes read into a Bsdf. Materials
// the scene lacks are compiled out there (core/shared/features.h).
#include "core/shared/scatter.h"

// The material's coat, as core/shared/coat.h takes it.
Coat CoatOf(GpuMaterial material) {
    return Coat(floatBitsToUint(material.layer.x), material.coat.x, material.coat.y, material.coat.z, material.layer.y,
                floatBitsToUint(material.coat.w), material.sheen.xyz, material.sheen.w);
}

// The material's conductor Fresnel term, as core/shared/conductor.h takes it; the tint alone in
// a scene whose metals all reflect it at every angle.
Conductor ConductorOf(GpuMaterial material) {
    return Conductor(kHasConductorFresnel ? floatBitsToUint(material.conductor_eta.w) : kConductorTint,
                     material.conductor_eta.xyz, material.conductor_k.xyz);
}

Bsdf BsdfOf(GpuMaterial material) {
    return Bsdf(material.type, material.base_color.w, material.roughness, kHasCoats && material.coat.x > 0.0,
                CoatOf(material), ConductorOf(material), floatBitsToUint(material.conductor_k.w),
                kHasTranslucency ? material.transmittance.xyz : vec3(0.0));
}
