// Packed arrays come back bit for bit (NaN payloads, signed zeros, denormals, arrays of many
// chunks), the same bytes whatever the thread count, in whichever layout packs smaller; and
// a truncated or altered array is refused or, where the change did not touch a value, read
// the same, never read as other numbers.
#include "core/util/packed_arrays.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>
#include <zstd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "core/math/vec3.h"

namespace pf {
namespace {

// Doubles of every kind: smooth values, noise, the special ones.
std::vector<Rgbd> Values(size_t count, uint32_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<Rgbd> values(count);
    for (size_t i = 0; i < count; ++i)
        values[i] = Rgbd(1.0 + 1e-3 * double(i), std::bit_cast<double>(rng()), 0.25);
    const double specials[] = {-0.0, std::numeric_limits<double>::denorm_min(),
                               std::numeric_limits<double>::infinity(),
                               std::bit_cast<double>(uint64_t{0x7ff8dead0000beef}),  // a NaN
                               std::numeric_limits<double>::max()};
    for (size_t i = 0; i < std::size(specials) && i < count; ++i) values[i].z = specials[i];
    return values;
}

bool SameBytes(const std::vector<Rgbd>& a, const std::vector<Rgbd>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Rgbd)) == 0;
}

TEST(PackedArraysTest, ArraysComeBackBitForBit) {
    // Past one chunk, not a whole number of them; one value; none.
    const size_t many = 2 * kPackedChunkBytes / sizeof(Rgbd) + 12345;
    const std::vector<Rgbd> large = Values(many, 1), one = Values(1, 2), none;
    std::vector<uint32_t> words(1000);
    for (size_t i = 0; i < words.size(); ++i) words[i] = uint32_t(i * 2654435761u);
    ByteWriter out;
    out.Value<uint32_t>(7);
    const PackedArray arrays[] = {large, one, none, words};
    WritePacked(out, arrays);
    out.Value<uint32_t>(8);
    EXPECT_LT(out.Bytes().size(), many * sizeof(Rgbd)) << "the smooth and constant doubles pack";

    ByteReader in(out.Bytes());
    uint32_t before = 0, after = 0;
    std::vector<Rgbd> large_read, one_read, none_read;
    std::vector<uint32_t> words_read;
    ASSERT_TRUE(in.Value(&before) && before == 7);
    ASSERT_TRUE(ReadPacked(in, many, &large_read));
    ASSERT_TRUE(ReadPacked(in, 1, &one_read));
    ASSERT_TRUE(ReadPacked(in, 0, &none_read));
    ASSERT_TRUE(ReadPacked(in, words.size(), &words_read));
    ASSERT_TRUE(in.Value(&after) && after == 8);
    EXPECT_TRUE(in.AtEnd());
    EXPECT_TRUE(SameBytes(large_read, large));
    EXPECT_TRUE(SameBytes(one_read, one));
    EXPECT_TRUE(none_read.empty());
    EXPECT_EQ(words_read, words);
}

TEST(PackedArraysTest, TheBytesDoNotDependOnTheThreadCount) {
    const std::vector<Rgbd> values = Values(3 * kPackedChunkBytes / sizeof(Rgbd), 3);
    const auto pack = [&](int threads) {
        ByteWriter out;
        tbb::task_arena(threads).execute([&] {
            const PackedArray arrays[] = {values};
            WritePacked(out, arrays);
        });
        return out.Bytes();
    };
    EXPECT_EQ(pack(1), pack(tbb::this_task_arena::max_concurrency()));
}

// The layout byte of each chunk of the one array in `bytes` (packed_arrays.h).
std::vector<int> Layouts(const std::string& bytes) {
    std::vector<int> layouts;
    ByteReader in(bytes);
    uint64_t count = 0, size = 0;
    std::string_view frame;
    if (!in.Value(&count)) return layouts;
    while (in.Value(&size) && in.Bytes(size, &frame)) {
        std::string content(ZSTD_getFrameContentSize(frame.data(), frame.size()), '\0');
        if (ZSTD_isError(
                ZSTD_decompress(content.data(), content.size(), frame.data(), frame.size())))
            return {};
        layouts.push_back(content[0]);
    }
    return layouts;
}

template <typename T>
std::string Pack(const std::vector<T>& values) {
    ByteWriter out;
    const PackedArray arrays[] = {values};
    WritePacked(out, arrays);
    return out.Bytes();
}

TEST(PackedArraysTest, EachLayoutIsChosenWhereItPacksSmaller) {
    // Smooth doubles: sign and exponent bytes that repeat plane by plane, mantissas that do not.
    std::vector<double> smooth(4096);
    for (size_t i = 0; i < smooth.size(); ++i) smooth[i] = std::sqrt(1.0 + double(i));
    // A few distinct noisy values repeated whole (as a hit point's photon sums are, built from
    // a few distinct fluxes): only the values as they are show zstd the repeats.
    const std::vector<Rgbd> distinct = Values(7, 6);
    std::mt19937 rng(5);
    std::vector<Rgbd> repeated(4096);
    for (Rgbd& value : repeated) value = distinct[rng() % distinct.size()];
    const std::string smooth_bytes = Pack(smooth), repeated_bytes = Pack(repeated);
    EXPECT_EQ(Layouts(smooth_bytes), std::vector<int>{1}) << "byte planes";
    EXPECT_EQ(Layouts(repeated_bytes), std::vector<int>{0}) << "as they are";
    EXPECT_LT(repeated_bytes.size(), repeated.size() * 4) << "under 4 bytes a 24-byte value";
    std::vector<double> smooth_read;
    std::vector<Rgbd> repeated_read;
    ByteReader smooth_in(smooth_bytes), repeated_in(repeated_bytes);
    ASSERT_TRUE(ReadPacked(smooth_in, smooth.size(), &smooth_read));
    ASSERT_TRUE(ReadPacked(repeated_in, repeated.size(), &repeated_read));
    EXPECT_EQ(std::memcmp(smooth_read.data(), smooth.data(), smooth.size() * sizeof(double)), 0);
    EXPECT_TRUE(SameBytes(repeated_read, repeated));
}

TEST(PackedArraysTest, TruncatedOrAlteredArraysAreRefusedNeverMisread) {
    const std::vector<Rgbd> values = Values(200, 4);
    ByteWriter out;
    const PackedArray arrays[] = {values};
    WritePacked(out, arrays);
    const std::string bytes = out.Bytes();
    std::vector<Rgbd> read;
    for (size_t length = 0; length < bytes.size(); ++length) {
        ByteReader in(std::string_view(bytes).substr(0, length));
        EXPECT_FALSE(ReadPacked(in, values.size(), &read)) << length << " bytes";
    }
    {
        ByteReader in(bytes);
        EXPECT_FALSE(ReadPacked(in, values.size() + 1, &read)) << "another count";
    }
    // Every byte altered, two ways: refused, or (a change zstd ignores, such as an unused
    // header bit) every value read as written. The frame's checksum covers the layout byte.
    size_t refused = 0;
    for (size_t at = 0; at < bytes.size(); ++at)
        for (uint8_t flip : {uint8_t{0x01}, uint8_t{0xff}}) {
            std::string altered = bytes;
            altered[at] = static_cast<char>(altered[at] ^ flip);
            ByteReader in(altered);
            if (!ReadPacked(in, values.size(), &read))
                ++refused;
            else
                EXPECT_TRUE(SameBytes(read, values)) << "byte " << at << " ^ " << int(flip);
        }
    EXPECT_GT(refused, bytes.size()) << "most alterations are refused";
}

}  // namespace
}  // namespace pf
