// pbrt-v4's procedural textures (textures.h), evaluated at a surface point: a texture is a
// small program of vec4 words in postfix order, each instruction pushing an RGB value (a
// constant, an image's texel, a noise texture's value) or combining the values on top of the
// stack (scale, mix, directionmix, checkerboard, dots). The CPU keeps a program in
// Texture::program; the Vulkan kernels find it in the texels binding where its GpuTexture has
// width 0 (first_texel: its first word; height: its length). Images inside a program are
// other textures, read through the backend's own lookup. One definition for both backends.
//
// An instruction is a header word (x: the op, kTexture*, as uint bits; y, z, w its fields)
// and the words after it its op takes:
//   kTextureConstant      y, z, w: the colour                                        push
//   kTextureImage         y: the image's texture (int bits); 2 words: a UV transform  push
//   kTextureMultiply      a * b, per channel (pbrt-v4's scale)                  pop 2, push
//   kTextureMix           (1 - amount) a + amount b, amount's first channel     pop 3, push
//   kTextureDirectionMix  y, z, w: the unit direction d; |n . d| a + (1 - |n . d|) b   pop 2
//   kTextureCheckerboard  2 words: a UV transform to (s, t); a on even checks, b on odd
//                         (filtered over the footprint as pbrt-v4 does)          pop 2, push
//   kTextureCheckerboard3D  3 words: a point transform; likewise in x, y and z   pop 2, push
//   kTextureDots          2 words: a UV transform to (s, t); a inside a dot, b outside  pop 2
//   kTextureBilerp        2 words: a UV transform to (s, t); 4 words: v00 v01 v10 v11  push
//   kTextureFbm, kTextureWrinkled  y: omega (pbrt-v4's roughness), z: octaves (uint bits);
//                         3 words: a point transform; FBm or Turbulence               push
//   kTextureWindy         3 words: a point transform                                   push
//   kTextureMarble        y: omega, z: octaves (uint bits), w: scale; 1 word: x the variation;
//                         3 words: a point transform                                   push
//   kTexturePower         y: an exponent: each channel max(0, c)^y                pop 1, push
//   kTextureClamp         y: a bound: each channel clamped to [0, y]              pop 1, push
// A UV transform maps the surface's texture coordinates (u, v) to (m0 u + m1 v + m2,
// m3 u + m4 v + m5): words (m0, m1, m2, m3) and (m4, m5, -, -). A point transform is a 3x4
// matrix's rows, from the world to the texture's space (pbrt-v4's textureFromRender).
#ifndef PF_CORE_SHARED_PROCEDURAL_TEXTURE_H
#define PF_CORE_SHARED_PROCEDURAL_TEXTURE_H

#include "core/shared/gpu_prelude.h"
#include "core/shared/noise.h"

PF_GPU_BEGIN

PF_CONST(uint32_t) kTextureConstant = 1;
PF_CONST(uint32_t) kTextureImage = 2;
PF_CONST(uint32_t) kTextureMultiply = 3;
PF_CONST(uint32_t) kTextureMix = 4;
PF_CONST(uint32_t) kTextureDirectionMix = 5;
PF_CONST(uint32_t) kTextureCheckerboard = 6;
PF_CONST(uint32_t) kTextureCheckerboard3D = 7;
PF_CONST(uint32_t) kTextureDots = 8;
PF_CONST(uint32_t) kTextureBilerp = 9;
PF_CONST(uint32_t) kTextureFbm = 10;
PF_CONST(uint32_t) kTextureWrinkled = 11;
PF_CONST(uint32_t) kTextureWindy = 12;
PF_CONST(uint32_t) kTextureMarble = 13;
PF_CONST(uint32_t) kTexturePower = 14;
PF_CONST(uint32_t) kTextureClamp = 15;
PF_CONST(uint32_t) kTextureOps = 16;  // one past the last op

// The values a program holds at once, at most (the loaders' programs are checked against it).
PF_CONST(int32_t) kTextureStackSize = 8;
// The octaves a noise texture sums, at most (pbrt-v4 sets no bound; its default is 8).
PF_CONST(uint32_t) kMaxNoiseOctaves = 32;

// Where a texture is looked up.
struct TextureLookup {
    vec3 position;   // world space (pbrt-v4's render space, up to a translation)
    vec3 normal;     // the surface's unit geometric normal (directionmix)
    vec2 uv;         // the surface's texture coordinates
    float width;     // the footprint's width in world units (a camera sample's); 0: a point
    float uv_width;  // the same in texture-coordinate units
};

