// penumbra/detail/technique.hpp — what a technique is to the rest of Penumbra: one self-describing
// value that each folder's detail/<technique>/technique.hpp provides and the registry
// (detail/techniques.hpp) returns for a Config's technique. Emission, the layout, validation, the
// files' headers and the cost model ask the descriptor; nothing outside the folder switches on
// the technique.
//
// A new technique: a folder with its emitters and a technique.hpp returning its descriptor, an
// enum value and parameter struct in config.hpp, and one case in detail/techniques.hpp.
#pragma once

#include "../config.hpp"
#include "../config_field.hpp"
#include "../program.hpp"
#include "problem.hpp"
#include "text.hpp"

#include <span>
#include <string_view>
#include <vector>

namespace penumbra {

struct PassDesc;

namespace detail {

struct Param;         // glsl_common.hpp
struct ParamGroup;    // layout_builder.hpp
struct LayoutBuilder; // layout_builder.hpp

// The vertex attributes a vertex stage reads (layout.json's "vertex_inputs", detail/vertex_inputs.hpp).
enum class VertexInputs : std::uint8_t {
    none,             // the full-screen triangle (gl_VertexID)
    caster,           // the casters drawn from the light: position (with the alpha test, material uv too)
    receiver,         // the receivers drawn by the camera: position and normal
    receiver_with_uv, // position, normal and the unique texture coordinates of a baked parameterization
};

// One file a technique emits: its name (unique within an emission; the extension tells glslang the
// stage), its stage, the attributes of a vertex stage, and the function writing its text for a
// valid configuration.
struct ShaderFileSpec {
    std::string_view name;
    Stage stage = Stage::fragment;
    Text (*text)(const Config&) = nullptr;
    VertexInputs vertex_inputs = VertexInputs::none;

    friend constexpr bool operator==(const ShaderFileSpec& a, const ShaderFileSpec& b) { return a.name == b.name; }
};

// penumbra_visibility.glsl: for inclusion into the engine's own shaders (no #version); WGSL's
// penumbra_visibility.wgsl (language.hpp, file_name).
inline constexpr std::string_view visibility_snippet_name = "penumbra_visibility.glsl";

// A program of a configuration: its name (as layout.json and the passes call it) and stage files.
struct ProgramPlan {
    std::string_view name;
    std::vector<ShaderFileSpec> stages;
};

// Everything Penumbra needs to know about one technique. Every function is set.
struct TechniqueDescriptor {
    // Its own fields of the configuration (penumbra/config_fields.hpp: JSON, flags, --help, panels,
    // schema); techniques that share a folder share its rows.
    std::span<const ConfigField> fields;

    // Emission: the programs in the order their passes run, and penumbra_visibility.glsl.
    std::vector<ProgramPlan> (*programs)(const Config&);
    Text (*visibility_snippet)(const Config&);

    // penumbraVisibility(), as every shading program declares it: its parameters, and its text with
    // the samplers bound from `next_binding` on (which it advances). With `reads_normal` it takes
    // the receiver's normal too, and the deferred pass reads the caller's penumbra_worldNormals.
    std::vector<Param> (*visibility_params)(const Config&);
    void (*write_visibility)(LineWriter&, const Config&, int& next_binding);
    bool (*reads_normal)(const Config&);

    // The layout: a program's declaration groups, and the technique's textures and passes.
    std::vector<ParamGroup> (*param_groups)(const Config&, std::string_view program);
    void (*describe_layout)(LayoutBuilder&, const Config&);

    // What is wrong with the technique's fields for the target (empty: valid).
    std::vector<Problem> (*problems)(const Config&);

    // The header of every emitted file: the configuration line (the fields the technique reads, its
    // light and target), the line after it (what the stored values mean), and the sampler types
    // besides sampler2D, sampler2DArray and sampler3D an ES stage declares highp.
    Text (*summary)(const Config&);
    Text (*storage_note)(const Config&);
    std::vector<std::string_view> (*es_sampler_precision)(const Config&);

    // The cost model (penumbra/cost_model.hpp): texels one fragment of `pass` reads.
    long long (*texels_per_fragment)(const Config&, const PassDesc& pass);

    // Whether its emitters write WGSL too (detail/language.hpp); validate() refuses target wgsl otherwise.
    bool writes_wgsl = false;
    // Whether its emitters write HLSL too (WGSL's passes in HLSL); validate() refuses target hlsl otherwise.
    bool writes_hlsl = false;

    // The section of another folder's rows marked `shared` that it reads too ("shadow_map": the depth
    // map's resolution and biases, for the techniques that build it as the shadow-map techniques do).
    // The rows' readers (--help, the schema, the panels) follow from it.
    std::string_view reads_shared_section = {};
};

// The descriptor of `technique`: detail/techniques.hpp. Precondition: a known value (validate()
// checks it first).
constexpr TechniqueDescriptor technique_descriptor(Technique technique);

} // namespace detail

// True when penumbraVisibility uses the receiver's normal (the tangent clip, the normal-offset bias or
// the receiver-plane depth bias): the deferred pass then reads the caller's penumbra_worldNormals.
constexpr bool reads_receiver_normal(const Config& config) {
    return detail::technique_descriptor(config.technique).reads_normal(config);
}

namespace detail {

// Cost model: G-buffer texels one fragment of the deferred pass reads (positions, and normals where
// penumbraVisibility takes them).
constexpr long long g_buffer_texels(const Config& config) { return reads_receiver_normal(config) ? 2 : 1; }

} // namespace detail
} // namespace penumbra
