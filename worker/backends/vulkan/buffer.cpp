// Buffers and their memory.
#include "worker/backends/vulkan/buffer.h"

#include <utility>

#include "absl/strings/str_cat.h"

namespace pf::vk {
namespace {

// The first memory type allowed by `type_bits` with all of `required`, preferring those
// that also have `preferred`; -1 if none.
int FindMemoryType(const VkPhysicalDeviceMemoryProperties& memory, uint32_t type_bits,
                   VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) {
    int fallback = -1;
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        const VkMemoryPropertyFlags flags = memory.memoryTypes[i].propertyFlags;
        if (!(type_bits & (1u << i)) || (flags & required) != required) continue;
        if ((flags & preferred) == preferred) return static_cast<int>(i);
        if (fallback < 0) fallback = static_cast<int>(i);
    }
    return fallback;
}

}  // namespace

absl::StatusOr<Buffer> Buffer::Create(const Context& context, VkDeviceSize bytes, MemoryUse use) {
    Buffer buffer;
    buffer.device_ = context.Device();
    buffer.bytes_ = std::max<VkDeviceSize>(16, (bytes + 15) / 16 * 16);
    VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (use == MemoryUse::kDevice)
        usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    if (use == MemoryUse::kUpload) usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    if (use == MemoryUse::kKernelToHost) usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    const VkBufferCreateInfo info{.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                                  .size = buffer.bytes_,
                                  .usage = usage,
                                  .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
    PF_VK_TRY(vkCreateBuffer(buffer.device_, &info, nullptr, &buffer.buffer_));
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(buffer.device_, buffer.buffer_, &requirements);
    VkMemoryPropertyFlags required = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, preferred = 0;
    if (use == MemoryUse::kUpload)
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if (use == MemoryUse::kReadback || use == MemoryUse::kKernelToHost)
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT,
        preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    const int type =
        FindMemoryType(context.Memory(), requirements.memoryTypeBits, required, preferred);
    if (type < 0)
        return absl::FailedPreconditionError(absl::StrCat(
            "Vulkan device ", context.Info().name, " has no memory type for a buffer of this use"));
    const VkMemoryAllocateInfo allocate{.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                        .allocationSize = requirements.size,
                                        .memoryTypeIndex = static_cast<uint32_t>(type)};
    PF_VK_TRY(vkAllocateMemory(buffer.device_, &allocate, nullptr, &buffer.memory_));
    PF_VK_TRY(vkBindBufferMemory(buffer.device_, buffer.buffer_, buffer.memory_, 0));
    if (use != MemoryUse::kDevice) {
        PF_VK_TRY(
            vkMapMemory(buffer.device_, buffer.memory_, 0, VK_WHOLE_SIZE, 0, &buffer.mapped_));
        buffer.coherent_ =
            context.Memory().memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    }
    return buffer;
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        Release();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        bytes_ = std::exchange(other.bytes_, 0);
        mapped_ = std::exchange(other.mapped_, nullptr);
        coherent_ = other.coherent_;
    }
    return *this;
}

void Buffer::InvalidateForRead() const {
    if (coherent_ || mapped_ == nullptr) return;
    const VkMappedMemoryRange range{
        .sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, .memory = memory_, .size = VK_WHOLE_SIZE};
    vkInvalidateMappedMemoryRanges(device_, 1, &range);
}

void Buffer::Release() {
    if (device_ == VK_NULL_HANDLE) return;
    if (mapped_ != nullptr) vkUnmapMemory(device_, memory_);
    if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(device_, buffer_, nullptr);
    if (memory_ != VK_NULL_HANDLE) vkFreeMemory(device_, memory_, nullptr);
    device_ = VK_NULL_HANDLE, buffer_ = VK_NULL_HANDLE, memory_ = VK_NULL_HANDLE, mapped_ = nullptr;
}

}  // namespace pf::vk
