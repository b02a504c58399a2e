#pragma once
// What the GPU can hold, asked before the first allocation: a render size over the limits gets one
// line naming the size and the limit, not the driver's GL errors.
#include <cstddef>
#include <cstdint>
#include <string>

namespace lp::gl {

struct RenderTargetLimits {
    int maxTextureSize = 0;      // GL_MAX_TEXTURE_SIZE
    int maxViewport[2] = {0, 0};  // GL_MAX_VIEWPORT_DIMS
    int maxFramebuffer[2] = {0, 0};  // GL_MAX_FRAMEBUFFER_WIDTH / _HEIGHT
    int64_t freeBytes = -1;       // free GPU memory where the driver says (NVX/ATI meminfo, or system memory
                                  // for a software rasteriser); -1: unknown
};

// Needs a current context. LIGHTPASS_GPU_FREE_BYTES=N in the environment overrides freeBytes.
RenderTargetLimits queryRenderTargetLimits(bool softwareRasteriser);

// GL_MAX_SHADER_STORAGE_BLOCK_SIZE: the most bytes one storage block of a shader reads. 0 without a
// current context.
uint64_t maxShaderStorageBlockBytes();

// Whether the driver can allocate one width x height texture of internalFormat (a proxy texture: no
// allocation, no GL error). Catches per-texture limits within GL_MAX_TEXTURE_SIZE, such as llvmpipe
// refusing a 16384x16384 RGBA32F texture (4 GiB). Needs a current context.
bool canAllocateTexture(unsigned internalFormat, int width, int height);

// How far an image must be halved before the driver takes it as one texture of internalFormat:
// `halvings` 0 when it fits as it is; otherwise `reason` says which limit it is over
// ("larger than this GPU's 16384 texel limit (GL_MAX_TEXTURE_SIZE)", or the per-texture memory).
struct TextureFit {
    int halvings = 0;
    std::string reason;
};
TextureFit fitTexture(unsigned internalFormat, int width, int height);

// Throws lp::Error "--size WxH: ..." when width x height exceeds a dimension limit, or when
// `renderTargetBytes` (the frame's render targets) exceeds the known free memory.
void requireRenderSizeFits(int width, int height, size_t renderTargetBytes, const RenderTargetLimits& limits);

}  // namespace lp::gl
