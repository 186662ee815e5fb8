// The unshadowed local lights through screen-space directional occlusion (ssdo, ssdo_ssgi).
// The includer includes scene.glsl (with its buffers), lights.glsl and gow_screen_space.glsl.
#ifndef GOW_SS_LIGHTS_GLSL
#define GOW_SS_LIGHTS_GLSL

// Radiance the local lights give a Lambertian surface (x, n, albedo) with no shadow ray, each
// scaled by gow_ss_visibility towards it over the directions `known` (open_bits among them;
// open fraction `open_fraction`: 1 lights everything, the ssdo 0 control).
vec3 gow_ss_local_light(vec3 x, vec3 n, vec3 albedo, uint open_bits, uint known, uint dirs, float turn,
                        float open_fraction) {
  vec3 result = vec3(0.0);
  for (uint i = 0u; i < gib_light_count(); ++i) {
    vec3 wi;
    float dist;
    vec3 e = gib_local_light(gib_lights[i], x, wi, dist);
    float c = dot(n, wi);
    if (c <= 0.0 || all(equal(e, vec3(0.0)))) continue;
    float vis = open_fraction >= 1.0 ? 1.0 : gow_ss_visibility(open_bits, known, dirs, turn, n, wi, open_fraction);
    result += albedo * (c / GIB_PI) * e * vis;
  }
  return result;
}

#endif
