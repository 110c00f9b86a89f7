// glTF textures into a Scene's.
#include "core/scene_io/gltf/gltf_textures.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <memory>

#include "absl/strings/str_cat.h"

namespace pf {

absl::StatusOr<std::pair<int, ImageDecodeOptions>> GltfTextureReader::Source(
    int texture, const std::string& element, ImageDecodeOptions options) const {
    const auto error = [&](const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat(path_, ": ", element, ": ", what));
    };
    if (texture < 0 || texture >= static_cast<int>(model_.textures.size()))
        return error(absl::StrCat("texture #", texture, " does not exist"));
    const tinygltf::Texture& source = model_.textures[texture];
    const int image = GltfTextureImage(source);
    // Only a KTX2 image: through the extension, or (as some exporters write it) as the
    // texture's own source.
    const bool ktx2 = image < 0 ? Extension(source.extensions, "KHR_texture_basisu") != nullptr
                      : image < static_cast<int>(model_.images.size())
                          ? model_.images[image].mimeType == "image/ktx2" ||
                                model_.images[image].uri.ends_with(".ktx2")
                          : false;
    if (ktx2)
        return error(absl::StrCat(
            "texture #", texture,
            " has only a KTX2 image (KHR_texture_basisu), which photonfarm cannot decode "
            "(Debian packages no KTX2/Basis Universal decoder): convert the model's KTX2 "
            "textures to PNG, e.g. with KTX-Software's `ktx extract` or glTF-Transform, and "
            "point its textures at them"));
    if (image < 0 || image >= static_cast<int>(model_.images.size()))
        return error(absl::StrCat("texture #", texture, " has no image"));
    // The sampler's wrap modes (its filters are the renderer's: bilinear, MIP levels).
    if (const int sampler = source.sampler;
        sampler >= 0 && sampler < static_cast<int>(model_.samplers.size())) {
        const auto wrap = [](int mode) {
            return mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? gpu::kWrapClamp
                   : mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? gpu::kWrapMirror
                                                                   : gpu::kWrapRepeat;
        };
        options.wrap_u = wrap(model_.samplers[sampler].wrapS);
        options.wrap_v = wrap(model_.samplers[sampler].wrapT);
    }
    return std::pair{image, options};
}

absl::StatusOr<Texture> GltfTextureReader::Decode(int texture, const std::string& element,
                                                  const ImageDecodeOptions& options) {
    const absl::StatusOr<std::pair<int, ImageDecodeOptions>> source =
        Source(texture, element, options);
    if (!source.ok()) return source.status();
    const int image = source->first;
    const auto encoded = images_.find(image);
    if (encoded == images_.end()) {
        const std::string& uri = model_.images[image].uri;
        return absl::InvalidArgumentError(
            absl::StrCat(path_, ": ", element, ": image #", image,
                         uri.empty() ? " has no data"
                                     : absl::StrCat(" '", uri,
                                                    "' is missing (not beside the "
                                                    "scene file, or not in its bundle)")));
    }
    absl::StatusOr<Texture> decoded =
        DecodeImage(encoded->second.bytes, encoded->second.name, limits_, source->second);
    if (!decoded.ok())
        return absl::Status(decoded.status().code(),
                            absl::StrCat(path_, ": ", element, ": ", decoded.status().message()));
    return decoded;
}

absl::StatusOr<int32_t> GltfTextureReader::Index(int texture, const std::string& element,
                                                 const ImageDecodeOptions& options) {
    const absl::StatusOr<std::pair<int, ImageDecodeOptions>> source =
        Source(texture, element, options);
    if (!source.ok()) return source.status();
    if (const auto it = indices_.find(*source); it != indices_.end()) return it->second;
    if (options.channels != ImageChannels::kAlpha && images_.contains(source->first)) {
        const auto index = static_cast<int32_t>(scene_->textures.size());
        scene_->textures.push_back(nullptr);
        pending_.push_back({index, texture, element, options});
        indices_[*source] = index;
        return index;
    }
    absl::StatusOr<Texture> decoded = Decode(texture, element, options);
    if (!decoded.ok()) return decoded.status();
    // An alpha channel that is all 1 (or none) cuts nothing out: no texture, no cost.
    if (options.channels == ImageChannels::kAlpha &&
        std::all_of(decoded->texels.begin(), decoded->texels.end(),
                    [](const Rgb& texel) { return texel.x >= 1.0f; })) {
        indices_[*source] = kNoTexture;
        return kNoTexture;
    }
    const auto index = static_cast<int32_t>(scene_->textures.size());
    scene_->textures.push_back(std::make_shared<const Texture>(std::move(*decoded)));
    indices_[*source] = index;
    return index;
}

absl::Status GltfTextureReader::DecodePending() {
    std::vector<absl::StatusOr<Texture>> decoded(pending_.size(), Texture{});
    tbb::parallel_for(size_t{0}, pending_.size(), [&](size_t i) {
        decoded[i] = Decode(pending_[i].texture, pending_[i].element, pending_[i].options);
    });
    for (size_t i = 0; i < pending_.size(); ++i) {
        if (!decoded[i].ok()) return decoded[i].status();
        scene_->textures[pending_[i].index] =
            std::make_shared<const Texture>(std::move(*decoded[i]));
    }
    pending_.clear();
    return absl::OkStatus();
}

GltfTextureAccess GltfTextureReader::Access(const std::string& element) {
    return {[this, element](int texture, const ImageDecodeOptions& options) {
                return Index(texture, element, options);
            },
            [this, element](int texture, const ImageDecodeOptions& options) {
                return Decode(texture, element, options);
            },
            [this](Texture texture) {
                scene_->textures.push_back(std::make_shared<const Texture>(std::move(texture)));
                return static_cast<int32_t>(scene_->textures.size() - 1);
            }};
}

}  // namespace pf
