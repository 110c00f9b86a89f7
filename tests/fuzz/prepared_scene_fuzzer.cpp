// libFuzzer target for the decoder of prepared scenes, the one scene input a worker takes
// (core/scene/prepared_scene.h). The input is a payload: the fuzzer frames it with a valid
// header and checksum, as a hostile coordinator could, so that mutations reach the checks
// behind the checksum; the unframed input is decoded too, for the header's own checks. Any
// outcome but a crash, a sanitizer report or a leak is fine. A scene that decodes is walked
// as tracing would walk it (every triangle's surface at its centre, every world curve's
// half way along it).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/geometry/ray.h"
#include "core/scene/prepared_scene.h"
#include "core/util/byte_stream.h"
#include "core/util/sha256.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string payload(reinterpret_cast<const char*>(data), size);
    pf::ByteWriter framed;
    framed.Bytes().append("PFSCENE", 8);
    framed.Value<uint32_t>(pf::kPreparedSceneVersion);
    framed.Value<uint64_t>(payload.size());
    framed.Bytes().append(pf::Sha256Hex(payload));
    framed.Bytes().append(payload);
    (void)pf::DecodePreparedScene(payload, true);
    const absl::StatusOr<pf::Scene> scene = pf::DecodePreparedScene(framed.Bytes(), true);
    if (!scene.ok()) return 0;
    for (uint32_t t = 0; t < scene->WorldTriangleCount(); ++t) {
        pf::RayHit hit;
        hit.triangle = t;
        hit.instance = pf::Instance::kNone;
        hit.b1 = hit.b2 = 1.0f / 3;
        const pf::SurfacePoint surface = scene->Surface(hit);
        (void)scene->BaseColor(surface, 0.01f);
    }
    for (uint32_t c = 0; c < scene->WorldCurveCount(); ++c) {  // met half way, side on
        pf::RayHit hit;
        hit.triangle = pf::RayHit::kCurveBit | c;
        hit.instance = pf::Instance::kNone;
        hit.b1 = 0.5f;
        hit.t = 1;
        hit.origin = pf::Vec3(0, 0, -1);
        hit.direction = pf::Vec3(0, 0, 1);
        const pf::SurfacePoint surface = scene->Surface(hit);
        (void)scene->BaseColor(surface, 0.01f);
        (void)scene->CurveAlpha(c, surface.uv.x, surface.uv.y);
    }
    return 0;
}
