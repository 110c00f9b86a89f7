// gzip through zlib's inflate.
#include "core/scene_io/decompress.h"

#include <zlib.h>

#include <algorithm>

#include "absl/strings/str_cat.h"

namespace pf {

bool IsGzip(std::string_view bytes) {
    return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
           static_cast<unsigned char>(bytes[1]) == 0x8b;
}

absl::StatusOr<std::string> Gunzip(std::string_view bytes, const std::string& name,
                                   uint64_t max_bytes) {
    const auto invalid = [&](const std::string& what) {
        return absl::InvalidArgumentError(absl::StrCat(name, ": not a valid gzip file: ", what));
    };
    if (!IsGzip(bytes)) return invalid("no gzip header");
    z_stream stream{};
    if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK) return invalid("zlib failed to start");
    std::string out;
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
    stream.avail_in = static_cast<uInt>(std::min<size_t>(bytes.size(), UINT32_MAX));
    char buffer[1 << 16];
    int result = Z_OK;
    while (true) {
        stream.next_out = reinterpret_cast<Bytef*>(buffer);
        stream.avail_out = sizeof buffer;
        result = inflate(&stream, Z_NO_FLUSH);
        const size_t produced = sizeof buffer - stream.avail_out;
        if (out.size() + produced > max_bytes) {
            inflateEnd(&stream);
            return absl::ResourceExhaustedError(absl::StrCat(
                name, ": decompresses to more than the limit of ", max_bytes, " bytes"));
        }
        out.append(buffer, produced);
        if (result == Z_STREAM_END) {
            // Another member follows (concatenated gzip files): decompress it too.
            if (stream.avail_in > 0 &&
                IsGzip(std::string_view(reinterpret_cast<const char*>(stream.next_in),
                                        stream.avail_in))) {
                inflateReset(&stream);
                continue;
            }
            break;
        }
        if (result != Z_OK) {
            const std::string what = result == Z_BUF_ERROR   ? "truncated"
                                     : stream.msg != nullptr ? stream.msg
                                                             : "corrupted";
            inflateEnd(&stream);
            return invalid(what);
        }
        if (stream.avail_in == 0 && produced == 0) {
            inflateEnd(&stream);
            return invalid("truncated");
        }
    }
    inflateEnd(&stream);
    return out;
}

}  // namespace pf
