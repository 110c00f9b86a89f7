// A VkBuffer with its own memory: device-local for what kernels read and write, or
// host-visible (mapped for its lifetime) for uploads and read-backs.
#pragma once

#include <cstddef>
#include <cstdint>

#include "absl/status/statusor.h"
#include "worker/backends/vulkan/context.h"

namespace pf::vk {

enum class MemoryUse {
    kDevice,        // device-local: kernels' storage and dispatch arguments; filled by transfers
    kUpload,        // host-visible, coherent: written by the CPU, copied to the device
    kReadback,      // host-visible, cached where possible: copied from the device, read by the CPU
    kKernelToHost,  // host-visible, cached where possible: written by kernels, read by the CPU
};

class Buffer {
public:
    Buffer() = default;
    // Sizes round up to 16 bytes (Vulkan has no empty buffers). RESOURCE_EXHAUSTED where the
    // device has no room.
    static absl::StatusOr<Buffer> Create(const Context& context, VkDeviceSize bytes, MemoryUse use);
    Buffer(Buffer&& other) noexcept { *this = std::move(other); }
    Buffer& operator=(Buffer&& other) noexcept;
    ~Buffer() { Release(); }

    VkBuffer Handle() const { return buffer_; }
    VkDeviceSize Bytes() const { return bytes_; }
    // The mapping of a host-visible buffer (null for device-local ones).
    void* Mapped() const { return mapped_; }
    // Makes the device's writes visible to Mapped() (a no-op on coherent memory).
    void InvalidateForRead() const;

private:
    void Release();

    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize bytes_ = 0;
    void* mapped_ = nullptr;
    bool coherent_ = true;
};

}  // namespace pf::vk
