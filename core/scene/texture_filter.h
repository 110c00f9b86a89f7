// Filtered texture lookups: MIP levels made once from each texture by 2x2 box filtering, and
// trilinear lookups with periodic wrapping (as pbrt-v4's MIPMap does with its bilinear
// filter). Plain C++ in pf_core, so that the coordinator's camera pass and every worker's
// camera samples (sppm, path, pm) filter alike, with no image library on the workers.
#pragma once

#include <memory>
#include <vector>

#include "core/scene/texture.h"

namespace pf {

// A filter over `textures` (indices as in Scene::textures), which it keeps alive. Its levels
// are built here, one pass per texture (a third more memory than the textures).
std::shared_ptr<const TextureFilter> MakeTextureFilter(
    std::vector<std::shared_ptr<const Texture>> textures);

}  // namespace pf
