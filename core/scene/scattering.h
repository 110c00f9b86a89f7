// Scattering at surfaces for the CPU passes: the shared definitions (core/shared/scatter.h),
// which the Vulkan kernels compile too, taken into namespace pf. A pass builds a material's
// gpu::Bsdf once per hit (BsdfOf, core/scene/material.h) and hands it to these.
#pragma once

#include "core/scene/material.h"
#include "core/shared/scatter.h"

namespace pf {

using gpu::ArriveAtCoat;
using gpu::Bsdf;
using gpu::ChooseDiffuseSide;
using gpu::CoatArrival;
using gpu::CoatInside;
using gpu::CoatLeaving;
using gpu::DiffuseSide;
using gpu::EvaluateRoughConductor;
using gpu::FresnelDielectric;  // (cos_incident, eta = n_incident / n_transmitted)
using gpu::GlossyResponse;
using gpu::GlossyToPunctualLights;
using gpu::kCarriesFlux;      // what a path carries (core/shared/path_sampling.h): photons
using gpu::kCarriesRadiance;  // camera paths, whose radiance refraction scales by eta^2
using gpu::LeaveCoatAt;
using gpu::ReflectionProbability;
using gpu::ReflectSpecular;
using gpu::Refract;  // (d, n facing d's side, eta, out refracted); false under TIR
using gpu::RefractionOf;
using gpu::RefractionScale;
using gpu::RoughReflection;
using gpu::ScatterNonDiffuse;
using gpu::ScatterSpecular;
using gpu::SegmentTransmittance;
using gpu::SpecularBounce;
using gpu::TransmitSpecular;

}  // namespace pf
