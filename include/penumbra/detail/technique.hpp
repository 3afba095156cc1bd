// penumbra/detail/technique.hpp — what a technique is to the rest of Penumbra: one self-describing
// value each folder detail/<technique>/technique.hpp provides, and the registry
// (detail/techniques.hpp) returns for a Config's technique. Emission, the layout, validation, the
// file headers and the cost model ask the descriptor; nothing outside the folder switches on the
// technique.
#pragma once

#include "../program.hpp"
#include "layout_builder.hpp"
#include "problem.hpp"
#include "text.hpp"

#include <string_view>
#include <vector>

namespace penumbra {

struct PassDesc;

namespace detail {

// One file a technique emits: its name (unique within an emission; the extension names the stage
// for glslang), its stage, and the function that writes its text for a valid configuration.
struct ShaderFileSpec {
    std::string_view name;
    Stage stage = Stage::fragment;
    Text (*text)(const Config&) = nullptr;

    friend constexpr bool operator==(const ShaderFileSpec& a, const ShaderFileSpec& b) { return a.name == b.name; }
};

// A program of a configuration: its name (as layout.json and the passes call it) and stage files.
struct ProgramPlan {
    std::string_view name;
    std::vector<ShaderFileSpec> stages;
};

// Everything Penumbra needs to know about one technique. Every member is set (no null pointers).
struct TechniqueDescriptor {
    std::string_view folder; // detail/<folder>/: where its emitters live

    // Emission: programs in the order their passes run, and penumbra_visibility.glsl.
    std::vector<ProgramPlan> (*programs)(const Config&);
    Text (*visibility_snippet)(const Config&);

    // penumbraVisibility(): its parameters and its text, as every shading program declares them
    // (from binding `next_binding` on, which it advances).
    std::vector<Param> (*visibility_params)(const Config&);
    void (*write_visibility)(LineWriter&, const Config&, int& next_binding);

    // The layout: a program's declaration groups, and the technique's textures and passes.
    std::vector<ParamGroup> (*param_groups)(const Config&, std::string_view program);
    void (*describe_layout)(LayoutBuilder&, const Config&);

    // What is wrong with the technique's fields for the target (empty: valid).
    std::vector<Problem> (*problems)(const Config&);

    // The header of every emitted file: the configuration line (the fields the technique reads,
    // ending with its light and target), the line after it (what the stored values mean), and the
    // sampler types beyond sampler2D/sampler2DArray/sampler3D an ES fragment stage declares highp.
    Text (*summary)(const Config&);
    Text (*storage_note)(const Config&);
    std::vector<std::string_view> (*es_sampler_precision)(const Config&);

    // Cost model (penumbra/cost_model.hpp): texels one fragment of `pass` reads.
    long long (*texels_per_fragment)(const Config&, const PassDesc& pass);
};

} // namespace detail
} // namespace penumbra
