// Reading a glTF model's accessors (through tinygltf's parsed model) into plain arrays, with
// every offset, stride and count checked against the buffers: a hostile file cannot make a
// read leave them.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <vector>

#include "absl/status/status.h"

namespace pf {

// Accessor `index` as `components` floats per element, normalised unsigned byte and short
// types converted; errors name the accessor (missing, wrong type, sparse, out of its buffer).
absl::Status ReadFloats(const tinygltf::Model& model, int index, int components,
                        std::vector<float>* out);

// Index accessor `index` (unsigned byte, short or int scalars) as 32-bit indices.
absl::Status ReadIndices(const tinygltf::Model& model, int index, std::vector<uint32_t>* out);

}  // namespace pf
