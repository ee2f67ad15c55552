// vkstats: what a GPU's Vulkan driver compiles a compute shader to — its register count and the other
// statistics of VK_KHR_pipeline_executable_properties (NVIDIA reports registers; GL reports nothing).
// A measurement tool for the GPU machine (docs/RENDERER.md, "Registers a program takes"), not part of
// the build: tools/shader-stats/README.md says how the SPIR-V is made from the raycaster's GLSL.
//
//   vkstats SHADER.spv BINDINGS [IR_OUT]
//
// BINDINGS: one descriptor a line, "BINDING KIND" with KIND ssbo, image, texture or ubo (set 0), as
// the program's reflection lists them (tools/shader-stats/bindings.py). IR_OUT: where the driver's
// internal representations are written, if it gives any.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vulkan/vulkan.h>

static void die(const char* what, VkResult r) {
  fprintf(stderr, "vkstats: %s failed (VkResult %d)\n", what, (int)r);
  exit(1);
}

static void* readFile(const char* path, size_t* size) {
  FILE* f = fopen(path, "rb");
  if (!f) {
    fprintf(stderr, "vkstats: cannot open %s\n", path);
    exit(1);
  }
  fseek(f, 0, SEEK_END);
  *size = (size_t)ftell(f);
  fseek(f, 0, SEEK_SET);
  void* data = malloc(*size ? *size : 1);
  if (fread(data, 1, *size, f) != *size) {
    fprintf(stderr, "vkstats: cannot read %s\n", path);
    exit(1);
  }
  fclose(f);
  return data;
}

