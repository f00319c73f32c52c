// bedlam — VTK XML PolyData writer (appended raw binary) and .pvd collections.
#define _POSIX_C_SOURCE 200809L // getline
#include "io/vtk.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file.h"

// Positions are written straight from memory as a 3-component Float64 array.
_Static_assert(sizeof(bdl_vec3) == 3 * sizeof(double), "bdl_vec3 must be three packed doubles");

/// Elements converted or generated per fwrite call, to bound scratch memory for any n.
enum { CHUNK_ELEMENTS = 4096 };

/// One appended block as described in the XML header: where it starts and what it holds.
typedef struct block {
    const char *name;
    const char *type_name;
    int components;
    size_t element_size;
    uint64_t count; ///< elements, i.e. points * components
} block;

static int host_is_little_endian(void)
{
    const uint16_t probe = 1;
    unsigned char first;
    memcpy(&first, &probe, 1);
    return first == 1;
}

/// Writes `count` elements of `element_size` bytes in little-endian order.
static int write_little_endian(FILE *file, const void *data, size_t element_size, uint64_t count)
{
    if (count == 0)
        return 1;
    if (host_is_little_endian())
        return fwrite(data, element_size, (size_t)count, file) == (size_t)count;
    unsigned char buffer[CHUNK_ELEMENTS * 8];
    const unsigned char *source = data;
    while (count > 0) {
        size_t chunk = count < CHUNK_ELEMENTS ? (size_t)count : CHUNK_ELEMENTS;
        for (size_t i = 0; i < chunk; ++i)
            for (size_t b = 0; b < element_size; ++b)
                buffer[i * element_size + b] = source[i * element_size + element_size - 1 - b];
        if (fwrite(buffer, element_size, chunk, file) != chunk)
            return 0;
        source += chunk * element_size;
        count -= chunk;
    }
    return 1;
}

static int write_block_header(FILE *file, uint64_t byte_count)
{
    return write_little_endian(file, &byte_count, sizeof byte_count, 1);
}

/// Writes the Int64 sequence first, first + 1, ... (vertex connectivity and offsets).
static int write_int64_sequence(FILE *file, int64_t first, uint64_t count)
{
    int64_t buffer[CHUNK_ELEMENTS];
    if (!write_block_header(file, count * sizeof(int64_t)))
        return 0;
    while (count > 0) {
        size_t chunk = count < CHUNK_ELEMENTS ? (size_t)count : CHUNK_ELEMENTS;
        for (size_t i = 0; i < chunk; ++i)
            buffer[i] = first + (int64_t)i;
        if (!write_little_endian(file, buffer, sizeof(int64_t), chunk))
            return 0;
        first += (int64_t)chunk;
        count -= chunk;
    }
    return 1;
}

/// Writes `text` with the five XML special characters escaped, for attribute values.
static void write_xml_escaped(FILE *file, const char *text)
{
    for (; *text; ++text) {
        switch (*text) {
        case '&':
            fputs("&amp;", file);
            break;
        case '<':
            fputs("&lt;", file);
            break;
        case '>':
            fputs("&gt;", file);
            break;
        case '"':
            fputs("&quot;", file);
            break;
        case '\'':
            fputs("&apos;", file);
            break;
        default:
            fputc(*text, file);
            break;
        }
    }
}

/// Writes one DataArray element and advances `offset` past its appended block.
static void write_data_array_tag(FILE *file, const block *b, uint64_t *offset)
{
    fprintf(file, "        <DataArray type=\"%s\" Name=\"", b->type_name);
    write_xml_escaped(file, b->name);
    fprintf(file, "\" NumberOfComponents=\"%d\" format=\"appended\" offset=\"%llu\"/>\n",
            b->components, (unsigned long long)*offset);
    *offset += sizeof(uint64_t) + b->count * b->element_size;
}

