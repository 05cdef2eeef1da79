// volk's implementation: the Vulkan loader (libvulkan.so.1) is opened at run time by
// volkInitialize (vulkan_context.cpp), so the program builds and runs where there is none.
#define VOLK_IMPLEMENTATION
#include <volk.h>
