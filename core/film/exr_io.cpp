// OpenEXR reading and writing.
#include "core/film/exr_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>

#include <cstdio>
#include <exception>

#include "absl/strings/str_cat.h"
#include "core/util/file_io.h"

namespace pf {
namespace {

void AddChannels(Imf::FrameBuffer& frame_buffer, Rgb* pixels, int width) {
    const size_t x_stride = sizeof(Rgb), y_stride = sizeof(Rgb) * static_cast<size_t>(width);
    char* base = reinterpret_cast<char*>(pixels);
    frame_buffer.insert("R", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, x), x_stride, y_stride));
    frame_buffer.insert("G", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, y), x_stride, y_stride));
    frame_buffer.insert("B", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, z), x_stride, y_stride));
}

// An EXR file written into a string.
class StringStream final : public Imf::OStream {
public:
    StringStream() : Imf::OStream("memory") {}
    void write(const char bytes[], int count) override {
        const size_t end = position_ + static_cast<size_t>(count);
        if (end > bytes_.size()) bytes_.resize(end);
        bytes_.replace(position_, static_cast<size_t>(count), bytes, static_cast<size_t>(count));
        position_ = end;
    }
    uint64_t tellp() override { return position_; }
    void seekp(uint64_t position) override { position_ = position; }
    std::string Take() { return std::move(bytes_); }

private:
    std::string bytes_;
    size_t position_ = 0;
};

}  // namespace

absl::StatusOr<std::string> EncodeExr(const Image& image, const ImageMetadata& metadata) {
    StringStream stream;
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        for (const char* channel : {"R", "G", "B"})
            header.channels().insert(channel, Imf::Channel(Imf::FLOAT));
        for (const auto& [key, value] : metadata) header.insert(key, Imf::StringAttribute(value));
        Imf::FrameBuffer frame_buffer;
        AddChannels(frame_buffer, const_cast<Rgb*>(image.pixels.data()), image.width);
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(frame_buffer);
        file.writePixels(image.height);
    } catch (const std::exception& error) {
        return absl::InvalidArgumentError(absl::StrCat("cannot encode EXR: ", error.what()));
    }
    return stream.Take();
}

absl::Status WriteExr(const std::string& path, const Image& image, const ImageMetadata& metadata) {
    absl::StatusOr<std::string> exr = EncodeExr(image, metadata);
    if (!exr.ok())
        return absl::InvalidArgumentError(absl::StrCat(path, ": ", exr.status().message()));
    return WriteFileAtomically(path, *exr);
}

absl::StatusOr<Image> ReadExr(const std::string& path, ImageMetadata* metadata) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        Image image(window.max.x - window.min.x + 1, window.max.y - window.min.y + 1);
        for (const char* channel : {"R", "G", "B"})
            if (file.header().channels().findChannel(channel) == nullptr)
                return absl::InvalidArgumentError(
                    absl::StrCat(path, ": EXR has no ", channel, " channel"));
        Imf::FrameBuffer frame_buffer;
        // Slices are addressed relative to the data window's origin.
        Rgb* origin =
            image.pixels.data() - window.min.x - static_cast<ptrdiff_t>(window.min.y) * image.width;
        AddChannels(frame_buffer, origin, image.width);
        file.setFrameBuffer(frame_buffer);
        file.readPixels(window.min.y, window.max.y);
        if (metadata != nullptr) {
            for (auto it = file.header().begin(); it != file.header().end(); ++it)
                if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                    (*metadata)[it.name()] = text->value();
        }
        return image;
    } catch (const std::exception& error) {
        return absl::InvalidArgumentError(absl::StrCat(path, ": cannot read EXR: ", error.what()));
    }
}

}  // namespace pf
