// A module Tint must accept (the test `wgsl_compile`): a uniform block, a depth texture and a comparison sampler, as the emitted deferred passes use them.
struct PenumbraVisibility { lightFromWorld: mat4x4f, size: vec2f }
@group(0) @binding(0) var<uniform> u: PenumbraVisibility;
@group(0) @binding(1) var shadowMap: texture_depth_2d;
@group(0) @binding(2) var shadowSampler: sampler_comparison;
@fragment
fn main(@location(0) p: vec3f) -> @location(0) vec4f {
    let q = u.lightFromWorld * vec4f(p, 1.0);
    let v = textureSampleCompareLevel(shadowMap, shadowSampler, q.xy, q.z);
    return vec4f(v, 0.0, 0.0, 1.0);
}
