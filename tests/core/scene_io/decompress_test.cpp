// gzip in memory: round trips, joined members, and malformed, truncated or oversized streams
// refused naming the file; pbrt scenes read .pbrt.gz includes and .ply.gz meshes through it.
#include "core/scene_io/decompress.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <string>

#include "core/scene_io/scene_loader.h"
#include "tests/support/ply_fixture.h"

namespace pf {
namespace {

// `text` as a gzip file, as gzip(1) writes one.
std::string Gzip(const std::string& text) {
    z_stream stream{};
    EXPECT_EQ(deflateInit2(&stream, 9, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
    std::string out(deflateBound(&stream, text.size()) + 32, '\0');
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
    stream.avail_in = static_cast<uInt>(text.size());
    stream.next_out = reinterpret_cast<Bytef*>(out.data());
    stream.avail_out = static_cast<uInt>(out.size());
    EXPECT_EQ(deflate(&stream, Z_FINISH), Z_STREAM_END);
    out.resize(stream.total_out);
    deflateEnd(&stream);
    return out;
}

TEST(DecompressTest, RoundTripsAndJoinsMembers) {
    std::string text;
    for (int i = 0; i < 20000; ++i) text += "Shape \"sphere\" \"float radius\" 1\n";
    const absl::StatusOr<std::string> back = Gunzip(Gzip(text), "a.pbrt.gz", 1u << 30);
    ASSERT_TRUE(back.ok()) << back.status();
    EXPECT_EQ(*back, text);
    const absl::StatusOr<std::string> joined =
        Gunzip(Gzip("first\n") + Gzip("second\n"), "b.gz", 1024);
    ASSERT_TRUE(joined.ok()) << joined.status();
    EXPECT_EQ(*joined, "first\nsecond\n");
    EXPECT_TRUE(Gunzip(Gzip(""), "empty.gz", 10).ok());
}

TEST(DecompressTest, BadStreamsAreRefusedNamingTheFile) {
    const std::string good = Gzip(std::string(100000, 'x'));
    const auto refused = [](const absl::StatusOr<std::string>& result, const std::string& what) {
        ASSERT_FALSE(result.ok()) << what;
        EXPECT_NE(result.status().message().find("c.ply.gz"), std::string::npos) << result.status();
        EXPECT_NE(result.status().message().find(what), std::string::npos) << result.status();
    };
    refused(Gunzip("plain text", "c.ply.gz", 1 << 20), "no gzip header");
    refused(Gunzip(good.substr(0, good.size() / 2), "c.ply.gz", 1 << 20), "truncated");
    std::string corrupted = good;
    corrupted[20] ^= 0x55, corrupted[21] ^= 0x55;
    refused(Gunzip(corrupted, "c.ply.gz", 1 << 20), "not a valid gzip file");
    // A small file that would expand past the limit: refused before it is all inflated.
    const absl::StatusOr<std::string> bomb = Gunzip(good, "c.ply.gz", 4096);
    ASSERT_FALSE(bomb.ok());
    EXPECT_TRUE(absl::IsResourceExhausted(bomb.status())) << bomb.status();
}

TEST(DecompressTest, PbrtReadsCompressedIncludesAndMeshes) {
    // An included .pbrt.gz holding a .ply.gz mesh: a binary PLY triangle.
    const std::string ply = testing::TrianglePly();
    SceneBundle bundle;
    bundle.main_file = "scene.pbrt";
    bundle.files["scene.pbrt"] =
        "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
        "LightSource \"point\" \"rgb I\" [1 1 1]\nInclude \"geometry/part.pbrt.gz\"\n";
    bundle.files["geometry/part.pbrt.gz"] =
        Gzip("Shape \"plymesh\" \"string filename\" \"geometry/mesh.ply.gz\"\n");
    bundle.files["geometry/mesh.ply.gz"] = Gzip(ply);
    const absl::StatusOr<Scene> scene = LoadScene(bundle, "scene.pbrt");
    ASSERT_TRUE(scene.ok()) << scene.status();
    EXPECT_EQ(scene->triangles.size(), 1u);
    bundle.files["geometry/mesh.ply.gz"] = Gzip(ply).substr(0, 30);
    const absl::StatusOr<Scene> broken = LoadScene(bundle, "scene.pbrt");
    ASSERT_FALSE(broken.ok());
    EXPECT_NE(broken.status().message().find("geometry/mesh.ply.gz"), std::string::npos)
        << broken.status();
}

}  // namespace
}  // namespace pf
