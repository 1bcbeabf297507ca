// Build: gcc -O1 -shared -fPIC -o bigmalloc.so bigmalloc.c -ldl -lpthread. Run: BIGMALLOC_OUT=/tmp/acc LD_PRELOAD=$PWD/bigmalloc.so BINARY;
// writes /tmp/acc.PID (top 60 call stacks of allocations >= 256 KiB, by bytes) and /tmp/acc.PID.maps. README "CI time, session 17".
// LD_PRELOAD shim: count allocations >= BIG bytes by (size, caller stack hash); dump at exit.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <execinfo.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>
#include <pthread.h>
#include <unistd.h>
#define BIG (256*1024)
#define NSITES 4096
#define DEPTH 40
static char names[NSITES][DEPTH][160];
typedef struct { uint64_t key; size_t size; long count; double bytes; void* bt[DEPTH]; int n; int idx; } Site;
static Site sites[NSITES];
static pthread_mutex_t mu = PTHREAD_MUTEX_INITIALIZER;
static __thread int inside = 0;
static void* (*rmalloc)(size_t); static void* (*rcalloc)(size_t,size_t); static void* (*rrealloc)(void*,size_t);
static int (*rpm)(void**,size_t,size_t); static void* (*raa)(size_t,size_t); static void* (*rmemalign)(size_t,size_t);
static char tmpbuf[65536]; static size_t tmpoff=0;
static void init(void){ if(rmalloc) return; rmalloc=dlsym(RTLD_NEXT,"malloc"); rcalloc=dlsym(RTLD_NEXT,"calloc"); rrealloc=dlsym(RTLD_NEXT,"realloc"); rpm=dlsym(RTLD_NEXT,"posix_memalign"); raa=dlsym(RTLD_NEXT,"aligned_alloc"); rmemalign=dlsym(RTLD_NEXT,"memalign"); }
static void record(size_t size){
  if(size<BIG||inside) return; inside=1;
  void* bt[DEPTH+2]; int n=backtrace(bt,DEPTH+2);
  uint64_t key=1315423911u; for(int i=2;i<n;i++) key=key*31+(uint64_t)bt[i];
  pthread_mutex_lock(&mu);
  unsigned h=(unsigned)(key%NSITES);
  for(int p=0;p<NSITES;p++){ Site* s=&sites[(h+p)%NSITES]; if(s->count==0){ s->key=key; s->size=size; s->n=n-2; memcpy(s->bt,bt+2,sizeof(void*)*(n-2)); int idx=(h+p)%NSITES; s->idx=idx; for(int k=0;k<n-2;k++){ Dl_info d; if(dladdr(bt[k+2],&d)&&d.dli_fname) snprintf(names[idx][k],160,"%s 0x%lx %s",d.dli_fname,(unsigned long)((char*)bt[k+2]-(char*)d.dli_fbase),d.dli_sname?d.dli_sname:"?"); else snprintf(names[idx][k],160,"raw %p",bt[k+2]); } } if(s->key==key){ s->count++; s->bytes+=size; if(size>s->size) s->size=size; break; } }
  pthread_mutex_unlock(&mu); inside=0;
}
void* malloc(size_t n){ if(!rmalloc){ if(!rmalloc && tmpoff+n<sizeof tmpbuf){ init(); if(!rmalloc){void*p=tmpbuf+tmpoff; tmpoff+=(n+15)&~15; return p;} } } record(n); return rmalloc(n); }
void* calloc(size_t a,size_t b){ if(!rcalloc){ void*p=tmpbuf+tmpoff; tmpoff+=(a*b+15)&~15; memset(p,0,a*b); return p; } record(a*b); return rcalloc(a,b); }
void* realloc(void*p,size_t n){ init(); record(n); return rrealloc(p,n); }
int posix_memalign(void**p,size_t a,size_t n){ init(); record(n); return rpm(p,a,n); }
void* aligned_alloc(size_t a,size_t n){ init(); record(n); return raa(a,n); }
void* memalign(size_t a,size_t n){ init(); record(n); return rmemalign(a,n); }
void free(void*p){ static void (*rfree)(void*); if((char*)p>=tmpbuf && (char*)p<tmpbuf+sizeof tmpbuf) return; if(!rfree) rfree=dlsym(RTLD_NEXT,"free"); rfree(p); }
static int cmp(const void*a,const void*b){ double x=((Site*)a)->bytes,y=((Site*)b)->bytes; return x<y?1:x>y?-1:0; }
__attribute__((destructor)) static void dump(void){
  inside=1; const char* f=getenv("BIGMALLOC_OUT"); if(!f) return;
  char path[512]; snprintf(path,sizeof path,"%s.%d",f,getpid()); FILE* o=fopen(path,"w"); if(!o) return;
  qsort(sites,NSITES,sizeof(Site),cmp); double tot=0; long cnt=0; for(int i=0;i<NSITES;i++){tot+=sites[i].bytes;cnt+=sites[i].count;}
  fprintf(o,"TOTAL >=%d: %ld allocations, %.1f MB\n",BIG,cnt,tot/1e6);
  for(int i=0;i<60&&sites[i].count;i++){ Site* s=&sites[i]; fprintf(o,"## %ld allocs, max %zu B, total %.1f MB, depth %d\n",s->count,s->size,s->bytes/1e6,s->n);
    for(int k=0;k<s->n;k++) fprintf(o,"   %s\n",names[s->idx][k]); }
  fclose(o);
  { FILE* mi=fopen("/proc/self/maps","r"); char mp[600]; snprintf(mp,sizeof mp,"%s.maps",path); FILE* mo=fopen(mp,"w"); char line[1024]; while(mi&&mo&&fgets(line,sizeof line,mi)) fputs(line,mo); if(mi) fclose(mi); if(mo) fclose(mo); }
}