#ifdef __cplusplus
// The CPU's programs and images: a program's words, and the backend's image lookup.
#define PF_TEXTURE_PROGRAM const vec4*
#define PF_TEXTURE_WORD(program, i) (program)[i]
class TextureImages {
public:
    virtual ~TextureImages() = default;
    // Image `texture` at coordinates uv, averaged over `width` texture-coordinate units
    // across (0: bilinear at the point).
    virtual vec3 ImageValue(int32_t texture, vec2 uv, float width) const = 0;
};
#define PF_TEXTURE_IMAGES const TextureImages&
#define PF_TEXTURE_IMAGE(images, texture, uv, width) (images).ImageValue(texture, uv, width)
#else
// The kernels': the program's first texel, and trace.glsl's ProceduralImage (point lookups).
#define PF_TEXTURE_PROGRAM uint
#define PF_TEXTURE_WORD(program, i) texels[(program) + (i)]
#define PF_TEXTURE_IMAGES uint
#define PF_TEXTURE_IMAGE(images, texture, uv, width) ProceduralImage(texture, uv)
#endif

PF_GPU_FN vec2 TextureApplyUv(vec4 first, vec4 second, vec2 uv) {
    return vec2(first.x * uv.x + first.y * uv.y + first.z,
                first.w * uv.x + second.x * uv.y + second.y);
}

// How much a UV transform scales lengths: the square root of its determinant's magnitude.
PF_GPU_FN float TextureUvScale(vec4 first, vec4 second) {
    return sqrt(abs(first.x * second.x - first.y * first.w));
}

PF_GPU_FN vec3 TextureApplyPoint(vec4 row0, vec4 row1, vec4 row2, vec3 p) {
    return vec3(row0.x * p.x + row0.y * p.y + row0.z * p.z + row0.w,
                row1.x * p.x + row1.y * p.y + row1.z * p.z + row1.w,
                row2.x * p.x + row2.y * p.y + row2.z * p.z + row2.w);
}

// How much a point transform scales lengths: the cube root of its determinant's magnitude.
PF_GPU_FN float TexturePointScale(vec4 row0, vec4 row1, vec4 row2) {
    const float determinant = row0.x * (row1.y * row2.z - row1.z * row2.y) -
                              row0.y * (row1.x * row2.z - row1.z * row2.x) +
                              row0.z * (row1.x * row2.y - row1.y * row2.x);
    return pow(abs(determinant), 1.0f / 3.0f);
}

// pbrt-v4's checkerboard along one axis: +1 on even cells, -1 on odd ones, averaged over a
// box of half-width r (its "bf", through the integral d of the square wave).
PF_GPU_FN float CheckerIntegral(float x) {
    const float y = x * 0.5f - floor(x * 0.5f) - 0.5f;
    return x * 0.5f + y * (1.0f - 2.0f * abs(y));
}
PF_GPU_FN float CheckerAxis(float x, float r) {
    if (floor(x - r) == floor(x + r)) {
        // The cell's parity in floats: an integer cast of a cell past 2^31 is undefined.
        const float cell = floor(x);
        return 1.0f - 2.0f * (cell - 2.0f * floor(cell * 0.5f));
    }
    return (CheckerIntegral(x + r) - 2.0f * CheckerIntegral(x) + CheckerIntegral(x - r)) / (r * r);
}

// pbrt-v4's InsidePolkaDot: each unit cell about an integer (s, t) holds a dot of radius 0.35
// where the noise there is positive, its centre moved by noise up to 0.15 each way.
PF_GPU_FN bool InsideDot(vec2 st) {
    const float cell_s = floor(st.x + 0.5f), cell_t = floor(st.y + 0.5f);
    vec3 noise = vec3(0.0f);  // whether there is a dot, and its centre's moves (one call a loop)
    for (int32_t k = 0; k < 3; ++k) {
        const float ds = k == 0 ? 0.5f : (k == 1 ? 1.5f : 4.5f);
        const float dt = k == 0 ? 0.5f : (k == 1 ? 2.8f : 9.8f);
        noise[k] = PerlinNoise(vec3(cell_s + ds, cell_t + dt, 0.5f));
    }
    if (!(noise.x > 0.0f)) return false;
    const float radius = 0.35f, shift = 0.5f - radius;
    const float s = st.x - (cell_s + shift * noise.y), t = st.y - (cell_t + shift * noise.z);
    return s * s + t * t < radius * radius;
}

