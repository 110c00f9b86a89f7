// Image decoding from memory: the samples through pf_image_oiio (OpenImageIO, loaded at the
// first image; image_module.h), then their transfer function and channels here.
#include "core/scene_io/image_decode.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <type_traits>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "core/scene_io/image_module.h"

namespace pf {
namespace {

// The module, loaded once per process: its entry point, or why there is none (one line).
struct ImageModule {
    PfDecodeImageFunction decode = nullptr;
    std::string error;
};

// Where the module is looked for, first found first: `lib` beside the running executable's
// folder (build/lib for build/tests/x, /usr/local/lib for /usr/local/bin/x), then the build
// tree's own (PF_IMAGE_MODULE_BUILD_PATH, for executables deeper in it, such as the fuzzers).
std::vector<std::string> ModulePaths() {
    std::vector<std::string> paths;
    std::error_code error;
    const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error)
        paths.push_back((executable.parent_path().parent_path() / "lib" / kPfImageModuleFile)
                            .lexically_normal()
                            .string());
#ifdef PF_IMAGE_MODULE_BUILD_PATH
    if (std::find(paths.begin(), paths.end(), PF_IMAGE_MODULE_BUILD_PATH) == paths.end())
        paths.push_back(PF_IMAGE_MODULE_BUILD_PATH);
#endif
    return paths;
}

ImageModule LoadModule() {
    ImageModule module;
    const std::vector<std::string> paths = ModulePaths();
    for (const std::string& path : paths) {
        std::error_code missing;
        if (!std::filesystem::exists(path, missing)) continue;
        // Never closed: the module lives as long as the process.
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* reason = dlerror();
            module.error = absl::StrCat("image module ", path, " could not be loaded (",
                                        reason ? reason : "unknown error", ")");
            return module;
        }
        module.decode =
            reinterpret_cast<PfDecodeImageFunction>(dlsym(handle, kPfDecodeImageSymbol));
        if (!module.decode)
            module.error = absl::StrCat("image module ", path, " has no ", kPfDecodeImageSymbol,
                                        " (a module from another build?)");
        return module;
    }
    module.error = absl::StrCat("images cannot be decoded: the image module ", kPfImageModuleFile,
                                " is not at ", absl::StrJoin(paths, " nor "));
    return module;
}

// Loaded at the first call, once, whichever thread calls first (a function-local static).
const ImageModule& Module() {
    static const ImageModule module = LoadModule();
    return module;
}

// The samples the module decodes, in memory owned here; `shape` says which are in use.
struct DecodedSamples {
    uint64_t max_pixels = 0;
    PfImageShape shape{};
    bool over_limit = false;
    std::vector<uint8_t> uint8;
    std::vector<uint16_t> uint16;
    std::vector<float> floats;
};

void* AllocateSamples(void* context, const PfImageShape* shape) noexcept {
    auto& decoded = *static_cast<DecodedSamples*>(context);
    decoded.shape = *shape;
    const uint64_t pixels = uint64_t(shape->width) * uint64_t(shape->height);
    if (pixels > decoded.max_pixels) {
        decoded.over_limit = true;
        return nullptr;
    }
    const size_t count = pixels * size_t(shape->channels);
    try {
        switch (shape->samples) {
            case kPfImageUint8:
                decoded.uint8.resize(count);
                return decoded.uint8.data();
            case kPfImageUint16:
                decoded.uint16.resize(count);
                return decoded.uint16.data();
            case kPfImageFloat:
                decoded.floats.resize(count);
                return decoded.floats.data();
        }
    } catch (const std::bad_alloc&) {
    }
    return nullptr;
}

}  // namespace

