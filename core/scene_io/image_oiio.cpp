// pf_image_oiio: the module that decodes images held in memory through OpenImageIO's IOProxy
// (image_module.h); image_decode.cpp loads it at a process's first image and turns the
// samples into textures.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <memory>
#include <string>
#include <type_traits>

#include "core/scene_io/image_module.h"

namespace {

// The first line of `text` into `error` (OpenImageIO's errors can span lines; messages are one
// line); returns kPfImageFailed.
int32_t Fail(const std::string& text, char* error, size_t error_size) {
    if (error_size == 0) return kPfImageFailed;
    const std::string line = text.substr(0, text.find('\n'));
    const size_t length = std::min(line.size(), error_size - 1);
    std::memcpy(error, line.data(), length);
    error[length] = '\0';
    return kPfImageFailed;
}

int32_t Decode(const void* bytes, size_t size, const char* extension, PfImageAllocate allocate,
               void* context, char* error, size_t error_size) {
    // OpenImageIO probes the file name on disk while it picks a reader; a name under
    // /dev/null cannot be opened, so only the proxy's bytes are ever read.
    const std::string probe_name = std::string("/dev/null/image") + extension;
    OIIO::Filesystem::IOMemReader proxy(const_cast<void*>(bytes), size);
    std::unique_ptr<OIIO::ImageInput> input =
        OIIO::ImageInput::create(OIIO::string_view(probe_name), false, nullptr, &proxy);
    if (!input) return Fail("not a readable image (" + OIIO::geterror() + ")", error, error_size);
    if (!input->supports("ioproxy"))
        return Fail(std::string("image format '") + input->format_name() +
                        "' cannot be read from a scene bundle",
                    error, error_size);
    input->set_ioproxy(&proxy);
    OIIO::ImageSpec spec;
    // Colour as stored: glTF and pbrt-v4 read an RGBA image's colour without alpha multiplied
    // in (OpenImageIO would premultiply a PNG's).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    if (!input->open(probe_name, spec, config))
        return Fail("not a readable image (" + input->geterror() + ")", error, error_size);
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth != 1)
        return Fail("image has no pixels or is a volume", error, error_size);
    // 8- and 16-bit images (PNG, JPEG: nearly every glTF texture) are read as stored, with no
    // conversion (a quarter or half the memory of floats); others as floats.
    const bool uniform = spec.channelformats.empty();
    const OIIO::TypeDesc format = uniform && spec.format == OIIO::TypeDesc::UINT8 ? spec.format
                                  : uniform && spec.format == OIIO::TypeDesc::UINT16
                                      ? spec.format
                                      : OIIO::TypeDesc::FLOAT;
    const PfImageShape shape{spec.width, spec.height, spec.nchannels,
                             format == OIIO::TypeDesc::UINT8    ? kPfImageUint8
                             : format == OIIO::TypeDesc::UINT16 ? kPfImageUint16
                                                                : kPfImageFloat};
    void* samples = allocate(context, &shape);
    if (!samples) return kPfImageStopped;
    if (!input->read_image(0, 0, 0, spec.nchannels, format, samples))
        return Fail("image data is corrupt (" + input->geterror() + ")", error, error_size);
    return kPfImageDecoded;
}

}  // namespace

// Checked against image_module.h's type where it is compiled.
extern "C" __attribute__((visibility("default"))) int32_t pf_decode_image_v1(
    const void* bytes, size_t size, const char* extension, PfImageAllocate allocate, void* context,
    char* error, size_t error_size) {
    static_assert(std::is_same_v<decltype(&pf_decode_image_v1), PfDecodeImageFunction>);
    // No exception crosses the C boundary.
    try {
        return Decode(bytes, size, extension, allocate, context, error, error_size);
    } catch (const std::exception& exception) {
        return Fail(std::string("image could not be decoded (") + exception.what() + ")", error,
                    error_size);
    }
}
