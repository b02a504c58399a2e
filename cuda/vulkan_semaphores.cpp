#include "cuda/vulkan_semaphores.hpp"

#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <vector>

#if LIGHTPASS_HAVE_VULKAN_HEADERS
#define VK_NO_PROTOTYPES
#include <vulkan/vulkan_core.h>
#endif

namespace lp::cuda {

#if LIGHTPASS_HAVE_VULKAN_HEADERS

namespace {

struct Loader {
    void* library = nullptr;
    PFN_vkGetInstanceProcAddr getInstanceProcAddr = nullptr;
    std::string problem;
};

// Opened once and kept for the process: the driver's threads may still run inside it at exit.
const Loader& loader() {
    static const Loader l = [] {
        Loader r;
        r.library = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
        if (!r.library) {
            const char* e = dlerror();
            r.problem = std::string("no Vulkan loader (") + (e ? e : "libvulkan.so.1 not found") + ")";
            return r;
        }
        r.getInstanceProcAddr = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(r.library, "vkGetInstanceProcAddr"));
        if (!r.getInstanceProcAddr) r.problem = "libvulkan.so.1 has no vkGetInstanceProcAddr";
        return r;
    }();
    return l;
}

std::string vkError(const char* call, VkResult r) { return std::string(call) + " failed (VkResult " + std::to_string(int(r)) + ")"; }

std::string uuidText(const uint8_t* u) {
    char s[40];
    std::snprintf(s, sizeof s, "%02x%02x%02x%02x-%02x%02x-...", u[0], u[1], u[2], u[3], u[4], u[5]);
    return s;
}

}  // namespace

struct VulkanSemaphoreDevice::Impl {
    VkInstance instance = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::string name;
    PFN_vkDestroyInstance destroyInstance = nullptr;
    PFN_vkDestroyDevice destroyDevice = nullptr;
    PFN_vkCreateSemaphore createSemaphore = nullptr;
    PFN_vkDestroySemaphore destroySemaphore = nullptr;
    PFN_vkGetSemaphoreFdKHR getSemaphoreFd = nullptr;
    ~Impl() {
        if (device && destroyDevice) destroyDevice(device, nullptr);
        if (instance && destroyInstance) destroyInstance(instance, nullptr);
    }
};

VulkanSemaphoreDevice::VulkanSemaphoreDevice() : impl_(std::make_unique<Impl>()) {}
VulkanSemaphoreDevice::~VulkanSemaphoreDevice() = default;
const std::string& VulkanSemaphoreDevice::deviceName() const { return impl_->name; }