// pbrt-v4's windy: |FBm at a tenth of the scale, 3 octaves| x FBm, 6 octaves (omega 1/2).
PF_GPU_FN float WindyNoise(vec3 p, float footprint_sq) {
    const float strength = FractalNoise(p * 0.1f, 0.01f * footprint_sq, 0.5f, 3);
    return abs(strength) * FractalNoise(p, footprint_sq, 0.5f, 6);
}

// pbrt-v4's marble's colours, the control points of its cubic Bezier segments.
PF_GPU_FN vec3 MarbleColour(int32_t i) {
    if (i == 3) return vec3(0.5f, 0.5f, 0.5f);
    if (i == 4) return vec3(0.6f, 0.59f, 0.58f);
    if (i == 7) return vec3(0.2f, 0.2f, 0.33f);
    return vec3(0.58f, 0.58f, 0.6f);
}

// pbrt-v4's marble of layers `marble` (y bent by FBm): 1.5 x a spline of its colours of
// 0.5 + 0.5 sin(marble).
PF_GPU_FN vec3 MarbleSpline(float marble) {
    float t = 0.5f + 0.5f * sin(marble);
    const int32_t segments = 6;  // 9 colours, 3 apart
    const int32_t cell = int32_t(floor(t * float(segments)));
    const int32_t first = cell < segments - 1 ? cell : segments - 1;
    t = t * float(segments) - float(first);
    const float s = 1.0f - t;
    return (MarbleColour(first) * (s * s * s) + MarbleColour(first + 1) * (3.0f * s * s * t) +
            MarbleColour(first + 2) * (3.0f * s * t * t) + MarbleColour(first + 3) * (t * t * t)) *
           1.5f;
}

// pbrt-v4's marble at p (already scaled): y + variation FBm(p) through MarbleSpline.
PF_GPU_FN vec3 MarbleColourAt(vec3 p, float footprint_sq, float omega, int32_t octaves,
                              float variation) {
    return MarbleSpline(p.y + variation * FractalNoise(p, footprint_sq, omega, octaves));
}

// The noise textures' value at texture-space point p: their octave sums through one call (the
// kernels inline every call): windy's two, the others' one.
PF_GPU_FN vec3 SolidNoise(uint32_t op, vec4 header, float variation, vec3 p, float footprint_sq) {
    const int32_t passes = op == kTextureWindy ? 2 : 1;
    vec2 sums = vec2(0.0f, 0.0f);
    for (int32_t pass = 0; pass < passes; ++pass) {
        float scale = 1.0f, omega = header.y;
        int32_t octaves = int32_t(floatBitsToUint(header.z));
        if (op == kTextureWindy) {
            scale = pass == 0 ? 0.1f : 1.0f, omega = 0.5f, octaves = pass == 0 ? 3 : 6;
        } else if (op == kTextureMarble) {
            scale = header.w;
        }
        const float sum = OctaveNoise(p * scale, footprint_sq * scale * scale, omega, octaves,
                                      op == kTextureWrinkled);
        if (pass == 0)
            sums.x = sum;
        else
            sums.y = sum;
    }
    if (op == kTextureWindy) return vec3(abs(sums.x) * sums.y);
    if (op == kTextureMarble) return MarbleSpline(p.y * header.w + variation * sums.x);
    return vec3(sums.x);
}

