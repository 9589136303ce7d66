// Calls every function of shaders/sphbasis.glsl so glslang compiles each one; included after
// "#version" and "#include <sphbasis.glsl>" by validate_glsl450.comp and validate_es310.comp.
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { float v[]; } out_buf;

void main()
{
    vec3 d = normalize(vec3(0.3, -0.4, 0.5));
    float s1[1]; sphbasis_sh_eval1(d, s1); out_buf.v[0] = s1[0];
    float s2[4]; sphbasis_sh_eval2(d, s2); out_buf.v[1] = s2[3];
    float s3[9]; sphbasis_sh_eval3(d, s3); out_buf.v[2] = s3[8];
    float s4[16]; sphbasis_sh_eval4(d, s4); out_buf.v[3] = s4[15];
    float s5[25]; sphbasis_sh_eval5(d, s5); out_buf.v[4] = s5[24];
    float s6[36]; sphbasis_sh_eval6(d, s6); out_buf.v[5] = s6[35];
    float s7[49]; sphbasis_sh_eval7(d, s7); out_buf.v[6] = s7[48];
    float s8[64]; sphbasis_sh_eval8(d, s8); out_buf.v[7] = s8[63];
    vec3 L[9];
    for (int i = 0; i < 9; ++i) L[i] = vec3(s3[i], 2.0 * s3[i], 0.5);
    vec3 e = sphbasis_sh_irradiance(L, d);
    out_buf.v[8] = e.x + e.y + e.z;
}
