// Build: gcc -O1 -shared -fPIC -o vkcache.so vkcache.c -ldl -lvulkan. Run: LD_PRELOAD=$PWD/vkcache.so BINARY (the cache is never destroyed:
// one validation error at exit). README "CI time, session 17".
// Experiment: one VkPipelineCache for every pipeline the process creates (when the app passes none),
// to see whether lavapipe reuses work across identical pipelines. Times the two calls.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <time.h>
#include <unistd.h>
#include <vulkan/vulkan.h>
static VkDevice dev; static VkPipelineCache cache; static double tg=0,tc=0; static long ng=0,nc=0;
static double now(void){ struct timespec t; clock_gettime(CLOCK_MONOTONIC,&t); return t.tv_sec+t.tv_nsec*1e-9; }
static VkPipelineCache get(VkDevice d,VkPipelineCache c){ if(c) return c; if(d!=dev){ VkPipelineCacheCreateInfo ci={VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO}; cache=VK_NULL_HANDLE; vkCreatePipelineCache(d,&ci,NULL,&cache); dev=d; } return cache; }
VKAPI_ATTR VkResult VKAPI_CALL vkCreateGraphicsPipelines(VkDevice d,VkPipelineCache c,uint32_t n,const VkGraphicsPipelineCreateInfo* ci,const VkAllocationCallbacks* a,VkPipeline* p){
  static PFN_vkCreateGraphicsPipelines r; if(!r) r=(PFN_vkCreateGraphicsPipelines)dlsym(RTLD_NEXT,"vkCreateGraphicsPipelines");
  double t=now(); VkResult x=r(d,get(d,c),n,ci,a,p); tg+=now()-t; ng+=n; return x; }
VKAPI_ATTR VkResult VKAPI_CALL vkCreateComputePipelines(VkDevice d,VkPipelineCache c,uint32_t n,const VkComputePipelineCreateInfo* ci,const VkAllocationCallbacks* a,VkPipeline* p){
  static PFN_vkCreateComputePipelines r; if(!r) r=(PFN_vkCreateComputePipelines)dlsym(RTLD_NEXT,"vkCreateComputePipelines");
  double t=now(); VkResult x=r(d,get(d,c),n,ci,a,p); tc+=now()-t; nc+=n; return x; }
__attribute__((destructor)) static void dump(void){ if(ng+nc) fprintf(stderr,"VKCACHE pid %d: graphics %ld pipelines %.1f s, compute %ld pipelines %.1f s\n",getpid(),ng,tg,nc,tc); }
