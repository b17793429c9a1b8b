// Pipeline helpers (after niagara's shaders.h): a descriptor-set layout from a list of binding
// types, a pipeline layout with one push-constant range, a compute pipeline in one call, and the
// graphics pipeline of a depth-tested draw into one integer colour attachment.
#pragma once

#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "bluetile/gpu/context.h"

namespace bluetile::gpu {

// Binding b of the layout has type types[b], one descriptor, visible to every stage.
VkDescriptorSetLayout create_set_layout(VkDevice device, std::span<const VkDescriptorType> types);
VkPipelineLayout create_pipeline_layout(VkDevice device, VkDescriptorSetLayout set_layout, VkShaderStageFlags push_stages,
                                        std::uint32_t push_bytes);
// Throws Error (naming the shader) when the device rejects it.
VkPipeline create_compute_pipeline(Context& context, VkPipelineLayout layout, const char* shader);

struct GraphicsPipelineDesc {
  const char* vertex_shader = nullptr;
  const char* fragment_shader = nullptr;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkFormat colour_format = VK_FORMAT_R32_UINT;  // one attachment, red channel written
  VkFormat depth_format = VK_FORMAT_D32_SFLOAT;  // test LESS, write on
};

// A render pass that clears both attachments, keeps the colour one for later shader reads and
// transfers (layout GENERAL), and discards depth; and a pipeline for it with dynamic viewport
// and scissor.
VkRenderPass create_render_pass(VkDevice device, const GraphicsPipelineDesc& desc);
VkPipeline create_graphics_pipeline(Context& context, VkPipelineLayout layout, VkRenderPass pass, const GraphicsPipelineDesc& desc);

}  // namespace bluetile::gpu
