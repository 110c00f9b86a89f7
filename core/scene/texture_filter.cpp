// OpenImageIO's TextureSystem reading our decoded textures through an ImageInput of its own
// (OpenImageIO calls it whenever its cache needs texels); each filter has a private
// TextureSystem, so scenes do not share cache entries.
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
    bool open(const std::string& name, OIIO::ImageSpec& spec, const OIIO::ImageSpec& config) override {
        const OIIO::ParamValue* pointer = config.find_attribute(kTextureAttribute, OIIO::TypeDesc::PTR);
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
        if (texture_ == nullptr || subimage != 0 || miplevel != 0 || y < 0 || y >= texture_->height) return false;
        static_assert(sizeof(Rgb) == 3 * sizeof(float), "texels are packed float RGB");
        std::memcpy(data, texture_->texels.data() + static_cast<size_t>(y) * texture_->width,
                    sizeof(Rgb) * texture_->width);
        return true;
    }

private:
    const Texture* texture_ = nullptr;
};

OIIO::ImageInput* CreateTextureInput() { return new TextureInput; }

class OiioTextureFilter final : public TextureFilter {
public:
    explicit OiioTextureFilter(std::vector<std::shared_ptr<const Texture>> textures)
        : textures_(std::move(textures)), system_(OIIO::TextureSystem::create(false)) {
        system_->attribute("automip", 1);   // MIP levels made from level 0 on first use
        system_->attribute("autotile", 64);  // cached in tiles, not whole levels
        for (size_t i = 0; i < textures_.size(); ++i) {
            const OIIO::ustring name(absl::StrCat("photonfarm-texture-", i));
            OIIO::ImageSpec config;
            const Texture* texture = textures_[i].get();
            config.attribute(kTextureAttribute, OIIO::TypeDesc::PTR, &texture);
            system_->imagecache()->add_file(name, CreateTextureInput, &config);
            handles_.push_back(system_->get_texture_handle(name));
        }
    }
    ~OiioTextureFilter() override { OIIO::TextureSystem::destroy(system_); }
    OiioTextureFilter(const OiioTextureFilter&) = delete;
    OiioTextureFilter& operator=(const OiioTextureFilter&) = delete;

    Rgb Sample(uint32_t texture, float u, float v, float footprint) const override {
        OIIO::TextureOpt options;
        options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
        options.mipmode = OIIO::TextureOpt::MipModeTrilinear;
        options.interpmode = OIIO::TextureOpt::InterpBilinear;
        float result[3] = {0, 0, 0};
        if (!system_->texture(handles_[texture], nullptr, options, u, v, footprint, 0, 0, footprint, 3, result)) {
            // Cannot happen for textures in memory; should it, the point lookup stands in.
            if (!warned_.exchange(true)) spdlog::warn("texture lookup failed: {}", system_->geterror());
            return textures_[texture]->Sample(u, v);
        }
        return {result[0], result[1], result[2]};
    }

private:
    std::vector<std::shared_ptr<const Texture>> textures_;
    OIIO::TextureSystem* system_;
    std::vector<OIIO::TextureSystem::TextureHandle*> handles_;
    mutable std::atomic<bool> warned_{false};
};

}  // namespace

std::shared_ptr<const TextureFilter> MakeTextureFilter(std::vector<std::shared_ptr<const Texture>> textures) {
    return std::make_shared<OiioTextureFilter>(std::move(textures));
}

}  // namespace pf
