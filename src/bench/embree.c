/* embree.c: Intel Embree 3 as the external anchor of `raysandbox bench
 * --throughput` (docs/performance.md, "Rays per second"): one triangle mesh,
 * single rays through rtcIntersect1. Compiled only with the cargo feature
 * `embree` (build.rs), which needs libembree-dev. */
#include <embree3/rtcore.h>
#include <math.h>
#include <stdlib.h>

struct rs_embree {
    RTCDevice device;
    RTCScene scene;
};

/* The mesh's world-space vertices (x, y, z per vertex) and triangles (three
 * vertex indices each), built with Embree's default (high quality off,
 * BVH over triangles). NULL on failure. */
struct rs_embree *rs_embree_new(const float *vertices, size_t vertex_count,
                                const unsigned *indices, size_t triangle_count) {
    struct rs_embree *e = calloc(1, sizeof *e);
    if (!e) return NULL;
    e->device = rtcNewDevice("threads=2");
    if (!e->device) { free(e); return NULL; }
    e->scene = rtcNewScene(e->device);
    RTCGeometry g = rtcNewGeometry(e->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), vertex_count);
    unsigned *t = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                          3 * sizeof(unsigned), triangle_count);
    if (!v || !t) { rtcReleaseGeometry(g); rtcReleaseScene(e->scene); rtcReleaseDevice(e->device); free(e); return NULL; }
    for (size_t i = 0; i < 3 * vertex_count; i++) v[i] = vertices[i];
    for (size_t i = 0; i < 3 * triangle_count; i++) t[i] = indices[i];
    rtcCommitGeometry(g);
    rtcAttachGeometry(e->scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(e->scene);
    return e;
}

/* Traces rays (origin x, y, z, direction x, y, z per ray) one at a time;
 * hits[i] = 1 where ray i hits a triangle at 0 <= t, else 0. */
void rs_embree_trace(const struct rs_embree *e, const float *rays, size_t count,
                     unsigned char *hits) {
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (size_t i = 0; i < count; i++) {
        const float *r = rays + 6 * i;
        struct RTCRayHit rh;
        rh.ray.org_x = r[0]; rh.ray.org_y = r[1]; rh.ray.org_z = r[2];
        rh.ray.dir_x = r[3]; rh.ray.dir_y = r[4]; rh.ray.dir_z = r[5];
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = INFINITY;
        rh.ray.time = 0.0f;
        rh.ray.mask = 0xffffffffu;
        rh.ray.id = 0;
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(e->scene, &context, &rh);
        hits[i] = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
}

void rs_embree_free(struct rs_embree *e) {
    if (!e) return;
    rtcReleaseScene(e->scene);
    rtcReleaseDevice(e->device);
    free(e);
}
