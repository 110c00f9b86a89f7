// EXT_meshopt_compression (and its ratified twin KHR_meshopt_compression): glTF buffer views
// stored as meshoptimizer streams (Debian's libmeshoptimizer), decoded into the fallback buffers
// they stand for before tinygltf reads the file, so that accessors read them as any other data.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"

namespace pf {

// One compressed buffer view, as its extension object describes it.
struct MeshoptStream {
    uint64_t count = 0;           // elements
    uint64_t stride = 0;          // bytes an element
    std::string mode;             // "ATTRIBUTES", "TRIANGLES" or "INDICES"
    std::string filter = "NONE";  // "NONE", "OCTAHEDRAL", "QUATERNION" or "EXPONENTIAL"
};

// The count x stride bytes `compressed` decodes to, filter applied. Errors say what is wrong
// (a mode, filter or stride the extension does not allow, a stream the decoder refuses, an
// output far larger than its stream could hold), for the caller to place.
absl::StatusOr<std::string> DecodeMeshoptStream(std::string_view compressed,
                                                const MeshoptStream& stream);

// Reads a file of the bundle by its bundle path.
using BundleFileReader = std::function<absl::StatusOr<std::string_view>(const std::string&)>;

// The glTF file `contents` (a .glb when `binary`, in bundle folder `folder`; `read` gives the
// files its buffers name) with every compressed buffer view decoded into its fallback buffer
// (one without data, given as a data URI); unchanged where nothing is compressed, or where a
// view's buffer holds the uncompressed data already. Errors name the buffer view
// ("bufferViews[3]: ...").
absl::StatusOr<std::string> DecodeMeshoptBuffers(const std::string& contents, bool binary,
                                                 const std::string& folder,
                                                 const BundleFileReader& read);

}  // namespace pf