int main(int argc, char** argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: vkstats SHADER.spv BINDINGS [IR_OUT]\n");
    return 2;
  }
  VkApplicationInfo app = {VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "vkstats";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo ici = {VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  VkInstance instance;
  VkResult r = vkCreateInstance(&ici, NULL, &instance);
  if (r != VK_SUCCESS) die("vkCreateInstance", r);
  uint32_t count = 1;
  VkPhysicalDevice gpu;
  r = vkEnumeratePhysicalDevices(instance, &count, &gpu);
  if ((r != VK_SUCCESS && r != VK_INCOMPLETE) || count == 0) die("vkEnumeratePhysicalDevices", r);
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(gpu, &props);

  VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR exeFeatures = {
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
  VkPhysicalDeviceFeatures2 features = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &exeFeatures;
  vkGetPhysicalDeviceFeatures2(gpu, &features);
  if (!exeFeatures.pipelineExecutableInfo) {
    fprintf(stderr, "vkstats: %s does not report pipeline executable statistics\n", props.deviceName);
    return 1;
  }
  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci = {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  const char* extensions[] = {VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME};
  // Only executable statistics: a core feature such as robustBufferAccess would compile bounds checks
  // into the program that GL's context does not, and change its registers.
  memset(&features.features, 0, sizeof features.features);
  VkDeviceCreateInfo dci = {VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &features;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = 1;
  dci.ppEnabledExtensionNames = extensions;
  VkDevice device;
  r = vkCreateDevice(gpu, &dci, NULL, &device);
  if (r != VK_SUCCESS) die("vkCreateDevice", r);

  // Set 0 as the reflection lists it.
  VkDescriptorSetLayoutBinding bindings[64];
  uint32_t bindingCount = 0;
  FILE* bf = fopen(argv[2], "r");
  if (!bf) {
    fprintf(stderr, "vkstats: cannot open %s\n", argv[2]);
    return 1;
  }
  unsigned binding;
  char kind[32];
  while (bindingCount < 64 && fscanf(bf, "%u %31s", &binding, kind) == 2) {
    VkDescriptorSetLayoutBinding* b = &bindings[bindingCount++];
    memset(b, 0, sizeof *b);
    b->binding = binding;
    b->descriptorCount = 1;
    b->stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    if (!strcmp(kind, "ssbo")) b->descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    else if (!strcmp(kind, "image")) b->descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    else if (!strcmp(kind, "texture")) b->descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    else if (!strcmp(kind, "ubo")) b->descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    else {
      fprintf(stderr, "vkstats: %s: kind '%s': valid are ssbo, image, texture, ubo\n", argv[2], kind);
      return 1;
    }
  }
  fclose(bf);
  VkDescriptorSetLayoutCreateInfo dslci = {VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  dslci.bindingCount = bindingCount;
  dslci.pBindings = bindings;
  VkDescriptorSetLayout setLayout;
  r = vkCreateDescriptorSetLayout(device, &dslci, NULL, &setLayout);
  if (r != VK_SUCCESS) die("vkCreateDescriptorSetLayout", r);
  VkPipelineLayoutCreateInfo plci = {VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  plci.setLayoutCount = 1;
  plci.pSetLayouts = &setLayout;
  VkPipelineLayout layout;
  r = vkCreatePipelineLayout(device, &plci, NULL, &layout);
  if (r != VK_SUCCESS) die("vkCreatePipelineLayout", r);

  size_t codeSize;
  void* code = readFile(argv[1], &codeSize);
  VkShaderModuleCreateInfo smci = {VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  smci.codeSize = codeSize;
  smci.pCode = (const uint32_t*)code;
  VkShaderModule module;
  r = vkCreateShaderModule(device, &smci, NULL, &module);
  if (r != VK_SUCCESS) die("vkCreateShaderModule", r);
  VkComputePipelineCreateInfo cpci = {VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  cpci.flags = VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR | VK_PIPELINE_CREATE_CAPTURE_INTERNAL_REPRESENTATIONS_BIT_KHR;
  cpci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  cpci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  cpci.stage.module = module;
  cpci.stage.pName = "main";
  cpci.layout = layout;
  VkPipeline pipeline;
  r = vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &cpci, NULL, &pipeline);
  if (r != VK_SUCCESS) die("vkCreateComputePipelines", r);

  PFN_vkGetPipelineExecutablePropertiesKHR getProperties =
      (PFN_vkGetPipelineExecutablePropertiesKHR)vkGetDeviceProcAddr(device, "vkGetPipelineExecutablePropertiesKHR");
  PFN_vkGetPipelineExecutableStatisticsKHR getStatistics =
      (PFN_vkGetPipelineExecutableStatisticsKHR)vkGetDeviceProcAddr(device, "vkGetPipelineExecutableStatisticsKHR");
  PFN_vkGetPipelineExecutableInternalRepresentationsKHR getIr =
      (PFN_vkGetPipelineExecutableInternalRepresentationsKHR)vkGetDeviceProcAddr(
          device, "vkGetPipelineExecutableInternalRepresentationsKHR");
  VkPipelineInfoKHR pinfo = {VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
  pinfo.pipeline = pipeline;
  uint32_t exeCount = 0;
  getProperties(device, &pinfo, &exeCount, NULL);
  VkPipelineExecutablePropertiesKHR exes[8];
  for (uint32_t i = 0; i < 8; ++i) {
    memset(&exes[i], 0, sizeof exes[i]);
    exes[i].sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR;
  }
  if (exeCount > 8) exeCount = 8;
  getProperties(device, &pinfo, &exeCount, exes);
  printf("%s: %s\n", argv[1], props.deviceName);
  for (uint32_t e = 0; e < exeCount; ++e) {
    printf("  executable %u: %s (subgroup %u)\n", e, exes[e].name, exes[e].subgroupSize);
    VkPipelineExecutableInfoKHR einfo = {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
    einfo.pipeline = pipeline;
    einfo.executableIndex = e;
    uint32_t statCount = 0;
    getStatistics(device, &einfo, &statCount, NULL);
    VkPipelineExecutableStatisticKHR stats[64];
    if (statCount > 64) statCount = 64;
    for (uint32_t i = 0; i < statCount; ++i) {
      memset(&stats[i], 0, sizeof stats[i]);
      stats[i].sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR;
    }
    getStatistics(device, &einfo, &statCount, stats);
    for (uint32_t i = 0; i < statCount; ++i) {
      printf("    %s: ", stats[i].name);
      switch (stats[i].format) {
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: printf("%s", stats[i].value.b32 ? "true" : "false"); break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: printf("%lld", (long long)stats[i].value.i64); break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
          printf("%llu (0x%llx)", (unsigned long long)stats[i].value.u64, (unsigned long long)stats[i].value.u64);
          break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR: printf("%g", stats[i].value.f64); break;
        default: printf("?");
      }
      printf("  (%s)\n", stats[i].description);
    }
    if (argc > 3 && getIr) {
      uint32_t irCount = 0;
      getIr(device, &einfo, &irCount, NULL);
      VkPipelineExecutableInternalRepresentationKHR irs[8];
      if (irCount > 8) irCount = 8;
      for (uint32_t i = 0; i < irCount; ++i) {
        memset(&irs[i], 0, sizeof irs[i]);
        irs[i].sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INTERNAL_REPRESENTATION_KHR;
      }
      getIr(device, &einfo, &irCount, irs);
      for (uint32_t i = 0; i < irCount; ++i) irs[i].pData = malloc(irs[i].dataSize ? irs[i].dataSize : 1);
      getIr(device, &einfo, &irCount, irs);
      FILE* out = fopen(argv[3], e == 0 ? "wb" : "ab");
      for (uint32_t i = 0; out && i < irCount; ++i) {
        printf("    representation %u: %s, %zu bytes%s\n", i, irs[i].name, irs[i].dataSize, irs[i].isText ? ", text" : "");
        fprintf(out, "=== %s (%s)\n", irs[i].name, irs[i].description);
        fwrite(irs[i].pData, 1, irs[i].dataSize, out);
        fprintf(out, "\n");
      }
      if (out) fclose(out);
      for (uint32_t i = 0; i < irCount; ++i) free(irs[i].pData);
    }
  }
  vkDestroyPipeline(device, pipeline, NULL);
  vkDestroyShaderModule(device, module, NULL);
  vkDestroyPipelineLayout(device, layout, NULL);
  vkDestroyDescriptorSetLayout(device, setLayout, NULL);
  vkDestroyDevice(device, NULL);
  vkDestroyInstance(instance, NULL);
  free(code);
  return 0;
}
