// targets/vulkan/runner_passes.cpp — the Runner's passes: the phases in order, each pass recorded (draws, full-screen passes, copies, mipmap blits) with a full barrier between commands (runner.hpp).
#include "runner.hpp"

namespace penumbra::vulkan::detail {

void Runner::run(LayoutOutput& out) {
    const json& layout = in_.layout;
    const int version = layout.value("layout_version", 1);
    if (version < 2 || version > 3)
        fail("layout.json has layout_version " + std::to_string(version) +
             "; this runner follows versions 2 (structured render state, pass phases, texture sizes and sources) "
             "and 3 (per-binding sampling, vertex inputs, descriptor sets, initial contents, copy and mipmap details)");
    // The vulkan target's GLSL, or the hlsl target's HLSL (compiled by glslang's HLSL front end,
    // each texture and its sampler bound apart as layout.json's sampler_binding says).
    target_ =
        parse_enum<Target>(layout.at("config").at("target").get<std::string>()).value_or(Target::glsl450);
    if (target_ != Target::vulkan && target_ != Target::hlsl)
        fail("layout.json is for target '" + layout.at("config").at("target").get<std::string>() +
             "'; this runner needs the vulkan or hlsl target's");
    check_required_limits(layout);
    std::vector<const json*> passes;
    for (const Phase phase : {Phase::shadow, Phase::screen})
        for (const json& pass : layout.at("passes"))
            if (word<Phase>(pass, "phase", "pass " + pass.value("name", std::string())) == phase) passes.push_back(&pass);
    for (const json& t : layout.at("textures")) create_texture(t, passes);
    vertices_ = create_buffer(std::max<std::size_t>(2 * in_.triangles.size() * sizeof(float), 16),
                              VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    fill_vertices(static_cast<float*>(vertices_.mapped));
    create_descriptor_pool(passes.size());
    const Texture& result = texture(layout.at("result").get<std::string>());
    if (result.format.depth || result.format.integer || (result.format.bytes_per_channel == 2))
        fail("result texture " + result.name + ": reading back " + result.desc->at("internal_format").get<std::string>() +
             " is not supported by this runner; allowed: 8-bit unorm or 32-bit float formats");
    const std::size_t result_bytes = static_cast<std::size_t>(result.width) * result.height *
                                     result.format.channels * result.format.bytes_per_channel;
    const Buffer readback = create_buffer(result_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    std::vector<std::function<void(VkCommandBuffer)>> commands;
    // Build every pipeline and descriptor set before recording: failures surface as messages here.
    for (const json* pass : passes) {
        commands.push_back(prepare_pass(*pass));
        out.passes.push_back(pass->at("name").get<std::string>());
    }
    std::vector<Buffer> uploads = stage_caller_textures();
    const std::string error = c_.submit([&](VkCommandBuffer cmd) {
        initialise_images(cmd, uploads);
        for (auto& record : commands) {
            record(cmd);
            barrier(cmd);
        }
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {result.width, result.height, 1};
        const VkImageSubresourceRange level0{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        transition(cmd, result.image, level0, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        vkCmdCopyImageToBuffer(cmd, result.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1, &region);
    });
    if (!error.empty()) fail(error);
    out.result = to_floats(result, readback.mapped);
}

void Runner::fill_vertices(float* out) const {
    const std::vector<float>& t = in_.triangles;
    for (std::size_t tri = 0; tri + 9 <= t.size(); tri += 9) {
        const float e1[3] = {t[tri + 3] - t[tri], t[tri + 4] - t[tri + 1], t[tri + 5] - t[tri + 2]};
        const float e2[3] = {t[tri + 6] - t[tri], t[tri + 7] - t[tri + 1], t[tri + 8] - t[tri + 2]};
        float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (float& c : n) c = length > 0 ? c / length : 0.0f;
        for (int v = 0; v < 3; ++v) {
            float* vertex = out + 2 * (tri + 3 * v);
            std::memcpy(vertex, &t[tri + 3 * v], 3 * sizeof(float));
            std::memcpy(vertex + 3, n, 3 * sizeof(float));
        }
    }
}

std::function<void(VkCommandBuffer)> Runner::prepare_pass(const json& pass) {
    const std::string name = pass.at("name");
    const PassAction action = word<PassAction>(pass, "action", "pass " + name);
    switch (action) {
    case PassAction::generate_mipmap: return prepare_mipmaps(pass);
    case PassAction::copy: return prepare_copy(pass);
    case PassAction::dispatch:
        fail("pass " + name + ": action 'dispatch' runs a compute shader, which this runner has no pipelines for; "
             "emit with prefilter_stage fragment");
    case PassAction::draw_scene:
    case PassAction::fullscreen: break;
    }

    Program& prog = program(pass.at("program"));
    const std::string program_name = pass.at("program");
    // A 0 x 0 viewport: the size of the first output's level (as the GL runtime), else the output size.
    std::uint32_t width = pass.at("viewport").at(0).get<std::uint32_t>();
    std::uint32_t height = pass.at("viewport").at(1).get<std::uint32_t>();
    if (width == 0 || height == 0) {
        width = static_cast<std::uint32_t>(in_.width);
        height = static_cast<std::uint32_t>(in_.height);
        if (!pass.at("outputs").empty()) {
            const json& o = pass.at("outputs").at(0);
            const Texture& t = texture(o.at("texture"));
            const int level = std::clamp(o.at("level").get<int>(), 0, 31);
            width = std::max(t.width >> level, 1u);
            height = std::max(t.height >> level, 1u);
        }
    }
    // Rendering beyond an attachment is undefined in Vulkan (GL clips it): refused.
    for (const json& o : pass.at("outputs")) {
        const Texture& t = texture(o.at("texture"));
        const int level = std::clamp(o.at("level").get<int>(), 0, 31);
        if (width > std::max(t.width >> level, 1u) || height > std::max(t.height >> level, 1u))
            fail("pass " + name + ": viewport " + std::to_string(width) + "x" + std::to_string(height) +
                 " is larger than level " + std::to_string(level) + " of output " + t.name + " (" +
                 std::to_string(std::max(t.width >> level, 1u)) + "x" + std::to_string(std::max(t.height >> level, 1u)) + ")");
    }
    std::vector<VkRenderingAttachmentInfo> attachments;
    std::vector<VkFormat> formats;
    const json& state = pass.at("state");
    VkClearValue clear{};
    const bool clears = !state.at("clear_color").is_null();
    if (clears)
        for (int i = 0; i < 4; ++i) clear.color.float32[i] = state.at("clear_color").at(i).get<float>();
    std::size_t colour_outputs = 0;
    auto kind_of = [&](const json& o) { return word<AttachmentKind>(o, "kind", "pass " + name, "color"); };
    for (const json& o : pass.at("outputs")) colour_outputs += kind_of(o) == AttachmentKind::color;
    if (colour_outputs > c_.properties().limits.maxColorAttachments)
        fail("pass " + name + ": " + std::to_string(colour_outputs) + " colour attachments; the device has " +
             std::to_string(c_.properties().limits.maxColorAttachments));
    std::optional<VkRenderingAttachmentInfo> depth_attachment;
    VkFormat depth_format = VK_FORMAT_UNDEFINED;
    for (const json& o : pass.at("outputs")) {
        const Texture& t = texture(o.at("texture"));
        VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageView = attachment_view(t, o.at("level").get<int>(), o.at("layer").get<int>());
        a.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
        a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        if (kind_of(o) == AttachmentKind::depth) { // create_texture checked the kinds and formats
            if (depth_attachment) fail("pass " + name + ": more than one output of kind \"depth\"");
            const bool clears_depth = state.contains("clear_depth") && !state.at("clear_depth").is_null();
            a.loadOp = clears_depth ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
            if (clears_depth) {
                const float d = state.at("clear_depth").get<float>();
                if (!(d >= 0.0f && d <= 1.0f))
                    fail("pass " + name + ": clear_depth " + std::to_string(d) + "; allowed: 0 to 1");
                a.clearValue.depthStencil = {d, 0};
            }
            depth_attachment = a;
            depth_format = t.format.format;
            continue;
        }
        a.loadOp = clears ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        a.clearValue = clear;
        if (clears && t.format.integer) // integer targets clear to integer values (GL's glClearBufferuiv)
            for (int i = 0; i < 4; ++i) {
                const float v = state.at("clear_color").at(i).get<float>();
                if (!(v >= 0.0f) || v != std::floor(v))
                    fail("pass " + name + ": clear_color " + std::to_string(v) + " for the integer texture " + t.name +
                         "; allowed: whole numbers >= 0");
                a.clearValue.color.uint32[i] = static_cast<std::uint32_t>(v);
            }
        attachments.push_back(a);
        formats.push_back(t.format.format);
    }
    const VkPipeline pipe = pipeline(program_name, prog, pass, formats, depth_format);

    // Descriptor sets (one per set the program uses): one uniform buffer per block, filled
    // now, and the pass's inputs, each through the sampler its sampling describes.
    std::vector<VkDescriptorSet> sets;
    for (const VkDescriptorSetLayout set_layout : prog.set_layouts) {
        VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        allocate.descriptorPool = pool_;
        allocate.descriptorSetCount = 1;
        allocate.pSetLayouts = &set_layout;
        VkDescriptorSet set = VK_NULL_HANDLE;
        check(vkAllocateDescriptorSets(device_, &allocate, &set), "pass " + name + ": vkAllocateDescriptorSets");
        sets.push_back(set);
    }
    std::vector<VkDescriptorBufferInfo> buffer_infos;
    std::vector<VkDescriptorImageInfo> image_infos;
    buffer_infos.reserve(prog.blocks.size());
    image_infos.reserve(prog.samplers.size());
    std::vector<VkWriteDescriptorSet> writes;
    for (const auto& [where, block] : prog.blocks) {
        const Buffer b = create_buffer(static_cast<std::size_t>(block.size), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        for (const json& member : block.members) write_member(member, pass, static_cast<unsigned char*>(b.mapped));
        buffer_infos.push_back({b.buffer, 0, static_cast<VkDeviceSize>(block.size)});
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = sets.at(static_cast<std::size_t>(where.first));
        w.dstBinding = static_cast<std::uint32_t>(where.second);
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        w.pBufferInfo = &buffer_infos.back();
        writes.push_back(w);
    }
    for (const auto& [where, param] : prog.samplers) {
        const std::string sampler_name = param.at("name");
        const json* input = nullptr;
        for (const json& i : pass.at("inputs"))
            if (i.at("sampler") == sampler_name) input = &i;
        if (!input)
            fail("pass " + name + ": no input for sampler " + sampler_name + " (set " + std::to_string(where.first) +
                 ", binding " + std::to_string(where.second) + ")");
        if (input->at("binding").get<int>() != where.second)
            fail("pass " + name + ": input " + sampler_name + " is at binding " +
                 std::to_string(input->at("binding").get<int>()) + ", the program has it at binding " +
                 std::to_string(where.second));
        const Texture& t = texture(input->at("texture"));
        const std::string what = "pass " + name + ", sampler " + sampler_name;
        const std::string type = param.at("type");
        if (t.format.integer != type.starts_with("usampler"))
            fail(what + ": texture " + t.name + " (" + t.desc->at("internal_format").get<std::string>() + ") is read through a " +
                 type + "; integer textures need a usampler, others a sampler");
        if (t.format.depth && type.find("Shadow") == std::string::npos && type != "sampler2D")
            fail(what + ": the depth texture " + t.name + " is read through a " + type + "; allowed: sampler2D, sampler2DShadow");
        const VkSampler handle = sampler(input_sampling(pass, *input), type, what);
        image_infos.push_back({handle, sampled_view(t, input->value("level", -1)), VK_IMAGE_LAYOUT_GENERAL});
        const int separate = param.value("sampler_binding", -2); // as in program()
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = sets.at(static_cast<std::size_t>(where.first));
        w.dstBinding = static_cast<std::uint32_t>(where.second);
        w.descriptorCount = 1;
        w.descriptorType =
            separate == -2 ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        w.pImageInfo = &image_infos.back();
        writes.push_back(w);
        if (separate >= 0) {
            w.dstBinding = static_cast<std::uint32_t>(separate);
            w.descriptorType = VK_DESCRIPTOR_TYPE_SAMPLER;
            writes.push_back(w);
        }
    }
    vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);

    const bool scene = action == PassAction::draw_scene;
    const auto vertex_count = static_cast<std::uint32_t>(in_.triangles.size() / 3);
    const VkPipelineLayout pipeline_layout = prog.pipeline_layout;
    const VkBuffer vertices = vertices_.buffer;
    return [=](VkCommandBuffer cmd) {
        VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
        rendering.renderArea = {{0, 0}, {width, height}};
        rendering.layerCount = 1;
        rendering.colorAttachmentCount = static_cast<std::uint32_t>(attachments.size());
        rendering.pColorAttachments = attachments.data();
        if (depth_attachment) rendering.pDepthAttachment = &*depth_attachment;
        vkCmdBeginRendering(cmd, &rendering);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        const VkViewport vp{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height), 0.0f, 1.0f};
        const VkRect2D scissor{{0, 0}, {width, height}};
        vkCmdSetViewport(cmd, 0, 1, &vp);
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        if (!sets.empty())
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout, 0,
                                    static_cast<std::uint32_t>(sets.size()), sets.data(), 0, nullptr);
        if (scene) {
            const VkDeviceSize offset = 0;
            vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
            if (vertex_count > 0) vkCmdDraw(cmd, vertex_count, 1, 0, 0);
        } else {
            vkCmdDraw(cmd, 3, 1, 0, 0);
        }
        vkCmdEndRendering(cmd);
    };
}

std::function<void(VkCommandBuffer)> Runner::prepare_mipmaps(const json& pass) {
    const std::string name = pass.at("name");
    if (pass.at("outputs").size() != 1) fail("pass " + name + ": generate_mipmap needs exactly one output");
    const Texture& t = texture(pass.at("outputs").at(0).at("texture"));
    int base = 0, levels = static_cast<int>(t.levels);
    if (pass.contains("mipmap")) {
        const json& m = pass.at("mipmap");
        base = m.at("base_level").get<int>();
        levels = m.at("levels").get<int>();
        const std::string downsample = m.value("downsample", std::string("box"));
        if (downsample != "box") fail("pass " + name + ": downsample '" + downsample + "' is unknown; allowed: box");
    }
    if (base < 0 || levels < 1 || base + levels > static_cast<int>(t.levels))
        fail("pass " + name + ": mipmap levels " + std::to_string(base) + " to " + std::to_string(base + levels - 1) +
             " of texture " + t.name + ", which has levels 0 to " + std::to_string(t.levels - 1));
    const auto first = static_cast<std::uint32_t>(base), last = static_cast<std::uint32_t>(base + levels - 1);
    return [this, t, first, last](VkCommandBuffer cmd) {
        for (std::uint32_t level = first + 1; level <= last; ++level) {
            auto size = [&](std::uint32_t l, std::uint32_t extent) {
                return static_cast<std::int32_t>(std::max(extent >> l, 1u));
            };
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, t.layers()};
            blit.srcOffsets[1] = {size(level - 1, t.width), size(level - 1, t.height), size(level - 1, t.extent_depth())};
            blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, t.layers()};
            blit.dstOffsets[1] = {size(level, t.width), size(level, t.height), size(level, t.extent_depth())};
            const VkImageSubresourceRange src{VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 1, 0, t.layers()};
            const VkImageSubresourceRange dst{VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, t.layers()};
            transition(cmd, t.image, src, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            transition(cmd, t.image, dst, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            vkCmdBlitImage(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, t.image,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
            transition(cmd, t.image, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
            transition(cmd, t.image, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
        }
    };
}

std::function<void(VkCommandBuffer)> Runner::prepare_copy(const json& pass) {
    const std::string name = pass.at("name");
    if (pass.at("inputs").size() != 1 || pass.at("outputs").size() != 1)
        fail("pass " + name + ": copy needs exactly one input and one output");
    const Texture& src = texture(pass.at("inputs").at(0).at("texture"));
    const json& o = pass.at("outputs").at(0);
    const Texture& dst = texture(o.at("texture"));
    int src_level = std::max(pass.at("inputs").at(0).value("level", -1), 0), src_layer = 0;
    int dst_level = o.at("level").get<int>(), dst_layer = o.at("layer").get<int>();
    int width = pass.at("viewport").at(0).get<int>(), height = pass.at("viewport").at(1).get<int>();
    if (pass.contains("copy")) {
        const json& c = pass.at("copy");
        src_level = c.at("source_level").get<int>();
        src_layer = c.at("source_layer").get<int>();
        dst_level = c.at("target_level").get<int>();
        dst_layer = c.at("target_layer").get<int>();
        width = c.at("width").get<int>();
        height = c.at("height").get<int>();
    }
    src_layer = std::max(src_layer, 0);
    dst_layer = std::max(dst_layer, 0);
    if (width == 0 || height == 0) {
        width = in_.width;
        height = in_.height;
    }
    auto check_region = [&](const Texture& t, int level, int layer, const std::string& role) {
        if (level < 0 || level >= static_cast<int>(t.levels) || layer >= static_cast<int>(std::max(t.layers(), t.extent_depth())))
            fail("pass " + name + ": copy " + role + " level " + std::to_string(level) + " layer " + std::to_string(layer) +
                 " of texture " + t.name + ", which has " + std::to_string(t.levels) + " levels and " +
                 std::to_string(std::max(t.layers(), t.extent_depth())) + " layers");
        if (width < 1 || height < 1 || static_cast<std::uint32_t>(width) > std::max(t.width >> level, 1u) ||
            static_cast<std::uint32_t>(height) > std::max(t.height >> level, 1u))
            fail("pass " + name + ": copy of " + std::to_string(width) + "x" + std::to_string(height) + " texels beyond " +
                 role + " " + t.name + " level " + std::to_string(level));
    };
    check_region(src, src_level, src_layer, "source");
    check_region(dst, dst_level, dst_layer, "target");
    if (src.format.format != dst.format.format)
        fail("pass " + name + ": copy from " + src.name + " (" + src.desc->at("internal_format").get<std::string>() +
             ") to " + dst.name + " (" + dst.desc->at("internal_format").get<std::string>() +
             "); Vulkan copies between identical formats here");
    const VkImageAspectFlags aspect = src.format.aspect();
    VkImageCopy region{};
    const auto layer_of = [](const Texture& t, int layer) {
        return t.target == TextureTarget::texture_2d_array ? static_cast<std::uint32_t>(layer) : 0u;
    };
    region.srcSubresource = {aspect, static_cast<std::uint32_t>(src_level), layer_of(src, src_layer), 1};
    region.dstSubresource = {aspect, static_cast<std::uint32_t>(dst_level), layer_of(dst, dst_layer), 1};
    if (src.target == TextureTarget::texture_3d) region.srcOffset.z = src_layer;
    if (dst.target == TextureTarget::texture_3d) region.dstOffset.z = dst_layer;
    region.extent = {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height), 1};
    const VkImage from = src.image, to = dst.image;
    const VkImageSubresourceRange from_range{aspect, region.srcSubresource.mipLevel, 1, region.srcSubresource.baseArrayLayer, 1};
    const VkImageSubresourceRange to_range{aspect, region.dstSubresource.mipLevel, 1, region.dstSubresource.baseArrayLayer, 1};
    if (from == to) fail("pass " + name + ": copy within texture " + src.name + " is not supported by this runner");
    return [=](VkCommandBuffer cmd) {
        transition(cmd, from, from_range, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        transition(cmd, to, to_range, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        vkCmdCopyImage(cmd, from, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, to, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                       &region);
        transition(cmd, from, from_range, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
        transition(cmd, to, to_range, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    };
}

void Runner::transition(VkCommandBuffer cmd, VkImage image, const VkImageSubresourceRange& range, VkImageLayout from, VkImageLayout to) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = from == VK_IMAGE_LAYOUT_UNDEFINED ? 0 : VK_ACCESS_MEMORY_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = range;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &b);
}

void Runner::barrier(VkCommandBuffer cmd) {
    VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &b, 0,
                         nullptr, 0, nullptr);
}

} // namespace penumbra::vulkan::detail
