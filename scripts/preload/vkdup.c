// Build: gcc -O1 -shared -fPIC -o vkdup.so vkdup.c -ldl -lpthread. Run: LD_PRELOAD=$PWD/vkdup.so BINARY; prints VKDUP on stderr at exit.
// README "CI time, session 17".
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <pthread.h>
#include <vulkan/vulkan.h>
// Which pipelines are created more than once with the same shaders + specialization (FNV over SPIR-V and spec data).
#define NM 65536
static struct { VkShaderModule h; uint64_t code; } mods[NM]; static int nmods=0;
#define NK 65536
static struct { uint64_t key; int count; double secs; } keys[NK];
static pthread_mutex_t mu=PTHREAD_MUTEX_INITIALIZER;
static uint64_t fnv(uint64_t h,const void* p,size_t n){ const unsigned char* c=p; for(size_t i=0;i<n;i++){ h^=c[i]; h*=1099511628211ull;} return h; }
static double now(void){ struct timespec t; clock_gettime(CLOCK_MONOTONIC,&t); return t.tv_sec+t.tv_nsec*1e-9; }
static uint64_t modcode(VkShaderModule m){ for(int i=nmods-1;i>=0;i--) if(mods[i].h==m) return mods[i].code; return 0; }
VKAPI_ATTR VkResult VKAPI_CALL vkCreateShaderModule(VkDevice d,const VkShaderModuleCreateInfo* ci,const VkAllocationCallbacks* a,VkShaderModule* m){
  static PFN_vkCreateShaderModule r; if(!r) r=(PFN_vkCreateShaderModule)dlsym(RTLD_NEXT,"vkCreateShaderModule");
  VkResult x=r(d,ci,a,m); pthread_mutex_lock(&mu); if(nmods<NM){ mods[nmods].h=*m; mods[nmods].code=fnv(14695981039346656037ull,ci->pCode,ci->codeSize); nmods++; } pthread_mutex_unlock(&mu); return x; }
static uint64_t stagekey(uint64_t h,const VkPipelineShaderStageCreateInfo* s){
  uint64_t c=modcode(s->module); h=fnv(h,&c,8); h=fnv(h,&s->stage,sizeof s->stage); h=fnv(h,s->pName,strlen(s->pName));
  if(s->pSpecializationInfo){ h=fnv(h,s->pSpecializationInfo->pData,s->pSpecializationInfo->dataSize); h=fnv(h,s->pSpecializationInfo->pMapEntries,s->pSpecializationInfo->mapEntryCount*sizeof(VkSpecializationMapEntry)); }
  return h; }
static void note(uint64_t k,double secs){ pthread_mutex_lock(&mu); unsigned i=(unsigned)(k%NK); while(keys[i].count&&keys[i].key!=k) i=(i+1)%NK; keys[i].key=k; keys[i].count++; keys[i].secs+=secs; pthread_mutex_unlock(&mu); }
VKAPI_ATTR VkResult VKAPI_CALL vkCreateGraphicsPipelines(VkDevice d,VkPipelineCache c,uint32_t n,const VkGraphicsPipelineCreateInfo* ci,const VkAllocationCallbacks* a,VkPipeline* p){
  static PFN_vkCreateGraphicsPipelines r; if(!r) r=(PFN_vkCreateGraphicsPipelines)dlsym(RTLD_NEXT,"vkCreateGraphicsPipelines");
  double t=now(); VkResult x=r(d,c,n,ci,a,p); double s=(now()-t)/n;
  for(uint32_t i=0;i<n;i++){ uint64_t h=1; for(uint32_t j=0;j<ci[i].stageCount;j++) h=stagekey(h,&ci[i].pStages[j]);
    if(ci[i].pColorBlendState) { h=fnv(h,&ci[i].pColorBlendState->attachmentCount,4); if(ci[i].pColorBlendState->pAttachments) h=fnv(h,ci[i].pColorBlendState->pAttachments,ci[i].pColorBlendState->attachmentCount*sizeof(VkPipelineColorBlendAttachmentState)); }
    note(h,s); }
  return x; }
VKAPI_ATTR VkResult VKAPI_CALL vkCreateComputePipelines(VkDevice d,VkPipelineCache c,uint32_t n,const VkComputePipelineCreateInfo* ci,const VkAllocationCallbacks* a,VkPipeline* p){
  static PFN_vkCreateComputePipelines r; if(!r) r=(PFN_vkCreateComputePipelines)dlsym(RTLD_NEXT,"vkCreateComputePipelines");
  double t=now(); VkResult x=r(d,c,n,ci,a,p); double s=(now()-t)/n;
  for(uint32_t i=0;i<n;i++) note(stagekey(2,&ci[i].stage),s);
  return x; }
__attribute__((destructor)) static void dump(void){
  long total=0,distinct=0; double all=0,firsts=0;
  for(int i=0;i<NK;i++) if(keys[i].count){ total+=keys[i].count; distinct++; all+=keys[i].secs; firsts+=keys[i].secs/keys[i].count; }
  if(total) fprintf(stderr,"VKDUP pid %d: %ld pipelines, %ld distinct (shaders+spec+blend); %.1f s in creation, of which %.1f s the first of each (estimate: mean per key)\n",getpid(),total,distinct,all,firsts);
}
