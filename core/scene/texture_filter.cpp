// OpenImageIO's TextureSystem reading our decoded textures through an ImageInput of its own
// (OpenImageIO calls it whenever its cache needs texels). One TextureSystem serves the process,
// so all scenes share one cache budget; each filter's textures have names of their own and are
// dropped from it when the filter goes.
#include "core/scene/texture_filter.h"

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cstring>
#include <string>

#include "absl/strings/str_cat.h"

namespace pf {
namespace {

constexpr char kTextureAttribute[] = "photonfarm:texture";

// Serves one Texture, named by a pointer in the open() configuration, as a float RGB image.
class TextureInput final : public OIIO::ImageInput {
public:
    const char* format_name() const override { return "photonfarm-texture"; }
    bool open(const std::string& name, OIIO::ImageSpec&) override {
        errorf("%s: photonfarm textures open only with their configuration", name);
        return false;
    }
    bool open(const std::string& name, OIIO::ImageSpec& spec,
              const OIIO::ImageSpec& config) override {
        const OIIO::ParamValue* pointer =
            config.find_attribute(kTextureAttribute, OIIO::TypeDesc::PTR);
        if (pointer == nullptr) return open(name, spec);
        texture_ = *static_cast<const Texture* const*>(pointer->data());
        m_spec = OIIO::ImageSpec(texture_->width, texture_->height, 3, OIIO::TypeDesc::FLOAT);
        spec = m_spec;
        return true;
    }
    bool close() override {
        texture_ = nullptr;
        return true;
    }
    bool read_native_scanline(int subimage, int miplevel, int y, int, void* data) override {
        if (texture_ == nullptr || subimage != 0 || miplevel != 0 || y < 0 || y >= texture_->height)
            return false;
        static_assert(sizeof(Rgb) == 3 * sizeof(float), "texels are packed float RGB");
        std::memcpy(data, texture_->texels.data() + static_cast<size_t>(y) * texture_->width,
                    sizeof(Rgb) * texture_->width);
        return true;
    }

private:
    const Texture* texture_ = nullptr;
};

OIIO::ImageInput* CreateTextureInput() { return new TextureInput; }

// Made once and kept for the process (OpenImageIO 2.4's TextureSystem::destroy frees its
// implementation through the interface's type, which AddressSanitizer reports).
OIIO::TextureSystem& ProcessTextureSystem() {
    static OIIO::TextureSystem* const system = [] {
        OIIO::TextureSystem* made = OIIO::TextureSystem::create(false);
        made->attribute("automip", 1);    // MIP levels made from level 0 on first use
        made->attribute("autotile", 64);  // cached in tiles, not whole levels
        return made;
    }();
    return *system;
}

class OiioTextureFilter final : public TextureFilter {
public:
    explicit OiioTextureFilter(std::vector<std::shared_ptr<const Texture>> textures)
        : textures_(std::move(textures)), system_(ProcessTextureSystem()) {
        static std::atomic<uint64_t> filters{0};
        const uint64_t filter = filters++;
        for (size_t i = 0; i < textures_.size(); ++i) {
            names_.emplace_back(absl::StrCat("photonfarm-texture-", filter, "-", i));
            OIIO::ImageSpec config;
            const Texture* texture = textures_[i].get();
            config.attribute(kTextureAttribute, OIIO::TypeDesc::PTR, &texture);
            system_.imagecache()->add_file(names_.back(), CreateTextureInput, &config);
            handles_.push_back(system_.get_texture_handle(names_.back()));
        }
    }
    // The cache lets go of the tiles and inputs of textures about to be freed.
    ~OiioTextureFilter() override {
        for (const OIIO::ustring& name : names_) system_.invalidate(name, true);
    }
    OiioTextureFilter(const OiioTextureFilter&) = delete;
    OiioTextureFilter& operator=(const OiioTextureFilter&) = delete;

    Rgb Sample(uint32_t texture, float u, float v, float footprint) const override {
        OIIO::TextureOpt options;
        options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
        options.mipmode = OIIO::TextureOpt::MipModeTrilinear;
        options.interpmode = OIIO::TextureOpt::InterpBilinear;
        float result[3] = {0, 0, 0};
        if (!system_.texture(handles_[texture], nullptr, options, u, v, footprint, 0, 0, footprint,
                             3, result)) {
            // Cannot happen for textures in memory; should it, the point lookup stands in.
            if (!warned_.exchange(true))
                spdlog::warn("texture lookup failed: {}", system_.geterror());
            return textures_[texture]->Sample(u, v);
        }
        return {result[0], result[1], result[2]};
    }

private:
    std::vector<std::shared_ptr<const Texture>> textures_;
    OIIO::TextureSystem& system_;
    std::vector<OIIO::ustring> names_;
    std::vector<OIIO::TextureSystem::TextureHandle*> handles_;
    mutable std::atomic<bool> warned_{false};
};

}  // namespace

std::shared_ptr<const TextureFilter> MakeTextureFilter(
    std::vector<std::shared_ptr<const Texture>> textures) {
    return std::make_shared<OiioTextureFilter>(std::move(textures));
}

}  // namespace pf
