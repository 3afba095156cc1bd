// A module Tint must reject (the test `wgsl_compile` expects the error at 6:21): `y` is undeclared.
@vertex
fn main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
    let x = f32(index) - 1.0;
    // the next line uses a name that does not exist
    return vec4f(x, y, 0.0, 1.0);
}
