// targets/vulkan/runner_pipelines.cpp — the Runner's programs: SPIR-V from glslang, descriptor set layouts from the parameters' sets and bindings, uniform blocks at their std140 offsets (runner.hpp).
#include "runner.hpp"

namespace penumbra::vulkan::detail {

const json* Runner::parameter(const std::string& program, const std::string& name) const {
    for (const json& p : in_.layout.at("programs"))
        if (p.at("name") == program)
            for (const json& param : p.at("parameters"))
                if (param.at("name") == name) return &param;
    return nullptr;
}

Sampling Runner::input_sampling(const json& pass, const json& input) const {
    const std::string sampler = input.at("sampler"), tex = input.at("texture");
    const std::string what = "pass " + pass.at("name").get<std::string>() + ", sampler " + sampler;
    if (input.contains("sampling")) return parse_sampling(input.at("sampling"), what);
    if (const json* param = parameter(pass.value("program", ""), sampler); param && param->contains("sampling"))
        return parse_sampling(param->at("sampling"), what);
    for (const json& t : in_.layout.at("textures"))
        if (t.at("name") == tex) return parse_sampling(t, "texture " + tex);
    fail(what + ": texture '" + tex + "' is not listed in textures");
}

Program& Runner::program(const std::string& name) {
    if (auto it = programs_.find(name); it != programs_.end()) return it->second;
    const json* desc = nullptr;
    for (const json& p : in_.layout.at("programs"))
        if (p.at("name") == name) desc = &p;
    if (!desc) fail("program '" + name + "' is used by a pass but not listed in programs");
    penumbra::Program source{name, {}};
    // layout.json states each file's stage: stages[i] is the stage of files[i].
    const json& files = desc->at("files");
    const json& stages = desc->at("stages");
    if (stages.size() != files.size())
        fail("program " + name + ": " + std::to_string(files.size()) + " files but " + std::to_string(stages.size()) +
             " stages; layout.json lists one stage per file");
    for (std::size_t i = 0; i < files.size(); ++i) {
        const std::string file = files[i].get<std::string>();
        const std::optional<Stage> stage = stage_named(stages[i].get<std::string>());
        if (!stage)
            fail("program " + name + ": stage '" + stages[i].get<std::string>() + "' of '" + file +
                 "'; allowed: vertex, fragment, compute");
        source.stages.push_back({file, *stage, read_text(in_.emission_dir / file)});
    }
    std::vector<std::vector<unsigned int>> spirv;
    const std::vector<ShaderDiagnostic> diagnostics = validate_program(source, target_, &spirv);
    if (has_errors(diagnostics)) fail("program " + name + ": " + format(diagnostics.front()));
    Program prog;
    for (std::size_t i = 0; i < source.stages.size(); ++i) {
        VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        info.codeSize = spirv.at(i).size() * sizeof(unsigned int);
        info.pCode = spirv[i].data();
        VkShaderModule module = VK_NULL_HANDLE;
        check(vkCreateShaderModule(device_, &info, nullptr, &module), "program " + name + ": vkCreateShaderModule");
        on_cleanup([this, module] { vkDestroyShaderModule(device_, module, nullptr); });
        VkPipelineShaderStageCreateInfo stage{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        stage.stage = vk_stage(source.stages[i].stage);
        stage.module = module;
        stage.pName = "main";
        prog.stages.push_back(stage);
    }
    // Descriptor sets from the parameters' "set" (layout_version 3; set 0 when absent).
    prog.desc = desc;
    std::map<int, std::vector<VkDescriptorSetLayoutBinding>> bindings; // by set
    for (const json& p : desc->at("parameters")) {
        const std::string type = p.at("type");
        const int set = p.value("set", 0);
        if (p.contains("block_binding")) {
            Block& block = prog.blocks[{set, p.at("block_binding").get<int>()}];
            block.size = std::max(block.size, p.at("offset").get<int>() + std140_size(type));
            block.members.push_back(p);
        } else if (type.find("sampler") != std::string::npos && p.contains("binding")) { // usampler2D too
            const SetBinding where{set, p.at("binding").get<int>()};
            if (prog.samplers.count(where))
                fail("program " + name + ": parameters " + prog.samplers[where].at("name").get<std::string>() + " and " +
                     p.at("name").get<std::string>() + " share set " + std::to_string(set) + " binding " +
                     std::to_string(where.second));
            prog.samplers[where] = p;
        } else {
            fail("program " + name + ": parameter " + p.at("name").get<std::string>() +
                 " has neither a uniform block nor a binding");
        }
    }
    for (auto& [where, block] : prog.blocks) {
        block.size = (block.size + 15) / 16 * 16; // std140 rounds a block up to a vec4
        if (prog.samplers.count(where))
            fail("program " + name + ": a uniform block and a sampler share set " + std::to_string(where.first) +
                 " binding " + std::to_string(where.second));
        bindings[where.first].push_back({static_cast<std::uint32_t>(where.second), VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
                                         VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
    }
    for (const auto& [where, param] : prog.samplers) {
        const int separate = param.value("sampler_binding", -2); // -2: combined; -1: a texture alone
        bindings[where.first].push_back({static_cast<std::uint32_t>(where.second),
                                         separate == -2 ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                                                        : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE,
                                         1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                         nullptr});
        if (separate >= 0)
            bindings[where.first].push_back(
                {static_cast<std::uint32_t>(separate), VK_DESCRIPTOR_TYPE_SAMPLER, 1,
                 VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
    }
    const int set_count = bindings.empty() ? 0 : bindings.rbegin()->first + 1;
    if (set_count > static_cast<int>(c_.properties().limits.maxBoundDescriptorSets))
        fail("program " + name + ": descriptor set " + std::to_string(set_count - 1) + "; the device binds " +
             std::to_string(c_.properties().limits.maxBoundDescriptorSets) + " sets");
    for (int set = 0; set < set_count; ++set) { // sets without parameters get empty layouts
        const std::vector<VkDescriptorSetLayoutBinding>& b = bindings[set];
        VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        set_info.bindingCount = static_cast<std::uint32_t>(b.size());
        set_info.pBindings = b.data();
        VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
        check(vkCreateDescriptorSetLayout(device_, &set_info, nullptr, &set_layout),
              "program " + name + ": descriptor set layout " + std::to_string(set));
        on_cleanup([this, set_layout] { vkDestroyDescriptorSetLayout(device_, set_layout, nullptr); });
        prog.set_layouts.push_back(set_layout);
    }
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = static_cast<std::uint32_t>(prog.set_layouts.size());
    layout_info.pSetLayouts = prog.set_layouts.data();
    check(vkCreatePipelineLayout(device_, &layout_info, nullptr, &prog.pipeline_layout), "program " + name + ": pipeline layout");
    VkPipelineLayout pipeline_layout = prog.pipeline_layout;
    on_cleanup([this, pipeline_layout] { vkDestroyPipelineLayout(device_, pipeline_layout, nullptr); });

    // Vertex inputs by name (layout_version 3); version 2: world position at location 0.
    if (!desc->contains("vertex_inputs")) {
        prog.vertex_inputs.position = 0;
    } else {
        for (const json& v : desc->at("vertex_inputs")) {
            const std::string input = v.at("name"), type = v.at("type");
            const int location = v.at("location").get<int>();
            int* slot = input == "penumbra_position" ? &prog.vertex_inputs.position
                        : input == "penumbra_normal" ? &prog.vertex_inputs.normal
                                                     : nullptr;
            if (!slot)
                fail("program " + name + ": vertex input '" + input +
                     "' is unknown to this runner; allowed: penumbra_position, penumbra_normal");
            if (type != "vec3")
                fail("program " + name + ": vertex input " + input + " is a " + type + "; allowed: vec3");
            if (location < 0 || location >= static_cast<int>(c_.properties().limits.maxVertexInputAttributes))
                fail("program " + name + ": vertex input " + input + " at location " + std::to_string(location) +
                     "; the device has locations 0 to " +
                     std::to_string(c_.properties().limits.maxVertexInputAttributes - 1));
            if (*slot >= 0) fail("program " + name + ": vertex input " + input + " is listed twice");
            *slot = location;
        }
        if (prog.vertex_inputs.position >= 0 && prog.vertex_inputs.position == prog.vertex_inputs.normal)
            fail("program " + name + ": penumbra_position and penumbra_normal share location " +
                 std::to_string(prog.vertex_inputs.position));
    }
    return programs_[name] = std::move(prog);
}

void Runner::create_descriptor_pool(std::size_t passes) {
    const auto sets = static_cast<std::uint32_t>(std::max<std::size_t>(passes, 1)) * RequiredLimits::bound_descriptor_sets;
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 12 * sets},
                                          {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16 * sets},
                                          {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 16 * sets},
                                          {VK_DESCRIPTOR_TYPE_SAMPLER, 16 * sets}};
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.maxSets = sets;
    info.poolSizeCount = 4;
    info.pPoolSizes = sizes;
    check(vkCreateDescriptorPool(device_, &info, nullptr, &pool_), "vkCreateDescriptorPool");
    on_cleanup([this] { vkDestroyDescriptorPool(device_, pool_, nullptr); });
}

void Runner::write_member(const json& param, const json& pass, unsigned char* block) {
    const std::string name = param.at("name"), type = param.at("type"), source = param.value("source", "");
    const int offset = param.at("offset").get<int>();
    if (source == "pass") {
        if (!pass.at("int_uniforms").contains(name))
            fail("pass " + pass.at("name").get<std::string>() + ": no value for " + name + " in int_uniforms");
        const std::int32_t value = pass.at("int_uniforms").at(name).get<std::int32_t>();
        std::memcpy(block + offset, &value, sizeof value);
        return;
    }
    if (source != "light")
        fail("pass " + pass.at("name").get<std::string>() + ": parameter " + name + " has source '" + source +
             "'; this runner provides 'light' and 'pass' values");
    auto it = in_.uniforms.find(name);
    if (it == in_.uniforms.end()) fail("no value for the light parameter " + name + " (uniforms.json)");
    const std::size_t floats = static_cast<std::size_t>(std140_size(type)) / 4;
    if (it->second.size() != floats)
        fail(name + ": " + std::to_string(it->second.size()) + " values for a " + type);
    std::memcpy(block + offset, it->second.data(), floats * sizeof(float));
}

VkPipeline Runner::pipeline(const std::string& program_name, Program& prog, const json& pass, const std::vector<VkFormat>& formats, VkFormat depth_format) {
    const json& state = pass.at("state");
    const std::string pass_name = pass.at("name");
    std::string key = program_name + "|" + pass.at("action").get<std::string>() + "|" + state.dump() + "|" +
                      std::to_string(depth_format);
    for (VkFormat f : formats) key.append("|").append(std::to_string(f));
    if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;
    const bool depth_test = state.at("depth_test").get<bool>(), depth_write = state.at("depth_write").get<bool>();
    if ((depth_test || depth_write) && depth_format == VK_FORMAT_UNDEFINED)
        fail("pass " + pass_name + ": depth_test or depth_write without an output of kind \"depth\" (this runner has no "
             "default framebuffer)");

    // draw_scene: the vertex buffer holds position and face normal (fill_vertices); each is fed
    // to the location the program's vertex_inputs name.
    const bool scene = word<PassAction>(pass, "action", "pass " + pass_name) == PassAction::draw_scene;
    if (!scene && (prog.vertex_inputs.position >= 0 || prog.vertex_inputs.normal >= 0) && prog.desc->contains("vertex_inputs"))
        fail("pass " + pass_name + ": program " + program_name + " has vertex inputs, but a fullscreen pass draws no vertices");
    if (scene && prog.vertex_inputs.position < 0)
        fail("pass " + pass_name + ": program " + program_name + " draws the scene but reads no penumbra_position");
    const VkVertexInputBindingDescription vertex_binding{0, 6 * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX};
    std::vector<VkVertexInputAttributeDescription> attributes;
    if (prog.vertex_inputs.position >= 0)
        attributes.push_back({static_cast<std::uint32_t>(prog.vertex_inputs.position), 0, VK_FORMAT_R32G32B32_SFLOAT, 0});
    if (prog.vertex_inputs.normal >= 0)
        attributes.push_back({static_cast<std::uint32_t>(prog.vertex_inputs.normal), 0, VK_FORMAT_R32G32B32_SFLOAT,
                              3 * sizeof(float)});
    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    if (scene) {
        vertex_input.vertexBindingDescriptionCount = 1;
        vertex_input.pVertexBindingDescriptions = &vertex_binding;
        vertex_input.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(attributes.size());
        vertex_input.pVertexAttributeDescriptions = attributes.data();
    }
    // Depth: GL's test, function and mask; polygon offset as depth bias (both APIs scale
    // `units` by the format's minimum resolvable difference).
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = depth_test ? VK_TRUE : VK_FALSE;
    depth.depthWriteEnable = depth_test && depth_write ? VK_TRUE : VK_FALSE; // GL writes depth only where it tests
    const std::string where = "pass " + pass_name + ": state";
    depth.depthCompareOp = compare_op(word<CompareFunc>(state, "depth_func", where, "LESS"));
    depth.minDepthBounds = 0.0f;
    depth.maxDepthBounds = 1.0f;
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = cull_mode(word<Cull>(state, "cull", where));
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    const float offset_factor = state.value("polygon_offset_factor", 0.0f), offset_units = state.value("polygon_offset_units", 0.0f);
    if (offset_factor != 0.0f || offset_units != 0.0f) {
        if (depth_format == VK_FORMAT_UNDEFINED)
            fail("pass " + pass_name + ": polygon offset without an output of kind \"depth\"");
        raster.depthBiasEnable = VK_TRUE;
        raster.depthBiasConstantFactor = offset_units;
        raster.depthBiasSlopeFactor = offset_factor;
    }
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    const LogicOp logic_op = word<LogicOp>(state, "logic_op", where, "NONE");
    if (logic_op == LogicOp::bitwise_or && !c_.logic_op())
        fail("pass state: logic_op OR needs the device feature logicOp, which this device lacks");
    VkPipelineColorBlendAttachmentState blend{};
    blend.blendEnable = state.at("blend").get<bool>() ? VK_TRUE : VK_FALSE;
    blend.colorBlendOp = blend.alphaBlendOp = blend_op(word<BlendEquation>(state, "blend_equation", where));
    blend.srcColorBlendFactor = blend.srcAlphaBlendFactor = blend_factor(word<BlendFactor>(state, "blend_src", where));
    blend.dstColorBlendFactor = blend.dstAlphaBlendFactor = blend_factor(word<BlendFactor>(state, "blend_dst", where));
    const std::vector<bool> mask = state.at("color_mask").get<std::vector<bool>>();
    for (std::size_t i = 0; i < 4 && i < mask.size(); ++i)
        if (mask[i]) blend.colorWriteMask |= VK_COLOR_COMPONENT_R_BIT << i;
    const std::vector<VkPipelineColorBlendAttachmentState> blends(formats.size(), blend);
    VkPipelineColorBlendStateCreateInfo blending{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blending.logicOpEnable = logic_op == LogicOp::bitwise_or ? VK_TRUE : VK_FALSE; // integer targets: fragments OR-ed in
    blending.logicOp = VK_LOGIC_OP_OR;
    blending.attachmentCount = static_cast<std::uint32_t>(blends.size());
    blending.pAttachments = blends.data();
    const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamic_states;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<std::uint32_t>(formats.size());
    rendering.pColorAttachmentFormats = formats.data();
    rendering.depthAttachmentFormat = depth_format;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount = static_cast<std::uint32_t>(prog.stages.size());
    info.pStages = prog.stages.data();
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pColorBlendState = &blending;
    if (depth_format != VK_FORMAT_UNDEFINED) info.pDepthStencilState = &depth;
    info.pDynamicState = &dynamic;
    info.layout = prog.pipeline_layout;
    VkPipeline p = VK_NULL_HANDLE;
    check(vkCreateGraphicsPipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &p),
          "pass " + pass.at("name").get<std::string>() + ": vkCreateGraphicsPipelines");
    on_cleanup([this, p] { vkDestroyPipeline(device_, p, nullptr); });
    return pipelines_[key] = p;
}

} // namespace penumbra::vulkan::detail
