// The door between the scene loaders and pf_image_oiio, the module that decodes images through
// OpenImageIO: image_decode.cpp loads it (dlopen) at a process's first image, so a process
// that reads no image never loads OpenImageIO's ~290 shared libraries (core/CMakeLists.txt).
// Plain C types only; both sides are built from this header in the same build.
#pragma once

#include <cstddef>
#include <cstdint>

extern "C" {

// How the module hands over an image's samples.
enum PfImageSamples : int32_t {
    kPfImageUint8 = 1,   // 8-bit codes as stored
    kPfImageUint16 = 2,  // 16-bit codes as stored
    kPfImageFloat = 3,   // everything else, as 32-bit floats
};

// An image's size, known before its pixels are decoded.
struct PfImageShape {
    int32_t width, height, channels;  // each > 0
    int32_t samples;                  // PfImageSamples
};

// Called by the decoder once `shape` is known, before any pixel is decoded: where its
// width x height x channels samples go (interleaved, top row first, owned by the caller), or
// null to stop there (an image over a limit).
typedef void* (*PfImageAllocate)(void* context, const PfImageShape* shape);

enum PfImageResult : int32_t {
    kPfImageDecoded = 0,
    kPfImageFailed = 1,   // a one-line reason, without the file's name, is in `error`
    kPfImageStopped = 2,  // `allocate` returned null
};

// Decodes the `size` bytes at `bytes`, an image file in memory whose `extension` (".png")
// picks the format; nothing is read from disk. `error` takes a NUL-terminated message of at
// most `error_size` bytes. Colour is read as stored (alpha not multiplied in). Thread-safe.
typedef int32_t (*PfDecodeImageFunction)(const void* bytes, size_t size, const char* extension,
                                         PfImageAllocate allocate, void* context, char* error,
                                         size_t error_size);

}  // extern "C"

// The module's one exported symbol, a PfDecodeImageFunction. Its version is in its name: a
// change to anything above is a new name, so a stale module is refused, not misread.
inline constexpr char kPfDecodeImageSymbol[] = "pf_decode_image_v1";
// The module's file, in the folder `lib` beside the executables' folder (build/lib for
// build/tests/..., /usr/local/lib for /usr/local/bin/... in the containers).
inline constexpr char kPfImageModuleFile[] = "libpf_image_oiio.so";
