// MIP levels by 2x2 box filtering and trilinear lookups between them.
#include "core/scene/texture_filter.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace pf {
namespace {

// The next coarser level: each texel the average of the 2x2 texels under it (a level of odd
// width or height wraps its last texel with its first, as the periodic lookups do).
Texture Downsample(const Texture& fine) {
    Texture coarse;
    coarse.wrap_u = fine.wrap_u, coarse.wrap_v = fine.wrap_v;
    coarse.width = std::max(1, fine.width / 2);
    coarse.height = std::max(1, fine.height / 2);
    coarse.texels.resize(static_cast<size_t>(coarse.width) * coarse.height);
    for (int y = 0; y < coarse.height; ++y)
        for (int x = 0; x < coarse.width; ++x) {
            const int x0 = 2 * x, y0 = 2 * y;
            coarse.texels[static_cast<size_t>(y) * coarse.width + x] =
                (fine.Texel(x0, y0) + fine.Texel(x0 + 1, y0) + fine.Texel(x0, y0 + 1) +
                 fine.Texel(x0 + 1, y0 + 1)) *
                0.25f;
        }
    return coarse;
}

class MipTextureFilter final : public TextureFilter {
public:
    explicit MipTextureFilter(std::vector<std::shared_ptr<const Texture>> textures)
        : textures_(std::move(textures)), levels_(textures_.size()) {
        // Each texture's levels on a thread of its own: a glTF model's dozen 2048^2 images.
        tbb::parallel_for(size_t{0}, textures_.size(), [&](size_t t) {
            const Texture* level = textures_[t].get();
            if (level == nullptr || level->texels.empty()) return;
            while (level->width > 1 || level->height > 1) {
                levels_[t].push_back(Downsample(*level));
                level = &levels_[t].back();
            }
        });
    }

    Rgb Sample(uint32_t texture, float u, float v, float footprint) const override {
        const Texture& finest = *textures_[texture];
        const std::vector<Texture>& coarser = levels_[texture];
        const auto level = [&](int l) -> const Texture& {
            return l == 0 ? finest : coarser[l - 1];
        };
        // The level whose texels are as wide as the footprint (level 0 below one texel).
        const int last = static_cast<int>(coarser.size());
        const float resolution = static_cast<float>(std::max(finest.width, finest.height));
        const float lod = std::log2(std::max(footprint * resolution, 1e-8f));
        if (!(lod > 0)) return finest.Sample(u, v);
        if (lod >= static_cast<float>(last)) return level(last).Sample(u, v);
        const int below = static_cast<int>(lod);
        const float t = lod - static_cast<float>(below);
        return level(below).Sample(u, v) * (1 - t) + level(below + 1).Sample(u, v) * t;
    }

private:
    std::vector<std::shared_ptr<const Texture>> textures_;
    std::vector<std::vector<Texture>> levels_;  // per texture: levels 1, 2, ... down to 1x1
};

}  // namespace

std::shared_ptr<const TextureFilter> MakeTextureFilter(
    std::vector<std::shared_ptr<const Texture>> textures) {
    return std::make_shared<MipTextureFilter>(std::move(textures));
}

}  // namespace pf
