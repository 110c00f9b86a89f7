// Image decoding from memory through OpenImageIO's IOProxy.
#include "core/scene/image_decode.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "absl/strings/str_cat.h"

namespace pf {
namespace {

// OpenImageIO's errors can span lines; messages here are one line.
std::string FirstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

}  // namespace

absl::StatusOr<Texture> DecodeImage(std::string_view bytes, const std::string& name,
                                    const SceneLimits& limits, const ImageDecodeOptions& options) {
    auto error = [&](const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat(name, ": ", what));
    };
    const size_t dot = name.rfind('.');
    if (dot == std::string::npos) return error("image file has no extension to tell its format");
    // OpenImageIO probes the file name on disk while it picks a reader; a name under
    // /dev/null cannot be opened, so only the proxy's bytes are ever read.
    const std::string probe_name = absl::StrCat("/dev/null/image", name.substr(dot));
    OIIO::Filesystem::IOMemReader proxy(bytes.data(), bytes.size());
    std::unique_ptr<OIIO::ImageInput> input =
        OIIO::ImageInput::create(OIIO::string_view(probe_name), false, nullptr, &proxy);
    if (!input)
        return error(absl::StrCat("not a readable image (", FirstLine(OIIO::geterror()), ")"));
    if (!input->supports("ioproxy"))
        return error(absl::StrCat("image format '", input->format_name(),
                                  "' cannot be read from a scene bundle"));
    input->set_ioproxy(&proxy);
    OIIO::ImageSpec spec;
    // Colour as stored: glTF and pbrt-v4 read an RGBA image's colour without alpha multiplied
    // in (OpenImageIO would premultiply a PNG's).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    if (!input->open(probe_name, spec, config))
        return error(absl::StrCat("not a readable image (", FirstLine(input->geterror()), ")"));
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth != 1)
        return error("image has no pixels or is a volume");
    const uint64_t pixels = uint64_t(spec.width) * uint64_t(spec.height);
    if (pixels > limits.max_image_pixels)
        return absl::ResourceExhaustedError(absl::StrCat(name, ": image is ", spec.width, "x",
                                                         spec.height, ", over the limit of ",
                                                         limits.max_image_pixels, " pixels"));
    ImageEncoding encoding = options.encoding;
    if (encoding == ImageEncoding::kAuto)
        encoding = spec.format.is_floating_point() ? ImageEncoding::kLinear : ImageEncoding::kSrgb;
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
    const size_t count = pixels * size_t(spec.nchannels);
    const int channels = spec.nchannels;
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
    // 8- and 16-bit images (PNG, JPEG: nearly every glTF texture) are read as stored, with
    // no conversion, and decoded through a table of every code (a pow per code, not per value;
    // a quarter or half the memory of floats); others as floats.
    const auto read_codes = [&](auto code_type, OIIO::TypeDesc format) -> absl::Status {
        using Code = decltype(code_type);
        const std::unique_ptr<Code[]> codes(new Code[count]);
        if (!input->read_image(0, 0, 0, spec.nchannels, format, codes.get()))
            return error(
                absl::StrCat("image data is corrupt (", FirstLine(input->geterror()), ")"));
        constexpr size_t kCodes = size_t{std::numeric_limits<Code>::max()} + 1;
        constexpr float kLargest = std::numeric_limits<Code>::max();
        std::vector<float> table(kCodes);
        for (size_t code = 0; code < kCodes; ++code)
            table[code] = to_linear(static_cast<float>(code) / kLargest);
        convert([&](size_t k) { return static_cast<float>(codes[k]) / kLargest; },
                [&](size_t k) { return table[codes[k]]; });
        return absl::OkStatus();
    };
    if (spec.channelformats.empty() && spec.format == OIIO::TypeDesc::UINT8) {
        if (absl::Status status = read_codes(uint8_t{}, OIIO::TypeDesc::UINT8); !status.ok())
            return status;
    } else if (spec.channelformats.empty() && spec.format == OIIO::TypeDesc::UINT16) {
        if (absl::Status status = read_codes(uint16_t{}, OIIO::TypeDesc::UINT16); !status.ok())
            return status;
    } else {
        const std::unique_ptr<float[]> values(new float[count]);
        if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, values.get()))
            return error(
                absl::StrCat("image data is corrupt (", FirstLine(input->geterror()), ")"));
        convert([&](size_t k) { return values[k]; },
                [&](size_t k) { return to_linear(values[k]); });
    }
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
