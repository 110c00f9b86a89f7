// Filtered texture lookups through OpenImageIO's TextureSystem: MIP levels made on first use
// (automip) and trilinear lookups with periodic wrapping, over a scene's decoded textures.
#pragma once

#include <memory>
#include <vector>

#include "core/scene/texture.h"

namespace pf {

// A filter over `textures` (indices as in Scene::textures), which it keeps alive: OpenImageIO
// reads their texels from memory (never from disk) when a lookup first needs them.
std::shared_ptr<const TextureFilter> MakeTextureFilter(
    std::vector<std::shared_ptr<const Texture>> textures);

}  // namespace pf
