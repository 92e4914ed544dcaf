#include <immintrin.h>
#include <chrono>
#include <cstdio>
#include <cstdint>
int main(){
  alignas(64) float table[256]; for(int i=0;i<256;++i) table[i]=i;
  alignas(16) uint8_t idx[64]; for(int i=0;i<64;++i) idx[i]=(i*37)%80;
  __m256 acc=_mm256_setzero_ps();
  const int N=20000000;
  auto t0=std::chrono::steady_clock::now();
  for(int n=0;n<N;++n){
    __m256i i=_mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i*)(idx+(n&7)*8)));
    acc=_mm256_add_ps(acc,_mm256_i32gather_ps(table,i,4));
  }
  auto t1=std::chrono::steady_clock::now();
  __m256 acc2=_mm256_setzero_ps();
  for(int n=0;n<N;++n){
    const uint8_t* p=idx+(n&7)*8;
    __m256 v=_mm256_set_ps(table[p[7]],table[p[6]],table[p[5]],table[p[4]],table[p[3]],table[p[2]],table[p[1]],table[p[0]]);
    acc2=_mm256_add_ps(acc2,v);
  }
  auto t2=std::chrono::steady_clock::now();
  // independent gathers (throughput)
  __m256 a0=_mm256_setzero_ps(),a1=a0,a2=a0,a3=a0;
  for(int n=0;n<N;n+=4){
    __m256i i=_mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i*)(idx+(n&7)*8)));
    a0=_mm256_add_ps(a0,_mm256_i32gather_ps(table,i,4));
    a1=_mm256_add_ps(a1,_mm256_i32gather_ps(table+1,i,4));
    a2=_mm256_add_ps(a2,_mm256_i32gather_ps(table+2,i,4));
    a3=_mm256_add_ps(a3,_mm256_i32gather_ps(table+3,i,4));
  }
  auto t3=std::chrono::steady_clock::now();
  float o[8]; _mm256_storeu_ps(o,_mm256_add_ps(_mm256_add_ps(acc,acc2),_mm256_add_ps(_mm256_add_ps(a0,a1),_mm256_add_ps(a2,a3))));
  auto ns=[&](auto a,auto b){return std::chrono::duration<double,std::nano>(b-a).count()/N;};
  printf("gather chain %.2f ns, scalar %.2f ns, gather indep %.2f ns  (%f)\n",ns(t0,t1),ns(t1,t2),ns(t2,t3),o[0]);
}
