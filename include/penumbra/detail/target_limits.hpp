// penumbra/detail/target_limits.hpp — what each shading target guarantees.
//
// Penumbra only emits what every conforming implementation of the target must accept, so the
// limits are the specifications' guaranteed minimums, not what a particular GPU offers.
#pragma once

#include "../config.hpp"

namespace penumbra::detail {

struct TargetLimits {
    int max_texture_size;       // GL_MAX_TEXTURE_SIZE / maxImageDimension2D
    int max_3d_texture_size;    // GL_MAX_3D_TEXTURE_SIZE / maxImageDimension3D
    int max_array_layers;       // GL_MAX_ARRAY_TEXTURE_LAYERS / maxImageArrayLayers
    int max_draw_buffers;       // GL_MAX_DRAW_BUFFERS / maxColorAttachments
    bool float32_render_filter; // 32-bit float textures are colour-renderable and filterable
    bool clamp_to_border;       // CLAMP_TO_BORDER with a transparent black border exists
    bool logic_op;              // logical operations on integer colour targets (glLogicOp / logicOp OR)
};

constexpr TargetLimits limits(Target target) {
    switch (target) {
    case Target::glsl330: return {1024, 256, 256, 8, true, true, true};   // OpenGL 3.3 core, table 6.54
    case Target::glsl450: return {16384, 2048, 2048, 8, true, true, true}; // OpenGL 4.5 core, table 23.53
    // OpenGL ES 3.0, table 6.28; ES 3.x and WebGL2 have no glLogicOp
    case Target::essl300: return {2048, 256, 256, 4, false, false, false};
    // Vulkan 1.0 required limits; logicOp is a device feature (every desktop driver and lavapipe have it)
    case Target::vulkan: return {4096, 256, 256, 4, true, true, true};
    // WebGPU's default limits; float32-filterable is an optional feature, and WebGPU has neither a
    // border colour nor logic operations. Eight colour attachments, but 32 bytes a sample across them
    // (maxColorAttachmentBytesPerSample) and RGBA8 counts 8: four RGBA8 targets a pass
    case Target::wgsl: return {8192, 2048, 256, 4, false, false, false};
    // Direct3D 12 at feature level 11_0 (D3D12_REQ_*) for the texture sizes. The passes are WGSL's
    // (one set of passes for the two languages that bind samplers apart): four render targets a pass,
    // 32-bit floats read texel by texel (Direct3D 12 could filter them) and no logic op (an optional
    // feature there)
    case Target::hlsl: return {16384, 2048, 2048, 4, false, true, false};
    // Metal: translated from the vulkan target's passes, which keep Vulkan's guaranteed limits
    case Target::msl: return limits(Target::vulkan);
    }
    return {};
}

} // namespace penumbra::detail
