// Calls every function of shaders/sphbasis.hlsl and sphbasis_render.hlsl so glslang's HLSL front end compiles each one.
#include "sphbasis.hlsl"
#include "sphbasis_render.hlsl"

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
    float h4[4]; sphbasis_hbasis4_eval(d, h4); out_buf[9] = h4[2];
    float h6[6]; sphbasis_hbasis6_eval(d, h6); out_buf[10] = h6[5];
    float m4[4]; sphbasis_hbasis_mod4_eval(d, m4); out_buf[11] = m4[2];
    float m6[6]; sphbasis_hbasis_mod6_eval(d, m6); out_buf[12] = m6[5];
    float t3[3]; sphbasis_hl2_eval(d, t3); out_buf[13] = t3[1];
    float3 c6[6];
    for (int i = 0; i < 6; ++i) c6[i] = float3(h6[i], 0.5f, -0.25f);
    float3 c4[4];
    for (int i = 0; i < 4; ++i) c4[i] = c6[i];
    float3 c3[3];
    for (int i = 0; i < 3; ++i) c3[i] = c6[i];
    float3 f = sphbasis_hbasis4_eval_sum(c4, d) + sphbasis_hbasis6_eval_sum(c6, d)
        + sphbasis_hbasis_mod4_eval_sum(c4, d) + sphbasis_hbasis_mod6_eval_sum(c6, d)
        + sphbasis_hl2_eval_sum(c3, d);
    out_buf[14] = f.x + f.y + f.z;
    out_buf[15] = sphbasis_clamped_cosine(4) + sphbasis_clamped_cosine_a6;
    float3 mh[6]; sphbasis_sh_to_hbasis_mod6(L, mh);
    f = sphbasis_hbasis_mod6_irradiance(mh, d) + sphbasis_hbasis_mod4_irradiance(c4, d)
        + sphbasis_sh_irradiance_hbasis_mod6(L, d);
    out_buf[16] = f.x + f.y + f.z;
    out_buf[17] = sphbasis_toksvig_factor(0.9f, 32.0f) + sphbasis_toksvig_specular(0.8f, 0.9f, 32.0f)
        + sphbasis_toksvig_specular_from_dots(0.8f, 0.81f, 32.0f);
    float2 q0 = float2(0.3f, 0.8f);
    int face;
    float2 q = sphbasis_octahedral_to_square(d) + sphbasis_cube_to_square(d, face)
        + sphbasis_paraboloid_to_square(d) + sphbasis_dual_paraboloid_direction_to_uv(d, 16, face)
        + sphbasis_square_to_uniform_disk_concentric(q0)
        + sphbasis_uniform_disk_to_square_concentric(d.xy);
    float3 r = sphbasis_square_to_octahedral(q0) + sphbasis_square_to_cube(face, q0)
        + sphbasis_square_to_paraboloid(q0) + sphbasis_dual_paraboloid_uv_to_direction(1, q0, 16);
    out_buf[18] = q.x + q.y + r.x + r.y + r.z + float(face);
    float hs[64]; sphbasis_hsh_eval(d, 8, hs);
    float mk[64]; sphbasis_makhotkin_eval(d, 8, mk);
    float zk[36]; sphbasis_zernike_eval(d, 8, zk);
    out_buf[19] = hs[63] + mk[63] + zk[35];
    int idx[4]; float wt[4]; sphbasis_cube_footprint(d, 16, idx, wt);
    int seam = sphbasis_cube_seam_texel(0, -1, 3, 16);
    float vis[36]; float3 t36[36];
    for (int i = 0; i < 36; ++i) { vis[i] = zk[i]; t36[i] = float3(hs[i], mk[i], 1.0f); }
    float3 g = sphbasis_lxh_shade(vis, t36, 16, float3(0.5f, 0.5f, 0.5f));
    float3 ev[SPHBASIS_MAX_VECTORS]; float ew[SPHBASIS_MAX_VECTORS];
    for (int i = 0; i < SPHBASIS_MAX_VECTORS; ++i) { ev[i] = float3(hs[i], 0.5f, 1.0f); ew[i] = mk[i]; }
    g += sphbasis_pca_exit(float3(1.0f, 1.0f, 1.0f), ev, ew, 8) * float(sphbasis_cpca_cluster(2.5f, 4));
    float3 u = sphbasis_normal_basis_tangent(d, float3(1.0f, 0.0f, 0.0f), float3(0.0f, 1.0f, 0.0f),
        float3(0.0f, 0.0f, 1.0f));
    float v54[54]; for (int i = 0; i < 54; ++i) v54[i] = hs[i];
    float p6[6]; sphbasis_normal_basis_weights(u, v54, 6, p6);
    float3 gl6[6]; for (int i = 0; i < 6; ++i) gl6[i] = c6[i];
    g += sphbasis_prt_normalmap_svd(p6, gl6, 4, float3(0.8f, 0.8f, 0.8f));
    g += sphbasis_prt_ratio(float3(0.5f, 0.5f, 0.5f), L, d, u, float3(0.7f, 0.7f, 0.7f));
    int pi8[8]; float pw[8]; bool ins[8];
    sphbasis_probe_weights(d, float3(-1.0f, -1.0f, -1.0f), float3(1.0f, 1.0f, 1.0f), int3(4, 3, 1), pi8, pw);
    for (int i = 0; i < 8; ++i) ins[i] = pi8[i] == 2;
    bool valid = sphbasis_probe_weights_valid(pw, ins);
    g += sphbasis_volume_shade(L, d, float3(pw[0], pw[7], valid ? 1.0f : 0.0f));
    out_buf[20] = g.x + g.y + g.z + wt[0] + float(idx[3] + seam);
    float ac[6]; sphbasis_ambient_cube_eval(d, ac);
    float ac5[5]; sphbasis_ambient_cube5_eval(d, ac5);
    float dc[12]; sphbasis_ambient_dice_eval(d, dc);
    float3 c12[12]; for (int i = 0; i < 12; ++i) c12[i] = float3(dc[i], 0.5f, s4[i]);
    float3 c9[9]; for (int i = 0; i < 9; ++i) c9[i] = c12[i];
    float3 c5[5]; for (int i = 0; i < 5; ++i) c5[i] = c12[i];
    float3 k = sphbasis_ambient_cube_eval_sum(c6, d) + sphbasis_ambient_cube5_eval_sum(c5, d)
        + sphbasis_ambient_dice_eval_sum(c12, d);
    float db[36]; sphbasis_ambient_dice_bezier_eval(d, db);
    float dl[12]; sphbasis_ambient_dice_linear_eval(d, dl);
    float3 c36[36]; for (int i = 0; i < 36; ++i) c36[i] = float3(db[i], dl[i / 3], 0.5f);
    k += sphbasis_ambient_dice_bezier_eval_sum(c36, d) + sphbasis_ambient_dice_linear_eval_sum(c12, d);
    float g5[5]; sphbasis_sg5_eval(d, g5);
    float g6[6]; sphbasis_sg6_eval(d, g6);
    float g9[9]; sphbasis_sg9_eval(d, g9);
    float g12[12]; sphbasis_sg12_eval(d, g12);
    k += sphbasis_sg5_eval_sum(c5, d) + sphbasis_sg6_eval_sum(c6, d) + sphbasis_sg9_eval_sum(c9, d)
        + sphbasis_sg12_eval_sum(c12, d) + sphbasis_sg5_irradiance(c5, d)
        + sphbasis_sg6_irradiance(c6, d) + sphbasis_sg9_irradiance(c9, d)
        + sphbasis_sg12_irradiance(c12, d);
    float z5[5]; for (int i = 0; i < 5; ++i) z5[i] = s4[i];
    float z4[4]; for (int i = 0; i < 4; ++i) z4[i] = s4[i];
    out_buf[21] = k.x + k.y + k.z + ac[5] + ac5[4] + g5[4] + g6[5] + g9[8] + g12[11]
        + sphbasis_sg_eval(d, 5.5f, 2.0f, d.zxy) + sphbasis_sg_irradiance_fitted(d, 5.5f, 2.0f, d.zxy)
        + sphbasis_zh3_eval(z5, d) + sphbasis_zh3_hallucinate(z4) + sphbasis_zh3_hallucinate_eval(z4, d)
        + sphbasis_sh_l1_nonlinear_eval(z4, d) + sphbasis_ambient_dice_axis_a + sphbasis_sg9_sharpness
        + sphbasis_sg12_axis[3].y;
}