static int arrays_are_valid(long n, const bdl_vec3 *positions, const bdl_vtk_array *arrays,
                            int array_count)
{
    if (n < 0 || array_count < 0 || (n > 0 && !positions) || (array_count > 0 && !arrays))
        return 0;
    for (int i = 0; i < array_count; ++i) {
        const bdl_vtk_array *a = &arrays[i];
        if (!a->name || a->components < 1 || (n > 0 && !a->data))
            return 0;
        if (a->type != BDL_VTK_FLOAT64 && a->type != BDL_VTK_INT32)
            return 0;
    }
    return 1;
}

static block block_for_array(const bdl_vtk_array *a, uint64_t n)
{
    int is_double = a->type == BDL_VTK_FLOAT64;
    return (block){a->name, is_double ? "Float64" : "Int32", a->components,
                   is_double ? sizeof(double) : sizeof(int32_t), n * (uint64_t)a->components};
}

/// The XML part, up to and including the '_' that starts the appended data. Block order here
/// must match write_payload: point arrays, points, connectivity, offsets.
static void write_xml_header(FILE *file, uint64_t n, const bdl_vtk_array *arrays, int array_count)
{
    uint64_t offset = 0;
    fputs("<?xml version=\"1.0\"?>\n"
          "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
          "header_type=\"UInt64\">\n"
          "  <PolyData>\n",
          file);
    fprintf(file,
            "    <Piece NumberOfPoints=\"%llu\" NumberOfVerts=\"%llu\" NumberOfLines=\"0\" "
            "NumberOfStrips=\"0\" "
            "NumberOfPolys=\"0\">\n",
            (unsigned long long)n, (unsigned long long)n);
    fputs("      <PointData>\n", file);
    for (int i = 0; i < array_count; ++i) {
        block b = block_for_array(&arrays[i], n);
        write_data_array_tag(file, &b, &offset);
    }
    fputs("      </PointData>\n      <Points>\n", file);
    block points = {"Points", "Float64", 3, sizeof(double), 3 * n};
    write_data_array_tag(file, &points, &offset);
    fputs("      </Points>\n      <Verts>\n", file);
    block connectivity = {"connectivity", "Int64", 1, sizeof(int64_t), n};
    block offsets = {"offsets", "Int64", 1, sizeof(int64_t), n};
    write_data_array_tag(file, &connectivity, &offset);
    write_data_array_tag(file, &offsets, &offset);
    fputs("      </Verts>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _",
          file);
}

static int write_array_block(FILE *file, const void *data, size_t element_size, uint64_t count)
{
    return write_block_header(file, count * element_size) &&
           write_little_endian(file, data, element_size, count);
}

static int write_payload(FILE *file, uint64_t n, const bdl_vec3 *positions,
                         const bdl_vtk_array *arrays, int array_count)
{
    for (int i = 0; i < array_count; ++i) {
        block b = block_for_array(&arrays[i], n);
        if (!write_array_block(file, arrays[i].data, b.element_size, b.count))
            return 0;
    }
    if (!write_array_block(file, positions, sizeof(double), 3 * n))
        return 0;
    // Vertex cell i holds point i; VTK XML offsets are the end of each cell's connectivity.
    return write_int64_sequence(file, 0, n) && write_int64_sequence(file, 1, n);
}

bdl_result bdl_vtp_write(const char *path, long n, const bdl_vec3 *positions,
                         const bdl_vtk_array *arrays, int array_count)
{
    if (!arrays_are_valid(n, positions, arrays, array_count))
        return BDL_ERR_IO;
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open(&af, path);
    if (r != BDL_OK)
        return r;
    write_xml_header(af.file, (uint64_t)n, arrays, array_count);
    int ok = write_payload(af.file, (uint64_t)n, positions, arrays, array_count);
    ok = ok && fputs("\n  </AppendedData>\n</VTKFile>\n", af.file) >= 0;
    if (!ok) {
        bdl_atomic_abort(&af);
        return BDL_ERR_IO;
    }
    return bdl_atomic_commit(&af);
}

/// One DataSet line of a collection.
typedef struct pvd_entry {
    double time;
    char *file;
} pvd_entry;

struct bdl_pvd {
    char *path;
    pvd_entry *entries;
    long count;
    long capacity;
};

