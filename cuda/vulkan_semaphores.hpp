#pragma once
// Semaphores that GL and CUDA can both import, made by Vulkan. GL (GL_EXT_semaphore_fd) and CUDA
// (cudaImportExternalSemaphore) can import a semaphore but neither can export one; Vulkan can
// (VK_KHR_external_semaphore_fd). So a minimal Vulkan instance and device on the same GPU (the
// physical device whose deviceUUID is the CUDA device's UUID) make binary semaphores exportable as
// opaque file descriptors, and GL and CUDA each import a descriptor of the same payload.
//
// The Vulkan loader is opened at run time (dlopen of libvulkan.so.1), not linked: the executable
// starts where no loader is installed, and every failure is a one-line reason for the fallback.
// Plain C++ (no CUDA), so it is testable everywhere.
#include <array>
#include <cstdint>
#include <memory>
#include <string>

namespace lp::cuda {

using DeviceUuid = std::array<unsigned char, 16>;

class VulkanSemaphoreDevice {
public:
    // The loader, an instance (Vulkan 1.1) and a device on the physical device whose deviceUUID is
    // `uuid` with VK_KHR_external_semaphore_fd and exportable opaque-fd semaphores; null with
    // `problem` set ("no Vulkan device has the CUDA device's UUID (2 devices: llvmpipe, ...)").
    static std::unique_ptr<VulkanSemaphoreDevice> open(const DeviceUuid& uuid, std::string& problem);
    ~VulkanSemaphoreDevice();
    VulkanSemaphoreDevice(const VulkanSemaphoreDevice&) = delete;
    VulkanSemaphoreDevice& operator=(const VulkanSemaphoreDevice&) = delete;

    const std::string& deviceName() const;
    // A binary semaphore exportable as an opaque fd (the VkSemaphore as an integer); 0 with
    // `problem` set on failure.
    uint64_t createSemaphore(std::string& problem) const;
    // A new descriptor of the semaphore's payload, owned by the caller (importing it hands it to
    // the importer); -1 with `problem` set on failure.
    int exportFd(uint64_t semaphore, std::string& problem) const;
    void destroySemaphore(uint64_t semaphore) const;

private:
    VulkanSemaphoreDevice();
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Empty when libvulkan.so.1 opens and has vkGetInstanceProcAddr, else why not.
std::string vulkanLoaderProblem();
// What vkEnumerateInstanceVersion of the opened loader reports (VK_MAKE_API_VERSION), 0 without one.
uint32_t vulkanLoaderVersion();

}  // namespace lp::cuda
