// blobs.glsl: a Shadertoy-style shader. Where Whitted's tracer intersects
// rays with shapes in closed form, this one marches along the ray through a
// signed distance field ("sphere tracing"): any shape with a distance
// function works, shapes melt into each other with a smooth minimum, and the
// same march gives soft shadows. Paste it into shadertoy.com as it is, or:
//
//   raysandbox shader assets/shaders/blobs.glsl
//
// Drag with the mouse to orbit (iMouse); the annotated uniforms are controls
// in the panel (on shadertoy.com, replace them by constants).

uniform float melt = 0.45;        // @slider(0.0, 1.0, 0.01) how softly the blobs merge
uniform float speed = 1.0;        // @slider(0.0, 3.0, 0.05) animation speed
uniform vec3 blob_color = vec3(0.9, 0.35, 0.2); // @color
uniform float softness = 12.0;    // @log(2, 64) shadow penumbra: small = soft
uniform int max_steps = 96;       // @slider(16, 256) march steps per ray

// Polynomial smooth minimum (Inigo Quilez): min with a rounded seam of width k.
float smin(float a, float b, float k) {
    float h = clamp(0.5 + 0.5 * (b - a) / max(k, 1e-4), 0.0, 1.0);
    return mix(b, a, h) - k * h * (1.0 - h);
}

float blobs(vec3 p) {
    float t = iTime * speed;
    float d = length(p - vec3(0.0, 1.0, 0.0)) - 0.7;
    for (int i = 0; i < 4; i++) {
        float a = t * (0.6 + 0.17 * float(i)) + 1.57 * float(i);
        vec3 c = vec3(1.1 * cos(a), 1.0 + 0.45 * sin(1.3 * a), 1.1 * sin(a));
        d = smin(d, length(p - c) - 0.35, melt);
    }
    return d;
}

// The distance to the scene and what was hit (0 = floor, 1 = blobs).
vec2 scene(vec3 p) {
    float b = blobs(p);
    float f = p.y;
    return b < f ? vec2(b, 1.0) : vec2(f, 0.0);
}

vec3 normal_at(vec3 p) {
    vec2 e = vec2(1e-3, 0.0);
    return normalize(vec3(scene(p + e.xyy).x - scene(p - e.xyy).x,
                          scene(p + e.yxy).x - scene(p - e.yxy).x,
                          scene(p + e.yyx).x - scene(p - e.yyx).x));
}

vec2 march(vec3 o, vec3 d) {
    float t = 0.0;
    for (int i = 0; i < 256; i++) {
        if (i >= max_steps) break;
        vec2 h = scene(o + t * d);
        if (h.x < 1e-3 * t) return vec2(t, h.y);
        t += h.x;
        if (t > 40.0) break;
    }
    return vec2(-1.0, 0.0);
}

// Soft shadow: how close the shadow ray passes to the scene, relative to
// how far along it is.
float shadow(vec3 o, vec3 d) {
    float light = 1.0;
    float t = 0.02;
    for (int i = 0; i < 64; i++) {
        float h = scene(o + t * d).x;
        light = min(light, softness * h / t);
        t += clamp(h, 0.02, 0.5);
        if (light < 0.001 || t > 10.0) break;
    }
    return clamp(light, 0.0, 1.0);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    // Orbit with the mouse while a button is held (iMouse.z > 0 then).
    vec2 m = iMouse.z > 0.0 ? iMouse.xy / iResolution.xy : vec2(0.55, 0.22);
    float yaw = 6.2832 * (m.x - 0.5);
    float pitch = 0.05 + 1.2 * m.y;
    vec3 target = vec3(0.0, 0.9, 0.0);
    vec3 eye = target + 5.0 * vec3(sin(yaw) * cos(pitch), sin(pitch), cos(yaw) * cos(pitch));
    vec3 w = normalize(target - eye);
    vec3 u = normalize(cross(w, vec3(0.0, 1.0, 0.0)));
    vec3 v = cross(u, w);
    vec3 d = normalize(uv.x * u + uv.y * v + 1.8 * w);

    vec3 sky = mix(vec3(0.55, 0.65, 0.85), vec3(0.12, 0.25, 0.6), clamp(d.y * 2.0, 0.0, 1.0));
    vec3 color = sky;
    vec2 hit = march(eye, d);
    if (hit.x > 0.0) {
        vec3 p = eye + hit.x * d;
        vec3 n = normal_at(p);
        vec3 l = normalize(vec3(0.6, 0.9, 0.4));
        vec3 albedo = pow(blob_color, vec3(2.2)); // the picker shows sRGB; light is linear
        if (hit.y < 0.5) {
            vec2 cell = floor(p.xz);
            albedo = mod(cell.x + cell.y, 2.0) == 0.0 ? vec3(0.6) : vec3(0.22);
        }
        float diffuse = max(dot(n, l), 0.0) * shadow(p + 2e-3 * n, l);
        float spec = pow(max(dot(reflect(d, n), l), 0.0), 40.0) * diffuse;
        // Sky light from above, a touch of ambient occlusion from the field.
        float ao = clamp(scene(p + 0.15 * n).x / 0.15, 0.3, 1.0);
        color = albedo * (0.9 * diffuse + 0.3 * ao * (0.5 + 0.5 * n.y)) + 0.4 * spec;
        color = mix(color, sky, 1.0 - exp(-0.004 * hit.x * hit.x));
    }
    fragColor = vec4(pow(color, vec3(1.0 / 2.2)), 1.0);
}
