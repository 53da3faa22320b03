// glTF's metallic-roughness lighting (glTF 2.0 specification, Appendix B) under the crowd's lights: a key
// light (a direction and a colour, weighted 1 - ambient) and a hemisphere (sky above, ground below, weighted
// ambient). Included by shaders/lit_mesh.frag (per pixel) and shaders/lit_mesh.vert (VERTEX_LIT, per vertex).
//
// Like the diffuse lighting of those shaders, the light is in units where a white diffuse surface facing the
// key light reflects the key's colour (the BRDF times pi), so a rough dielectric looks as the diffuse model
// shows it, less the little its Fresnel reflection takes.
// - Key light: ((1 - F) c_diff + pi D V F) (N.L), with c_diff = base (1 - metallic), F0 = mix(0.04, base,
//   metallic), F Schlick's Fresnel at V.H, D the GGX (Trowbridge-Reitz) distribution and V the height-correlated
//   Smith visibility, alpha = roughness^2.
// - Hemisphere: c_diff (1 - E) hemisphere(N) + E hemisphere(R) blurred towards hemisphere(N) by alpha, with E the
//   split-sum environment BRDF in Karis's analytic fit ("Physically Based Shading on Mobile", 2014) and R the
//   mirror direction: the hemisphere is the whole environment, so a metal reflects the sky and the ground.
// Under an even white sky (the impostor bake's albedo pass: ambient 1, sky = ground = white) the result is
// c_diff (1 - E) + E, the surface's colour in a white furnace.

const float kPi = 3.14159265;
// Roughness below this is lit as this by the key light: alpha^2 stays above 4e-6, so a mirror's highlight from
// a light that is a direction (no size) keeps a finite peak a float holds. The hemisphere uses the roughness as it is.
const float kMinRoughness = 0.045;

// Karis's analytic fit of the split-sum environment BRDF: the share of an even environment a surface of
// reflectance f0 and `roughness` reflects at N.V = nv.
vec3 pbr_environment_brdf(vec3 f0, float roughness, float nv) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    const vec4 r = roughness * c0 + c1;
    const float a004 = min(r.x * r.x, exp2(-9.28 * nv)) * r.x + r.y;
    const vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
    return f0 * ab.x + ab.y;
}

// The light a surface of display-encoded `base` colour, `metallic` and `roughness` (each in [0, 1]) reflects
// towards the camera: unit normal n, unit direction to the camera v, unit direction to the key light l, the
// hemisphere's weight `ambient` (its share of the light, times any occlusion) and the key light's `key_weight`
// (1 - the share before occlusion), with the key's, the sky's and the ground's colours.
vec3 pbr_light(vec3 base, float metallic, float roughness, vec3 n, vec3 v, vec3 l, float ambient, float key_weight, vec3 key, vec3 sky,
               vec3 ground) {
    const float r = clamp(roughness, 0.0, 1.0);
    const float a = r * r;
    const float rk = max(r, kMinRoughness);  // the key light's
    const float a2 = rk * rk * rk * rk;
    const vec3 c_diff = base * (1.0 - metallic);
    const vec3 f0 = mix(vec3(0.04), base, metallic);
    const float nv = clamp(dot(n, v), 1e-4, 1.0);
    // Key light.
    const float nl = max(dot(n, l), 0.0);
    vec3 key_term = vec3(0.0);
    if (nl > 0.0) {
        const vec3 h = normalize(l + v);
        const float nh = max(dot(n, h), 0.0);
        const float vh = max(dot(v, h), 0.0);
        const vec3 f = f0 + (1.0 - f0) * pow(1.0 - vh, 5.0);
        const float q = nh * nh * (a2 - 1.0) + 1.0;
        const float d = a2 / (kPi * q * q);
        const float vis = 0.5 / (nl * sqrt(nv * nv * (1.0 - a2) + a2) + nv * sqrt(nl * nl * (1.0 - a2) + a2));
        key_term = ((1.0 - f) * c_diff + kPi * d * vis * f) * nl;
    }
    // Hemisphere.
    const vec3 e = pbr_environment_brdf(f0, r, nv);
    const vec3 reflected = reflect(-v, n);
    const vec3 hemi_n = mix(ground, sky, 0.5 + 0.5 * n.y);
    const vec3 hemi_r = mix(ground, sky, 0.5 + 0.5 * clamp(reflected.y, -1.0, 1.0));
    const vec3 ambient_term = c_diff * (1.0 - e) * hemi_n + e * mix(hemi_r, hemi_n, a);
    return ambient * ambient_term + key_weight * key * key_term;
}
