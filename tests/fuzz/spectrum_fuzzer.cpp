// libFuzzer target for the spectrum files (.spd) pbrt scenes name and the conversion of any
// spectrum to RGB: any bytes must come back as finite colours or an error, never a crash, a
// sanitizer report or a leak.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/scene_io/pbrt/pbrt_parameters.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const absl::StatusOr<std::vector<double>> numbers = pf::pbrt::ParseSpectrumFile(
        std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.spd");
    if (!numbers.ok()) return 0;
    for (pf::SpectrumUse use : {pf::SpectrumUse::kReflectance, pf::SpectrumUse::kIlluminant,
                                pf::SpectrumUse::kUnbounded}) {
        const absl::StatusOr<pf::SampledSpectrum> spectrum = pf::MakeSampledSpectrum(*numbers, use);
        if (!spectrum.ok()) continue;
        const pf::Rgb rgb = pf::SpectrumToRgb(*spectrum, use);
        // Bounded inputs give finite colours (an unbounded one may overflow float: +-inf).
        if (use != pf::SpectrumUse::kUnbounded && !pf::IsFinite(rgb)) __builtin_trap();
    }
    return 0;
}
