// Calls every function of shaders/sphbasis.hlsl so glslang's HLSL front end compiles each one.
#include "sphbasis.hlsl"

RWStructuredBuffer<float> out_buf : register(u0);

[numthreads(1, 1, 1)]
void main()
{
    float3 d = normalize(float3(0.3f, -0.4f, 0.5f));
    float s1[1]; sphbasis_sh_eval1(d, s1); out_buf[0] = s1[0];
    float s2[4]; sphbasis_sh_eval2(d, s2); out_buf[1] = s2[3];
    float s3[9]; sphbasis_sh_eval3(d, s3); out_buf[2] = s3[8];
    float s4[16]; sphbasis_sh_eval4(d, s4); out_buf[3] = s4[15];
    float s5[25]; sphbasis_sh_eval5(d, s5); out_buf[4] = s5[24];
    float s6[36]; sphbasis_sh_eval6(d, s6); out_buf[5] = s6[35];
    float s7[49]; sphbasis_sh_eval7(d, s7); out_buf[6] = s7[48];
    float s8[64]; sphbasis_sh_eval8(d, s8); out_buf[7] = s8[63];
    float3 L[9];
    for (int i = 0; i < 9; ++i) L[i] = float3(s3[i], 2.0f * s3[i], 0.5f);
    float3 e = sphbasis_sh_irradiance(L, d);
    out_buf[8] = e.x + e.y + e.z;
}