static char *copy_string(const char *text)
{
    size_t length = strlen(text) + 1;
    char *copy = malloc(length);
    if (copy)
        memcpy(copy, text, length);
    return copy;
}

static bdl_result pvd_write(const bdl_pvd *pvd)
{
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open(&af, pvd->path);
    if (r != BDL_OK)
        return r;
    FILE *file = af.file;
    fputs("<?xml version=\"1.0\"?>\n"
          "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
          "  <Collection>\n",
          file);
    for (long i = 0; i < pvd->count; ++i) {
        fprintf(file, "    <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" file=\"",
                pvd->entries[i].time);
        write_xml_escaped(file, pvd->entries[i].file);
        fputs("\"/>\n", file);
    }
    fputs("  </Collection>\n</VTKFile>\n", file);
    // Write errors stick in the stream; bdl_atomic_commit checks them.
    return bdl_atomic_commit(&af);
}

bdl_pvd *bdl_pvd_create(const char *pvd_path)
{
    bdl_pvd *pvd = calloc(1, sizeof *pvd);
    if (!pvd)
        return NULL;
    pvd->path = copy_string(pvd_path);
    if (!pvd->path || pvd_write(pvd) != BDL_OK) {
        bdl_pvd_destroy(pvd);
        return NULL;
    }
    return pvd;
}

static bdl_result pvd_reserve(bdl_pvd *pvd)
{
    if (pvd->count < pvd->capacity)
        return BDL_OK;
    long capacity = pvd->capacity > 0 ? 2 * pvd->capacity : 64;
    pvd_entry *entries = realloc(pvd->entries, (size_t)capacity * sizeof *entries);
    if (!entries)
        return BDL_ERR_NOMEM;
    pvd->entries = entries;
    pvd->capacity = capacity;
    return BDL_OK;
}

bdl_result bdl_pvd_add(bdl_pvd *pvd, double time, const char *relative_file)
{
    if (!pvd || !relative_file)
        return BDL_ERR_IO;
    if (pvd_reserve(pvd) != BDL_OK)
        return BDL_ERR_NOMEM;
    char *file = copy_string(relative_file);
    if (!file)
        return BDL_ERR_NOMEM;
    pvd->entries[pvd->count++] = (pvd_entry){time, file};
    return pvd_write(pvd);
}

