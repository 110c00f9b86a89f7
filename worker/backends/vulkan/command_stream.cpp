// Recording, submission and barriers.
#include "worker/backends/vulkan/command_stream.h"

#include <cstdint>
#include <utility>

namespace pf::vk {

absl::StatusOr<CommandStream> CommandStream::Create(const Context& context) {
    CommandStream stream;
    stream.device_ = context.Device();
    stream.queue_ = context.Queue();
    const VkCommandPoolCreateInfo pool{.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                       .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                       .queueFamilyIndex = context.QueueFamily()};
    PF_VK_TRY(vkCreateCommandPool(stream.device_, &pool, nullptr, &stream.pool_));
    const VkCommandBufferAllocateInfo allocate{
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = stream.pool_,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1};
    PF_VK_TRY(vkAllocateCommandBuffers(stream.device_, &allocate, &stream.commands_));
    const VkFenceCreateInfo fence{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    PF_VK_TRY(vkCreateFence(stream.device_, &fence, nullptr, &stream.fence_));
    return stream;
}

CommandStream::CommandStream(CommandStream&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      queue_(other.queue_),
      pool_(std::exchange(other.pool_, VK_NULL_HANDLE)),
      commands_(std::exchange(other.commands_, VK_NULL_HANDLE)),
      fence_(std::exchange(other.fence_, VK_NULL_HANDLE)) {}

CommandStream::~CommandStream() {
    if (device_ == VK_NULL_HANDLE) return;
    if (fence_ != VK_NULL_HANDLE) vkDestroyFence(device_, fence_, nullptr);
    if (pool_ != VK_NULL_HANDLE) vkDestroyCommandPool(device_, pool_, nullptr);  // frees the buffer
}

absl::StatusOr<VkCommandBuffer> CommandStream::Begin() {
    PF_VK_TRY(vkResetCommandBuffer(commands_, 0));
    const VkCommandBufferBeginInfo begin{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                         .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    PF_VK_TRY(vkBeginCommandBuffer(commands_, &begin));
    return commands_;
}

absl::Status CommandStream::SubmitAndWait() {
    PF_VK_TRY(vkEndCommandBuffer(commands_));
    const VkSubmitInfo submit{.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
                              .commandBufferCount = 1,
                              .pCommandBuffers = &commands_};
    PF_VK_TRY(vkResetFences(device_, 1, &fence_));
    PF_VK_TRY(vkQueueSubmit(queue_, 1, &submit, fence_));
    PF_VK_TRY(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
    return absl::OkStatus();
}

void CommandStream::Barrier() const {
    const VkMemoryBarrier barrier{
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                         VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT |
                         VK_ACCESS_HOST_READ_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT};
    const VkPipelineStageFlags stages =
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    vkCmdPipelineBarrier(commands_, stages,
                         stages | VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                         0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace pf::vk