std::unique_ptr<VulkanSemaphoreDevice> VulkanSemaphoreDevice::open(const DeviceUuid& uuid, std::string& problem) {
    const Loader& l = loader();
    if (!l.problem.empty()) {
        problem = l.problem;
        return nullptr;
    }
    auto global = [&](const char* fn) { return l.getInstanceProcAddr(VK_NULL_HANDLE, fn); };
    auto enumerateVersion = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(global("vkEnumerateInstanceVersion"));
    uint32_t version = VK_API_VERSION_1_0;
    if (enumerateVersion) enumerateVersion(&version);
    if (version < VK_API_VERSION_1_1) {
        problem = "the Vulkan loader is older than 1.1";
        return nullptr;
    }
    auto createInstance = reinterpret_cast<PFN_vkCreateInstance>(global("vkCreateInstance"));
    if (!createInstance) {
        problem = "the Vulkan loader has no vkCreateInstance";
        return nullptr;
    }
    std::unique_ptr<VulkanSemaphoreDevice> d(new VulkanSemaphoreDevice);
    Impl& m = *d->impl_;
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "lightpass GL-CUDA semaphores";
    app.apiVersion = VK_API_VERSION_1_1;
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pApplicationInfo = &app;
    if (VkResult r = createInstance(&ici, nullptr, &m.instance); r != VK_SUCCESS) {
        m.instance = VK_NULL_HANDLE;
        problem = r == VK_ERROR_INCOMPATIBLE_DRIVER ? "no Vulkan driver (vkCreateInstance: no ICD)" : vkError("vkCreateInstance", r);
        return nullptr;
    }
    auto inst = [&](const char* fn) { return l.getInstanceProcAddr(m.instance, fn); };
    m.destroyInstance = reinterpret_cast<PFN_vkDestroyInstance>(inst("vkDestroyInstance"));
    auto enumerateDevices = reinterpret_cast<PFN_vkEnumeratePhysicalDevices>(inst("vkEnumeratePhysicalDevices"));
    auto properties2 = reinterpret_cast<PFN_vkGetPhysicalDeviceProperties2>(inst("vkGetPhysicalDeviceProperties2"));
    auto extensions = reinterpret_cast<PFN_vkEnumerateDeviceExtensionProperties>(inst("vkEnumerateDeviceExtensionProperties"));
    auto semaphoreProps = reinterpret_cast<PFN_vkGetPhysicalDeviceExternalSemaphoreProperties>(
        inst("vkGetPhysicalDeviceExternalSemaphoreProperties"));
    auto createDevice = reinterpret_cast<PFN_vkCreateDevice>(inst("vkCreateDevice"));
    auto getDeviceProcAddr = reinterpret_cast<PFN_vkGetDeviceProcAddr>(inst("vkGetDeviceProcAddr"));
    if (!m.destroyInstance || !enumerateDevices || !properties2 || !extensions || !semaphoreProps || !createDevice ||
        !getDeviceProcAddr) {
        problem = "the Vulkan instance lacks a 1.1 entry point";
        return nullptr;
    }
    uint32_t count = 0;
    enumerateDevices(m.instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    if (count) enumerateDevices(m.instance, &count, devices.data());
    VkPhysicalDevice chosen = VK_NULL_HANDLE;
    std::string seen;
    for (VkPhysicalDevice pd : devices) {
        VkPhysicalDeviceIDProperties id{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
        VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
        props.pNext = &id;
        properties2(pd, &props);
        seen += (seen.empty() ? "" : ", ") + std::string(props.properties.deviceName);
        if (std::memcmp(id.deviceUUID, uuid.data(), VK_UUID_SIZE) == 0) {
            chosen = pd;
            m.name = props.properties.deviceName;
        }
    }
    if (!chosen) {
        problem = "no Vulkan device has the CUDA device's UUID " + uuidText(uuid.data()) + " (" +
                  std::to_string(count) + " device" + (count == 1 ? "" : "s") + (seen.empty() ? "" : ": " + seen) + ")";
        return nullptr;
    }
    uint32_t extCount = 0;
    extensions(chosen, nullptr, &extCount, nullptr);
    std::vector<VkExtensionProperties> exts(extCount);
    if (extCount) extensions(chosen, nullptr, &extCount, exts.data());
    bool hasSemaphoreFd = false;
    for (const VkExtensionProperties& e : exts)
        hasSemaphoreFd = hasSemaphoreFd || std::strcmp(e.extensionName, VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME) == 0;
    if (!hasSemaphoreFd) {
        problem = "the Vulkan device " + m.name + " has no " VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME;
        return nullptr;
    }
    VkPhysicalDeviceExternalSemaphoreInfo semInfo{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_SEMAPHORE_INFO};
    semInfo.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
    VkExternalSemaphoreProperties semProps{VK_STRUCTURE_TYPE_EXTERNAL_SEMAPHORE_PROPERTIES};
    semaphoreProps(chosen, &semInfo, &semProps);
    if (!(semProps.externalSemaphoreFeatures & VK_EXTERNAL_SEMAPHORE_FEATURE_EXPORTABLE_BIT)) {
        problem = "the Vulkan device " + m.name + " cannot export semaphores as opaque file descriptors";
        return nullptr;
    }
    // One queue because a device needs one; it is never used (GL and CUDA do the signalling).
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = 0;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    const char* enabled[] = {VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME};
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &queue;
    dci.enabledExtensionCount = 1;
    dci.ppEnabledExtensionNames = enabled;
    if (VkResult r = createDevice(chosen, &dci, nullptr, &m.device); r != VK_SUCCESS) {
        m.device = VK_NULL_HANDLE;
        problem = vkError("vkCreateDevice", r);
        return nullptr;
    }
    m.destroyDevice = reinterpret_cast<PFN_vkDestroyDevice>(getDeviceProcAddr(m.device, "vkDestroyDevice"));
    m.createSemaphore = reinterpret_cast<PFN_vkCreateSemaphore>(getDeviceProcAddr(m.device, "vkCreateSemaphore"));
    m.destroySemaphore = reinterpret_cast<PFN_vkDestroySemaphore>(getDeviceProcAddr(m.device, "vkDestroySemaphore"));
    m.getSemaphoreFd = reinterpret_cast<PFN_vkGetSemaphoreFdKHR>(getDeviceProcAddr(m.device, "vkGetSemaphoreFdKHR"));
    if (!m.destroyDevice || !m.createSemaphore || !m.destroySemaphore || !m.getSemaphoreFd) {
        problem = "the Vulkan device " + m.name + " lacks vkGetSemaphoreFdKHR";
        return nullptr;
    }
    return d;
}

uint64_t VulkanSemaphoreDevice::createSemaphore(std::string& problem) const {
    VkExportSemaphoreCreateInfo exportInfo{VK_STRUCTURE_TYPE_EXPORT_SEMAPHORE_CREATE_INFO};
    exportInfo.handleTypes = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
    VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    info.pNext = &exportInfo;
    VkSemaphore s = VK_NULL_HANDLE;
    if (VkResult r = impl_->createSemaphore(impl_->device, &info, nullptr, &s); r != VK_SUCCESS) {
        problem = vkError("vkCreateSemaphore", r);
        return 0;
    }
    return reinterpret_cast<uint64_t>(s);
}

int VulkanSemaphoreDevice::exportFd(uint64_t semaphore, std::string& problem) const {
    VkSemaphoreGetFdInfoKHR info{VK_STRUCTURE_TYPE_SEMAPHORE_GET_FD_INFO_KHR};
    info.semaphore = reinterpret_cast<VkSemaphore>(semaphore);
    info.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
    int fd = -1;
    if (VkResult r = impl_->getSemaphoreFd(impl_->device, &info, &fd); r != VK_SUCCESS || fd < 0) {
        problem = vkError("vkGetSemaphoreFdKHR", r);
        return -1;
    }
    return fd;
}

void VulkanSemaphoreDevice::destroySemaphore(uint64_t semaphore) const {
    if (semaphore) impl_->destroySemaphore(impl_->device, reinterpret_cast<VkSemaphore>(semaphore), nullptr);
}

std::string vulkanLoaderProblem() { return loader().problem; }

uint32_t vulkanLoaderVersion() {
    const Loader& l = loader();
    if (!l.problem.empty()) return 0;
    auto fn = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(l.getInstanceProcAddr(VK_NULL_HANDLE, "vkEnumerateInstanceVersion"));
    uint32_t v = VK_API_VERSION_1_0;
    if (fn && fn(&v) != VK_SUCCESS) return 0;
    return v;
}

#else  // built without the Vulkan headers (libvulkan-dev): every semaphore request says so

struct VulkanSemaphoreDevice::Impl {
    std::string name;
};
VulkanSemaphoreDevice::VulkanSemaphoreDevice() : impl_(std::make_unique<Impl>()) {}
VulkanSemaphoreDevice::~VulkanSemaphoreDevice() = default;
const std::string& VulkanSemaphoreDevice::deviceName() const { return impl_->name; }
std::unique_ptr<VulkanSemaphoreDevice> VulkanSemaphoreDevice::open(const DeviceUuid&, std::string& problem) {
    problem = vulkanLoaderProblem();
    return nullptr;
}
uint64_t VulkanSemaphoreDevice::createSemaphore(std::string& problem) const {
    problem = vulkanLoaderProblem();
    return 0;
}
int VulkanSemaphoreDevice::exportFd(uint64_t, std::string& problem) const {
    problem = vulkanLoaderProblem();
    return -1;
}
void VulkanSemaphoreDevice::destroySemaphore(uint64_t) const {}
std::string vulkanLoaderProblem() { return "built without the Vulkan headers (libvulkan-dev)"; }
uint32_t vulkanLoaderVersion() { return 0; }

#endif

}  // namespace lp::cuda
