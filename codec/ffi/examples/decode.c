/* A viewer-side use of the swm C interface: read a .swm file, decode it
 * both ways (library-owned arrays, then caller-owned buffers sized by
 * swm_decoded_len), and print the counts.
 *
 *     decode FILE.swm [--sharpen | --no-sharpen] [--bend N] [--normals] [--attributes]
 *
 * Without --sharpen, --no-sharpen or --bend, the file's post-processing
 * hint decides (the options' default, -1).
 *
 * Prints "vertices V triangles T" and exits 0, or prints
 * "decode: error N: MESSAGE" and exits 1. With --attributes it also
 * decodes the attribute streams (swm_decode_attributed: per vertex, the
 * mesh split at seams) and prints "split vertices V streams S", then
 * "stream KIND SET DIMS" for each. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swm.h"

static unsigned char *read_file(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char *buf = NULL;
    size_t cap = 0, n = 0;
    for (;;) {
        if (n == cap) {
            cap = cap ? 2 * cap : 1 << 16;
            unsigned char *grown = realloc(buf, cap);
            if (!grown) { free(buf); fclose(f); return NULL; }
            buf = grown;
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0) break;
    }
    fclose(f);
    *len = n;
    return buf;
}

static int fail(int code) {
    fprintf(stderr, "decode: error %d: %s\n", code, swm_last_error());
    return 1;
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: decode FILE.swm [--sharpen | --no-sharpen] [--bend N] [--normals] [--attributes]\n");
        return 2;
    }
    swm_decode_options opts = swm_decode_options_default();
    bool attributes = false;
    for (int i = 2; i < argc; i++) {
        if (!strcmp(argv[i], "--sharpen")) opts.sharpen = 1;
        else if (!strcmp(argv[i], "--no-sharpen")) opts.sharpen = 0;
        else if (!strcmp(argv[i], "--normals")) opts.normals = true;
        else if (!strcmp(argv[i], "--attributes")) attributes = true;
        else if (!strcmp(argv[i], "--bend") && i + 1 < argc) opts.bend_steps = (int32_t)atoi(argv[++i]);
    }
    size_t len = 0;
    unsigned char *data = read_file(argv[1], &len);
    if (!data) { fprintf(stderr, "decode: cannot read %s\n", argv[1]); return 1; }

    /* 1. The library allocates; swm_mesh_free releases. */
    swm_mesh mesh;
    int rc = swm_decode_with(data, len, &opts, &mesh);
    if (rc != SWM_OK) { free(data); return fail(rc); }
    if (opts.normals) {
        for (size_t v = 0; v < mesh.vertex_count; v++) {
            const float *n = mesh.normals + 3 * v;
            float l = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
            if (l < 0.999f || l > 1.001f) fprintf(stderr, "decode: normal %zu has length^2 %f\n", v, l);
        }
    }

    /* With the attribute streams: one vertex per distinct position and
     * values, so every stream is a vertex buffer beside the positions. */
    swm_attributed_mesh split;
    memset(&split, 0, sizeof split); /* zeroed: freeing it is harmless */
    if (attributes) {
        rc = swm_decode_attributed(data, len, &opts, &split);
        if (rc != SWM_OK) { swm_mesh_free(&mesh); free(data); return fail(rc); }
        for (size_t s = 0; s < split.attribute_count; s++) {
            const swm_attribute *a = &split.attributes[s];
            if (a->dims < 1 || a->dims > 4 || (split.mesh.vertex_count && !a->values))
                fprintf(stderr, "decode: stream %zu is malformed\n", s);
        }
    }

    /* 2. The caller allocates, from the bounds. */
    swm_decoded_size bound, got;
    rc = swm_decoded_len(data, len, &opts, &bound);
    if (rc != SWM_OK) { swm_attributed_mesh_free(&split); swm_mesh_free(&mesh); free(data); return fail(rc); }
    float *positions = malloc(3 * bound.vertex_count * sizeof(float) + 1);
    uint32_t *indices = malloc(3 * bound.triangle_count * sizeof(uint32_t) + 1);
    rc = swm_decode_into(data, len, &opts, positions, 3 * bound.vertex_count,
                         indices, 3 * bound.triangle_count, &got);
    int same = rc == SWM_OK && got.vertex_count == mesh.vertex_count &&
               got.triangle_count == mesh.triangle_count &&
               !memcmp(positions, mesh.positions, 3 * got.vertex_count * sizeof(float)) &&
               !memcmp(indices, mesh.indices, 3 * got.triangle_count * sizeof(uint32_t));
    free(positions);
    free(indices);
    free(data);
    if (rc != SWM_OK) { swm_attributed_mesh_free(&split); swm_mesh_free(&mesh); return fail(rc); }
    if (!same) {
        fprintf(stderr, "decode: the two decodes differ\n");
        swm_attributed_mesh_free(&split);
        swm_mesh_free(&mesh);
        return 1;
    }

    printf("vertices %zu triangles %zu\n", mesh.vertex_count, mesh.triangle_count);
    if (attributes) {
        printf("split vertices %zu streams %zu\n", split.mesh.vertex_count, split.attribute_count);
        for (size_t s = 0; s < split.attribute_count; s++) {
            const swm_attribute *a = &split.attributes[s];
            printf("stream %u %u %u\n", (unsigned)a->kind, (unsigned)a->set, (unsigned)a->dims);
        }
    }
    swm_attributed_mesh_free(&split);
    swm_mesh_free(&mesh);
    swm_mesh_free(&mesh); /* freeing twice is harmless: the first call zeroed it */
    return 0;
}
