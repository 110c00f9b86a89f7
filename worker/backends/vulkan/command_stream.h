// One command buffer recorded, submitted and waited for at a time, with the barriers the
// backend's kernels and transfers need between them.
#pragma once

#include "absl/status/statusor.h"
#include "worker/backends/vulkan/context.h"

namespace pf::vk {

class CommandStream {
public:
    static absl::StatusOr<CommandStream> Create(const Context& context);
    CommandStream(CommandStream&& other) noexcept;
    CommandStream& operator=(CommandStream&&) = delete;
    ~CommandStream();

    // Starts recording; the buffer returned stays valid until SubmitAndWait.
    absl::StatusOr<VkCommandBuffer> Begin();
    // Ends recording, submits to the context's queue and waits for the device to finish.
    absl::Status SubmitAndWait();

    // Orders everything recorded so far (kernels and transfers) before what follows.
    void Barrier() const;

private:
    CommandStream() = default;

    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer commands_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace pf::vk