// The value of the program of `length` words at `at`. (The kernels inline every call: each
// call site holds a copy of all this, so their callers look textures up in one place.)
PF_GPU_FN vec3 EvaluateProceduralTexture(PF_TEXTURE_PROGRAM program, uint32_t length,
                                         TextureLookup at, PF_TEXTURE_IMAGES images) {
    vec3 stack[kTextureStackSize];
    int32_t top = 0;  // values on the stack
    uint32_t pc = 0;
    while (pc < length) {
        const vec4 header = PF_TEXTURE_WORD(program, pc);
        const uint32_t op = floatBitsToUint(header.x);
        if (op == kTextureConstant) {
            stack[top++] = vec3(header.y, header.z, header.w);
            pc += 1;
        } else if (op == kTextureImage) {
            const vec4 first = PF_TEXTURE_WORD(program, pc + 1);
            const vec4 second = PF_TEXTURE_WORD(program, pc + 2);
            stack[top++] = PF_TEXTURE_IMAGE(images, floatBitsToInt(header.y),
                                            TextureApplyUv(first, second, at.uv),
                                            at.uv_width * TextureUvScale(first, second));
            pc += 3;
        } else if (op == kTextureMultiply) {
            top -= 1;
            stack[top - 1] = stack[top - 1] * stack[top];
            pc += 1;
        } else if (op == kTextureMix) {
            top -= 2;
            const float amount = stack[top + 1].x;
            stack[top - 1] = stack[top - 1] * (1.0f - amount) + stack[top] * amount;
            pc += 1;
        } else if (op == kTextureDirectionMix) {
            top -= 1;
            const float amount = abs(dot(at.normal, vec3(header.y, header.z, header.w)));
            stack[top - 1] = stack[top - 1] * amount + stack[top] * (1.0f - amount);
            pc += 1;
        } else if (op == kTextureCheckerboard || op == kTextureDots) {
            const vec4 first = PF_TEXTURE_WORD(program, pc + 1);
            const vec4 second = PF_TEXTURE_WORD(program, pc + 2);
            const vec2 st = TextureApplyUv(first, second, at.uv);
            float w;  // the weight of b
            if (op == kTextureDots) {
                w = InsideDot(st) ? 0.0f : 1.0f;
            } else {
                // pbrt-v4 filters over 1.5 footprints each way (its dsdx, dtdx, ...).
                const float r = 1.5f * at.uv_width * TextureUvScale(first, second);
                w = 0.5f - 0.5f * CheckerAxis(st.x, r) * CheckerAxis(st.y, r);
            }
            top -= 1;
            stack[top - 1] = stack[top - 1] * (1.0f - w) + stack[top] * w;
            pc += 3;
        } else if (op == kTextureBilerp) {
            const vec4 first = PF_TEXTURE_WORD(program, pc + 1);
            const vec4 second = PF_TEXTURE_WORD(program, pc + 2);
            const vec2 st = TextureApplyUv(first, second, at.uv);
            const vec4 v00 = PF_TEXTURE_WORD(program, pc + 3);
            const vec4 v01 = PF_TEXTURE_WORD(program, pc + 4);
            const vec4 v10 = PF_TEXTURE_WORD(program, pc + 5);
            const vec4 v11 = PF_TEXTURE_WORD(program, pc + 6);
            stack[top++] = vec3(v00.x, v00.y, v00.z) * ((1.0f - st.x) * (1.0f - st.y)) +
                           vec3(v10.x, v10.y, v10.z) * (st.x * (1.0f - st.y)) +
                           vec3(v01.x, v01.y, v01.z) * ((1.0f - st.x) * st.y) +
                           vec3(v11.x, v11.y, v11.z) * (st.x * st.y);
            pc += 7;
        } else if (op == kTexturePower) {
            const vec3 c = stack[top - 1];
            stack[top - 1] = vec3(pow(max(c.x, 0.0f), header.y), pow(max(c.y, 0.0f), header.y),
                                  pow(max(c.z, 0.0f), header.y));
            pc += 1;
        } else if (op == kTextureClamp) {
            const vec3 c = stack[top - 1];
            stack[top - 1] = vec3(clamp(c.x, 0.0f, header.y), clamp(c.y, 0.0f, header.y),
                                  clamp(c.z, 0.0f, header.y));
            pc += 1;
        } else {  // the noise textures and the 3D checkerboard
            const uint32_t words = op == kTextureMarble ? 2u : 1u;
            const vec4 row0 = PF_TEXTURE_WORD(program, pc + words);
            const vec4 row1 = PF_TEXTURE_WORD(program, pc + words + 1);
            const vec4 row2 = PF_TEXTURE_WORD(program, pc + words + 2);
            const vec3 p = TextureApplyPoint(row0, row1, row2, at.position);
            const float footprint = at.width * TexturePointScale(row0, row1, row2);
            if (op == kTextureCheckerboard3D) {
                const float r = 1.5f * footprint;
                const float w =
                    0.5f - 0.5f * CheckerAxis(p.x, r) * CheckerAxis(p.y, r) * CheckerAxis(p.z, r);
                top -= 1;
                stack[top - 1] = stack[top - 1] * (1.0f - w) + stack[top] * w;
            } else {
                const float variation = PF_TEXTURE_WORD(program, pc + 1).x;  // marble's
                stack[top++] = SolidNoise(op, header, variation, p, footprint * footprint);
            }
            pc += words + 3;
        }
    }
    return stack[0];
}

PF_GPU_END

#endif  // PF_CORE_SHARED_PROCEDURAL_TEXTURE_H