absl::StatusOr<Texture> DecodeImage(std::string_view bytes, const std::string& name,
                                    const SceneLimits& limits, const ImageDecodeOptions& options) {
    auto error = [&](const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat(name, ": ", what));
    };
    const size_t dot = name.rfind('.');
    if (dot == std::string::npos) return error("image file has no extension to tell its format");
    const ImageModule& module = Module();
    if (!module.decode)
        return absl::FailedPreconditionError(absl::StrCat(name, ": ", module.error));
    DecodedSamples decoded;
    decoded.max_pixels = limits.max_image_pixels;
    char message[512] = "";
    const int32_t result = module.decode(bytes.data(), bytes.size(), name.substr(dot).c_str(),
                                         AllocateSamples, &decoded, message, sizeof(message));
    if (result == kPfImageFailed) return error(message);
    const PfImageShape& spec = decoded.shape;
    if (decoded.over_limit)
        return absl::ResourceExhaustedError(absl::StrCat(name, ": image is ", spec.width, "x",
                                                         spec.height, ", over the limit of ",
                                                         limits.max_image_pixels, " pixels"));
    if (result != kPfImageDecoded)
        return absl::ResourceExhaustedError(absl::StrCat(name, ": image of ", spec.width, "x",
                                                         spec.height, "x", spec.channels,
                                                         " samples does not fit in memory"));
    const uint64_t pixels = uint64_t(spec.width) * uint64_t(spec.height);
    ImageEncoding encoding = options.encoding;
    if (encoding == ImageEncoding::kAuto)
        encoding = spec.samples == kPfImageFloat ? ImageEncoding::kLinear : ImageEncoding::kSrgb;
    auto to_linear = [&](float value) {
        if (!std::isfinite(value)) return 0.0f;
        switch (encoding) {
            case ImageEncoding::kSrgb:
                return SrgbToLinear(std::clamp(value, 0.0f, 1.0f));
            case ImageEncoding::kGamma:
                return static_cast<float>(std::pow(std::max(value, 0.0f), options.gamma));
            default:
                return std::max(value, 0.0f);
        }
    };
    const int channels = spec.channels;
    Texture texture;
    texture.width = spec.width;
    texture.height = spec.height;
    texture.texels.reserve(pixels);
    // Each texel from its values: `stored(k)` the k-th value as stored (alpha is linear in
    // every format), `linear(k)` decoded.
    const auto convert = [&](const auto& stored, const auto& linear) {
        const auto alpha = [&](size_t i) {
            if (channels != 2 && channels != 4) return 1.0f;
            const float value = stored(i * channels + channels - 1);
            return std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : 0.0f;
        };
        const int picked = options.channels == ImageChannels::kGreen  ? 1
                           : options.channels == ImageChannels::kBlue ? 2
                                                                      : 0;
        for (size_t i = 0; i < pixels; ++i) {
            const size_t first = i * channels;
            switch (options.channels) {
                case ImageChannels::kColour:
                    texture.texels.emplace_back(linear(first),
                                                linear(first + (channels < 3 ? 0 : 1)),
                                                linear(first + (channels < 3 ? 0 : 2)));
                    break;
                case ImageChannels::kFloat:
                    texture.texels.emplace_back(
                        channels == 4 ? alpha(i)
                        : channels == 3
                            ? (linear(first) + linear(first + 1) + linear(first + 2)) / 3
                            : linear(first));
                    break;
                case ImageChannels::kAlpha:
                    texture.texels.emplace_back(alpha(i));
                    break;
                case ImageChannels::kRed:
                case ImageChannels::kGreen:
                case ImageChannels::kBlue:
                    texture.texels.emplace_back(linear(first + (channels < 3 ? 0 : picked)));
                    break;
            }
        }
    };
    // 8- and 16-bit codes are decoded through a table of every code (a pow per code, not per
    // value); floats one by one.
    const auto decode_codes = [&](const auto& codes) {
        using Code = typename std::decay_t<decltype(codes)>::value_type;
        constexpr size_t kCodes = size_t{std::numeric_limits<Code>::max()} + 1;
        constexpr float kLargest = std::numeric_limits<Code>::max();
        std::vector<float> table(kCodes);
        for (size_t code = 0; code < kCodes; ++code)
            table[code] = to_linear(static_cast<float>(code) / kLargest);
        convert([&](size_t k) { return static_cast<float>(codes[k]) / kLargest; },
                [&](size_t k) { return table[codes[k]]; });
    };
    if (spec.samples == kPfImageUint8)
        decode_codes(decoded.uint8);
    else if (spec.samples == kPfImageUint16)
        decode_codes(decoded.uint16);
    else
        convert([&](size_t k) { return decoded.floats[k]; },
                [&](size_t k) { return to_linear(decoded.floats[k]); });
    ApplyValueOptions(options, &texture);
    return texture;
}

void ApplyValueOptions(const ImageDecodeOptions& options, Texture* texture) {
    texture->wrap_u = options.wrap_u, texture->wrap_v = options.wrap_v;
    for (Rgb& texel : texture->texels) {
        if (options.invert) texel = Max(Rgb(1.0f) - texel, Rgb(0.0f));
        if (options.exponent != 1)
            for (int c = 0; c < 3; ++c)
                texel[c] =
                    static_cast<float>(std::pow(std::max(0.0, double(texel[c])), options.exponent));
    }
}

}  // namespace pf