/// The value of attribute `name` (`name="..."`) in `line`, with the five XML entities undone,
/// into `out`; 0 when the line has no such attribute or it does not fit.
static int xml_attribute(const char *line, const char *name, char *out, size_t len)
{
    char key[32];
    snprintf(key, sizeof key, " %s=\"", name);
    const char *v = strstr(line, key);
    if (!v)
        return 0;
    v += strlen(key);
    static const char *const entities[][2] = {
        {"&amp;", "&"}, {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&apos;", "'"}};
    size_t n = 0;
    while (*v && *v != '"' && n + 1 < len) {
        int matched = 0;
        for (int k = 0; k < 5 && !matched; ++k)
            if (strncmp(v, entities[k][0], strlen(entities[k][0])) == 0) {
                out[n++] = entities[k][1][0];
                v += strlen(entities[k][0]);
                matched = 1;
            }
        if (!matched)
            out[n++] = *v++;
    }
    out[n] = '\0';
    return *v == '"';
}

/// Appends the entries of an existing collection file with times <= t_keep to `pvd`.
static bdl_result read_entries(bdl_pvd *pvd, FILE *in, double t_keep)
{
    char *line = NULL, time_text[64], file[1024];
    size_t capacity = 0;
    bdl_result r = BDL_OK;
    while (r == BDL_OK && getline(&line, &capacity, in) >= 0) {
        if (!strstr(line, "<DataSet") || !xml_attribute(line, "timestep", time_text, 64) ||
            !xml_attribute(line, "file", file, sizeof file))
            continue;
        char *end;
        const double time = strtod(time_text, &end);
        if (end == time_text || *end != '\0' || !(time <= t_keep))
            continue;
        char *copy = copy_string(file);
        if (!copy || pvd_reserve(pvd) != BDL_OK) {
            free(copy);
            r = BDL_ERR_NOMEM;
            break;
        }
        pvd->entries[pvd->count++] = (pvd_entry){time, copy};
    }
    free(line);
    return r;
}

bdl_pvd *bdl_pvd_continue(const char *pvd_path, double t_keep)
{
    bdl_pvd *pvd = calloc(1, sizeof *pvd);
    if (!pvd || !(pvd->path = copy_string(pvd_path))) {
        bdl_pvd_destroy(pvd);
        return NULL;
    }
    char why[256];
    FILE *in = bdl_open_regular(pvd_path, why, sizeof why); // none yet: an empty collection
    bdl_result r = in ? read_entries(pvd, in, t_keep) : BDL_OK;
    if (in)
        fclose(in);
    if (r != BDL_OK || pvd_write(pvd) != BDL_OK) {
        bdl_pvd_destroy(pvd);
        return NULL;
    }
    return pvd;
}

bdl_pvd *bdl_pvd_read(const char *pvd_path, char *why, size_t why_len)
{
    bdl_pvd *pvd = calloc(1, sizeof *pvd);
    if (!pvd || !(pvd->path = copy_string(pvd_path))) {
        snprintf(why, why_len, "out of memory");
        bdl_pvd_destroy(pvd);
        return NULL;
    }
    FILE *in = bdl_open_regular(pvd_path, why, why_len);
    if (!in || read_entries(pvd, in, INFINITY) != BDL_OK) {
        if (in) {
            fclose(in);
            snprintf(why, why_len, "out of memory");
        }
        bdl_pvd_destroy(pvd);
        return NULL;
    }
    fclose(in);
    return pvd;
}

long bdl_pvd_count(const bdl_pvd *pvd) { return pvd->count; }

const char *bdl_pvd_file(const bdl_pvd *pvd, long k, double *time)
{
    *time = pvd->entries[k].time;
    return pvd->entries[k].file;
}

bdl_result bdl_vtp_open(const char *path, bdl_vtp_file *f, char *why, size_t why_len)
{
    *f = (bdl_vtp_file){0};
    if (bdl_check_regular_file(path, NULL, why, why_len) != BDL_OK)
        return BDL_ERR_IO;
    f->data = bdl_read_file(path, &f->size);
    if (!f->data) {
        snprintf(why, why_len, "cannot be read: %s", strerror(errno));
        return BDL_ERR_IO;
    }
    const char *piece = strstr(f->data, "<Piece ");
    const char *app = strstr(f->data, "<AppendedData encoding=\"raw\">");
    const char *mark = app ? strchr(app, '_') : NULL;
    char text[64];
    char *end = NULL;
    if (piece && xml_attribute(piece, "NumberOfPoints", text, sizeof text))
        f->points = strtol(text, &end, 10);
    if (!piece || !end || *end || f->points < 0 || !mark ||
        !strstr(f->data, "header_type=\"UInt64\"")) {
        snprintf(why, why_len, "is not a particle file bedlam wrote (no points or appended data)");
        bdl_vtp_close(f);
        return BDL_ERR_IO;
    }
    f->appended = (size_t)(mark + 1 - f->data);
    return BDL_OK;
}

/// The DataArray element named `name` in the header (before the appended data), or NULL.
static const char *vtp_element(const bdl_vtp_file *f, const char *name)
{
    char key[96];
    snprintf(key, sizeof key, "Name=\"%s\"", name);
    const char *at = strstr(f->data, key);
    if (!at || (size_t)(at - f->data) >= f->appended)
        return NULL;
    while (at > f->data && *at != '<')
        --at;
    return at;
}

bdl_result bdl_vtp_array(const bdl_vtp_file *f, const char *name, int components, double **out,
                         char *why, size_t why_len)
{
    *out = NULL;
    const char *e = vtp_element(f, name);
    char type[32], comps[32], offset_text[32];
    if (!e || !xml_attribute(e, "type", type, sizeof type) ||
        !xml_attribute(e, "NumberOfComponents", comps, sizeof comps) ||
        !xml_attribute(e, "offset", offset_text, sizeof offset_text) ||
        (strcmp(type, "Float64") != 0 && strcmp(type, "Int32") != 0) || atoi(comps) != components) {
        snprintf(why, why_len, "has no Float64 or Int32 array '%s' of %d components", name,
                 components);
        return BDL_ERR_IO;
    }
    const int int32 = strcmp(type, "Int32") == 0;
    const unsigned long long offset = strtoull(offset_text, NULL, 10);
    const size_t values = (size_t)f->points * (size_t)components;
    const size_t bytes = values * (int32 ? sizeof(int32_t) : sizeof(double));
    uint64_t header = 0;
    if (offset > f->size || f->size - f->appended < offset + 8 + bytes) {
        snprintf(why, why_len, "is truncated: array '%s' runs past the end", name);
        return BDL_ERR_IO;
    }
    memcpy(&header, f->data + f->appended + offset, 8);
    if (header != bytes) {
        snprintf(why, why_len, "array '%s' holds %llu bytes, %zu expected", name,
                 (unsigned long long)header, bytes);
        return BDL_ERR_IO;
    }
    *out = malloc(values > 0 ? values * sizeof(double) : 1);
    if (!*out) {
        snprintf(why, why_len, "out of memory");
        return BDL_ERR_NOMEM;
    }
    const char *at = f->data + f->appended + offset + 8;
    if (!int32) {
        memcpy(*out, at, bytes);
        return BDL_OK;
    }
    for (size_t k = 0; k < values; ++k) { // Int32 values, as doubles
        int32_t v;
        memcpy(&v, at + k * sizeof v, sizeof v);
        (*out)[k] = v;
    }
    return BDL_OK;
}

void bdl_vtp_close(bdl_vtp_file *f)
{
    free(f->data);
    *f = (bdl_vtp_file){0};
}

void bdl_pvd_destroy(bdl_pvd *pvd)
{
    if (!pvd)
        return;
    for (long i = 0; i < pvd->count; ++i)
        free(pvd->entries[i].file);
    free(pvd->entries);
    free(pvd->path);
    free(pvd);
}

bdl_result bdl_vti_write(const char *path, const int n[3], const double origin[3],
                         const double spacing[3], const bdl_vtk_array *arrays, int array_count)
{
    long cells = (long)n[0] * n[1] * n[2];
    for (int k = 0; k < array_count; ++k)
        if (arrays[k].type != BDL_VTK_FLOAT64 || arrays[k].components < 1 ||
            (cells > 0 && !arrays[k].data))
            return BDL_ERR_IO;
    bdl_atomic_file af;
    if (bdl_atomic_open(&af, path) != BDL_OK)
        return BDL_ERR_IO;
    FILE *f = af.file;
    fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\" "
               "byte_order=\"LittleEndian\">\n");
    fprintf(f,
            "  <ImageData WholeExtent=\"0 %d 0 %d 0 %d\" Origin=\"%.17g %.17g %.17g\" "
            "Spacing=\"%.17g %.17g %.17g\">\n",
            n[0], n[1], n[2], origin[0], origin[1], origin[2], spacing[0], spacing[1], spacing[2]);
    fprintf(f, "    <Piece Extent=\"0 %d 0 %d 0 %d\">\n      <CellData>\n", n[0], n[1], n[2]);
    for (int k = 0; k < array_count; ++k) {
        const double *v = arrays[k].data;
        fprintf(f,
                "        <DataArray type=\"Float64\" Name=\"%s\" NumberOfComponents=\"%d\" "
                "format=\"ascii\">\n",
                arrays[k].name, arrays[k].components);
        long values = cells * arrays[k].components;
        for (long i = 0; i < values; ++i)
            fprintf(f, "%.9g%s", v[i], (i + 1) % 9 == 0 || i + 1 == values ? "\n" : " ");
        fprintf(f, "        </DataArray>\n");
    }
    fprintf(f, "      </CellData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n");
    return bdl_atomic_commit(&af);
}
