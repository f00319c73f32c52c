// Tests for src/io: atomic files, output folders, VTK PolyData and PVD, CSV time series.
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "core/file.h"
#include "io/csv.h"
#include "io/vtk.h"

/// Paths inside the per-run scratch folder.
typedef struct scratch {
    char root[64];
} scratch;

static void path_in(const scratch *s, const char *name, char *out, size_t len)
{
    snprintf(out, len, "%s/%s", s->root, name);
}

static int file_exists(const char *path)
{
    struct stat info;
    return stat(path, &info) == 0;
}

/// Reads a whole file into a NUL-terminated buffer (the caller frees it); NULL on failure.
static char *read_all(const char *path, size_t *size)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        return NULL;
    fseek(file, 0, SEEK_END);
    long length = ftell(file);
    fseek(file, 0, SEEK_SET);
    char *data = malloc((size_t)length + 1);
    if (data && fread(data, 1, (size_t)length, file) != (size_t)length) {
        free(data);
        data = NULL;
    }
    fclose(file);
    if (data) {
        data[length] = '\0';
        if (size)
            *size = (size_t)length;
    }
    return data;
}

/// Counts the entries of a folder other than "." and "..", to catch leftover temporary files.
static int count_entries(const char *folder)
{
    char command[256];
    snprintf(command, sizeof command, "ls -A '%s' | wc -l", folder);
    FILE *pipe = popen(command, "r");
    int count = -1;
    if (pipe) {
        if (fscanf(pipe, "%d", &count) != 1)
            count = -1;
        pclose(pipe);
    }
    return count;
}

static void test_atomic_write(const scratch *s)
{
    char folder[256], path[256];
    path_in(s, "atomic", folder, sizeof folder);
    CHECK(bdl_mkdir_p(folder) == BDL_OK);
    path_in(s, "atomic/data.bin", path, sizeof path);
    const char text[] = "hello, atomic world\n";
    CHECK(bdl_write_file_atomic(path, text, sizeof text - 1) == BDL_OK);
    size_t size = 0;
    char *back = read_all(path, &size);
    CHECK(back && size == sizeof text - 1 && memcmp(back, text, size) == 0);
    free(back);

    // Replacing keeps exactly one file and no temporary.
    CHECK(bdl_write_file_atomic(path, "x", 1) == BDL_OK);
    back = read_all(path, &size);
    CHECK(back && size == 1 && back[0] == 'x');
    free(back);
    CHECK(count_entries(folder) == 1);
}

static void test_atomic_abort(const scratch *s)
{
    char folder[256], path[256];
    path_in(s, "abort", folder, sizeof folder);
    CHECK(bdl_mkdir_p(folder) == BDL_OK);
    path_in(s, "abort/never.bin", path, sizeof path);
    bdl_atomic_file af;
    CHECK(bdl_atomic_open(&af, path) == BDL_OK);
    CHECK(af.file != NULL && file_exists(af.temp_path));
    fputs("partial", af.file);
    bdl_atomic_abort(&af);
    CHECK(af.file == NULL);
    CHECK(!file_exists(path));
    CHECK(count_entries(folder) == 0);
    bdl_atomic_abort(&af); // a second abort is harmless
}

static void test_atomic_failures(const scratch *s)
{
    char path[256];
    path_in(s, "missing/parent/file.bin", path, sizeof path);
    bdl_atomic_file af;
    CHECK(bdl_atomic_open(&af, path) == BDL_ERR_IO);
    CHECK(af.file == NULL);
    CHECK(bdl_write_file_atomic(path, "x", 1) == BDL_ERR_IO);
    CHECK(!file_exists(path));

    // A rename refused at commit (the target is a folder) reports an error and cleans up.
    char folder[256];
    path_in(s, "commit_fails", folder, sizeof folder);
    CHECK(bdl_mkdir_p(folder) == BDL_OK);
    path_in(s, "commit_fails/target", path, sizeof path);
    CHECK(bdl_mkdir_p(path) == BDL_OK);
    CHECK(bdl_atomic_open(&af, path) == BDL_OK);
    fputs("data", af.file);
    CHECK(bdl_atomic_commit(&af) == BDL_ERR_IO);
    CHECK(!file_exists(af.temp_path));
    CHECK(count_entries(folder) == 1);
    CHECK(bdl_atomic_commit(&af) == BDL_ERR_IO); // nothing left to commit
}

static void test_folders(const scratch *s)
{
    char path[256], file[256], why[512];
    path_in(s, "deep/a/b//c/", path, sizeof path);
    CHECK(bdl_mkdir_p(path) == BDL_OK);
    CHECK(bdl_mkdir_p(path) == BDL_OK); // existing is fine
    CHECK(bdl_check_writable_dir(path, why, sizeof why) == BDL_OK);
    CHECK(why[0] == '\0');
    path_in(s, "fresh/out", path, sizeof path);
    CHECK(bdl_check_writable_dir(path, why, sizeof why) == BDL_OK);
    CHECK(file_exists(path) && count_entries(path) == 0); // the probe is gone

    path_in(s, "plain_file", file, sizeof file);
    CHECK(bdl_write_file_atomic(file, "x", 1) == BDL_OK);
    path_in(s, "plain_file/sub", path, sizeof path);
    errno = 0;
    CHECK(bdl_mkdir_p(path) == BDL_ERR_IO);
    CHECK(errno == ENOTDIR);
    CHECK(bdl_mkdir_p(file) == BDL_ERR_IO);
    CHECK(bdl_check_writable_dir(path, why, sizeof why) == BDL_ERR_IO);
    CHECK_MSG(strstr(why, path) != NULL && strstr(why, ": ") != NULL, "why = '%s'", why);
    printf("  check_writable_dir says: %s\n", why);
    char small[8];
    CHECK(bdl_check_writable_dir(path, small, sizeof small) == BDL_ERR_IO);
    CHECK(strlen(small) == sizeof small - 1);
}

/// Value of attribute `name` in the tag of `xml` that contains `anchor`, as a number; -1 if absent.
static long long attribute_after(const char *xml, const char *anchor, const char *name)
{
    const char *tag = strstr(xml, anchor);
    if (!tag)
        return -1;
    const char *end = strchr(tag, '>');
    char key[64];
    snprintf(key, sizeof key, "%s=\"", name);
    const char *value = strstr(tag, key);
    if (!value || (end && value > end))
        return -1;
    return strtoll(value + strlen(key), NULL, 10);
}

/// Start of the data of the appended block whose DataArray has Name="name"; sets its byte count.
static const unsigned char *appended_block(const char *xml, const unsigned char *payload,
                                           const char *name, uint64_t *bytes)
{
    char anchor[96];
    snprintf(anchor, sizeof anchor, "Name=\"%s\"", name);
    long long offset = attribute_after(xml, anchor, "offset");
    if (offset < 0)
        return NULL;
    memcpy(bytes, payload + offset, sizeof *bytes); // the test host is little-endian like the file
    return payload + offset + sizeof *bytes;
}

static void test_vtp(const scratch *s)
{
    char path[256];
    path_in(s, "particles.vtp", path, sizeof path);
    bdl_vec3 positions[3] = {{0.1, 0.2, 0.3}, {-1.5, 2.25, 1e-300}, {3.0, -4.0, 5.5}};
    double radius[3] = {0.01, 0.02, 1.0 / 3.0};
    int32_t id[3] = {7, -8, 2147483647};
    bdl_vec3 velocity[3] = {{1, 2, 3}, {4, 5, 6}, {-7, -8, -9.125}};
    bdl_vtk_array arrays[] = {
        {"radius", BDL_VTK_FLOAT64, 1, radius},
        {"id", BDL_VTK_INT32, 1, id},
        {"velocity", BDL_VTK_FLOAT64, 3, velocity},
    };
    CHECK(bdl_vtp_write(path, 3, positions, arrays, 3) == BDL_OK);
    size_t size = 0;
    char *data = read_all(path, &size);
    CHECK(data != NULL);
    if (!data)
        return;
    const char *appended = strstr(data, "<AppendedData encoding=\"raw\">");
    CHECK(appended != NULL);
    if (!appended) {
        free(data);
        return;
    }
    const char *underscore = strchr(appended, '_');
    CHECK(underscore != NULL);
    const unsigned char *payload = (const unsigned char *)underscore + 1;
    CHECK(strstr(data, "header_type=\"UInt64\"") && strstr(data, "byte_order=\"LittleEndian\""));
    CHECK(strstr(data, "NumberOfPoints=\"3\"") && strstr(data, "NumberOfVerts=\"3\""));
    CHECK(attribute_after(data, "Name=\"radius\"", "offset") == 0);
    CHECK(attribute_after(data, "Name=\"id\"", "offset") == 8 + 3 * 8);
    CHECK(attribute_after(data, "Name=\"velocity\"", "offset") == 32 + 8 + 3 * 4);
    CHECK(attribute_after(data, "Name=\"velocity\"", "NumberOfComponents") == 3);
    CHECK(attribute_after(data, "Name=\"Points\"", "offset") == 52 + 8 + 9 * 8);
    CHECK(strstr(data, "type=\"Int32\" Name=\"id\"") != NULL);

    uint64_t bytes = 0;
    const unsigned char *block = appended_block(data, payload, "radius", &bytes);
    CHECK(block && bytes == sizeof radius && memcmp(block, radius, sizeof radius) == 0);
    block = appended_block(data, payload, "id", &bytes);
    CHECK(block && bytes == sizeof id && memcmp(block, id, sizeof id) == 0);
    block = appended_block(data, payload, "velocity", &bytes);
    CHECK(block && bytes == sizeof velocity && memcmp(block, velocity, sizeof velocity) == 0);
    block = appended_block(data, payload, "Points", &bytes);
    double decoded[9];
    CHECK(block && bytes == sizeof decoded);
    if (block) {
        memcpy(decoded, block, sizeof decoded);
        CHECK(decoded[0] == 0.1 && decoded[4] == 2.25 && decoded[5] == 1e-300 && decoded[8] == 5.5);
    }
    int64_t cells[3];
    block = appended_block(data, payload, "connectivity", &bytes);
    CHECK(block && bytes == sizeof cells);
    if (block) {
        memcpy(cells, block, sizeof cells);
        CHECK(cells[0] == 0 && cells[1] == 1 && cells[2] == 2);
    }
    block = appended_block(data, payload, "offsets", &bytes);
    CHECK(block && bytes == sizeof cells);
    if (block) {
        memcpy(cells, block, sizeof cells);
        CHECK(cells[0] == 1 && cells[1] == 2 && cells[2] == 3);
        // The offsets block is last: the closing tags follow it directly.
        CHECK(strncmp((const char *)block + sizeof cells, "\n  </AppendedData>\n</VTKFile>\n",
                      (size_t)(data + size - ((const char *)block + sizeof cells))) == 0);
    }
    free(data);

    // Zero particles still make a valid file; bad arguments are refused without a file.
    path_in(s, "empty.vtp", path, sizeof path);
    CHECK(bdl_vtp_write(path, 0, NULL, NULL, 0) == BDL_OK);
    CHECK(file_exists(path));
    path_in(s, "bad.vtp", path, sizeof path);
    bdl_vtk_array bad = {"nothing", BDL_VTK_FLOAT64, 1, NULL};
    CHECK(bdl_vtp_write(path, 3, positions, &bad, 1) == BDL_ERR_IO);
    CHECK(!file_exists(path));
}

/// A minimal well-formedness check: every start tag is closed in order, outside the payload.
static int xml_is_balanced(const char *xml)
{
    char stack[16][32];
    int depth = 0;
    for (const char *p = strchr(xml, '<'); p; p = strchr(p + 1, '<')) {
        const char *end = strchr(p, '>');
        if (!end)
            return 0;
        if (p[1] == '?')
            continue;
        int closing = p[1] == '/';
        const char *name = p + 1 + closing;
        size_t length = strcspn(name, " />");
        if (length == 0 || length >= sizeof stack[0])
            return 0;
        if (closing) {
            if (depth == 0 || strncmp(stack[depth - 1], name, length) != 0 ||
                stack[depth - 1][length])
                return 0;
            --depth;
        } else if (end[-1] != '/') {
            if (depth == 16)
                return 0;
            memcpy(stack[depth], name, length);
            stack[depth++][length] = '\0';
        }
    }
    return depth == 0;
}

static int count_occurrences(const char *text, const char *needle)
{
    int count = 0;
    for (const char *p = strstr(text, needle); p; p = strstr(p + 1, needle))
        ++count;
    return count;
}

static void test_pvd(const scratch *s)
{
    char path[256];
    path_in(s, "particles.pvd", path, sizeof path);
    bdl_pvd *pvd = bdl_pvd_create(path);
    CHECK(pvd != NULL);
    if (!pvd)
        return;
    char *data = read_all(path, NULL);
    CHECK(data && xml_is_balanced(data) && count_occurrences(data, "<DataSet ") == 0);
    free(data);
    CHECK(bdl_pvd_add(pvd, 0.0, "vtk/particles_000000.vtp") == BDL_OK);
    CHECK(bdl_pvd_add(pvd, 0.1, "vtk/particles_000001.vtp") == BDL_OK);
    CHECK(bdl_pvd_add(pvd, 0.2, "vtk/a&b.vtp") == BDL_OK);
    bdl_pvd_destroy(pvd);
    data = read_all(path, NULL);
    CHECK(data != NULL);
    if (data) {
        CHECK(xml_is_balanced(data));
        CHECK(strstr(data, "type=\"Collection\"") != NULL);
        CHECK(count_occurrences(data, "<DataSet ") == 3);
        CHECK(strstr(data, "timestep=\"0.10000000000000001\"") != NULL);
        CHECK(strstr(data, "file=\"vtk/particles_000001.vtp\"") != NULL);
        CHECK(strstr(data, "file=\"vtk/a&amp;b.vtp\"") != NULL);
    }
    free(data);
    path_in(s, "no/such/folder.pvd", path, sizeof path);
    CHECK(bdl_pvd_create(path) == NULL);
}

static void test_csv(const scratch *s)
{
    char path[256];
    path_in(s, "diagnostics.csv", path, sizeof path);
    const char *const columns[] = {"time", "step", "energy"};
    bdl_csv *csv = bdl_csv_open(path, columns, 3, 0);
    CHECK(csv != NULL);
    if (!csv)
        return;
    double energies[5] = {1.0 / 3.0, -2e-300, 6.02214076e23, 0.1 + 0.2, 123456789012345.0};
    for (int i = 0; i < 5; ++i) {
        double row[3] = {0.1 * i, 1000.0 * i, energies[i]};
        CHECK(bdl_csv_row(csv, row) == BDL_OK);
    }
    CHECK(bdl_csv_flush(csv) == BDL_OK);
    CHECK(bdl_csv_close(csv) == BDL_OK);

    char *text = read_all(path, NULL);
    CHECK(text && strncmp(text, "time,step,energy\n0,0,", 21) == 0);
    CHECK(text && strstr(text, ",4000,123456789012345\n") != NULL);
    free(text);
    double values[8];
    CHECK(bdl_csv_read_column(path, "energy", values, 8) == 5);
    for (int i = 0; i < 5; ++i)
        CHECK_MSG(values[i] == energies[i], "row %d: %.17g", i, values[i]);
    CHECK(bdl_csv_read_column(path, "time", values, 8) == 5);
    CHECK(values[3] == 0.1 * 3);
    CHECK(bdl_csv_read_column(path, "step", values, 2) == 2);
    CHECK(bdl_csv_read_column(path, "step", NULL, 0) == 5);
    CHECK(bdl_csv_read_column(path, "missing", values, 8) == -1);
    CHECK(bdl_csv_read_column("/nonexistent/file.csv", "time", values, 8) == -1);

    // Resume: keep rows up to t = 0.2 and append after them; a cut last line is dropped.
    FILE *file = fopen(path, "ab");
    CHECK(file != NULL);
    if (file) {
        fputs("0.5,50", file);
        fclose(file);
    }
    // The reader leaves the cut row out (a run killed while writing it).
    CHECK(bdl_csv_read_column(path, "time", values, 8) == 5);
    CHECK(bdl_csv_read_column(path, "step", NULL, 0) == 5);
    CHECK(bdl_csv_truncate_after(path, 0.1 * 2) == BDL_OK);
    CHECK(bdl_csv_read_column(path, "time", values, 8) == 3);
    CHECK(values[2] == 0.1 * 2);
    csv = bdl_csv_open(path, columns, 3, 1);
    CHECK(csv != NULL);
    if (csv) {
        double row[3] = {0.3, 3000, 42};
        CHECK(bdl_csv_row(csv, row) == BDL_OK);
        CHECK(bdl_csv_close(csv) == BDL_OK);
    }
    CHECK(bdl_csv_read_column(path, "energy", values, 8) == 4);
    CHECK(values[0] == energies[0] && values[2] == energies[2] && values[3] == 42.0);

    // Appending keeps a half-written row out; a different header is refused.
    file = fopen(path, "ab");
    if (file) {
        fputs("0.4,40", file);
        fclose(file);
    }
    csv = bdl_csv_open(path, columns, 3, 1);
    CHECK(csv != NULL);
    CHECK(bdl_csv_close(csv) == BDL_OK);
    CHECK(bdl_csv_read_column(path, "step", values, 8) == 4);
    CHECK(values[3] == 3000.0);
    const char *const other[] = {"time", "energy"};
    CHECK(bdl_csv_open(path, other, 2, 1) == NULL);
    path_in(s, "fresh.csv", path, sizeof path);
    csv = bdl_csv_open(path, other, 2, 1);
    CHECK(csv != NULL);
    CHECK(bdl_csv_close(csv) == BDL_OK);
    text = read_all(path, NULL);
    CHECK(text && strcmp(text, "time,energy\n") == 0);
    free(text);
    CHECK(bdl_csv_truncate_after("/nonexistent-bedlam.csv", 1.0) == BDL_OK);
}

static void test_vti(const scratch *s)
{
    char path[128];
    path_in(s, "grid.vti", path, sizeof path);
    const int n[3] = {2, 1, 3};
    const double origin[3] = {0.5, 0, -1}, spacing[3] = {0.25, 1, 0.5};
    double eps[6] = {0.4, 0.5, 0.6, 0.7, 0.8, 0.9}, u[18];
    for (int i = 0; i < 18; ++i)
        u[i] = i * 0.125;
    bdl_vtk_array arrays[] = {{"voidage", BDL_VTK_FLOAT64, 1, eps},
                              {"gas_velocity", BDL_VTK_FLOAT64, 3, u}};
    CHECK(bdl_vti_write(path, n, origin, spacing, arrays, 2) == BDL_OK);
    char *text = read_all(path, NULL);
    CHECK(text != NULL);
    if (text) {
        CHECK(strstr(text, "type=\"ImageData\"") != NULL);
        CHECK(strstr(text, "WholeExtent=\"0 2 0 1 0 3\"") != NULL);
        CHECK(strstr(text, "Origin=\"0.5 0 -1\"") != NULL);
        CHECK(strstr(text, "Name=\"gas_velocity\" NumberOfComponents=\"3\"") != NULL);
        CHECK(strstr(text, "0.4 0.5 0.6 0.7 0.8 0.9\n") != NULL);
        CHECK(strstr(text, "2.125\n") != NULL); // the last of 18 values ends its line
        free(text);
    }
    const bdl_vtk_array bad = {"x", BDL_VTK_INT32, 1, eps};
    CHECK(bdl_vti_write(path, n, origin, spacing, &bad, 1) == BDL_ERR_IO);
}

int main(void)
{
    scratch s;
    snprintf(s.root, sizeof s.root, "/tmp/bedlam_test_io_XXXXXX");
    if (!mkdtemp(s.root)) {
        perror("mkdtemp");
        return 1;
    }
    test_atomic_write(&s);
    test_atomic_abort(&s);
    test_atomic_failures(&s);
    test_folders(&s);
    test_vtp(&s);
    test_pvd(&s);
    test_csv(&s);
    test_vti(&s);
    char command[128];
    snprintf(command, sizeof command, "rm -rf '%s'", s.root);
    if (system(command) != 0)
        fprintf(stderr, "could not remove %s\n", s.root);
    return bdl_test_summary("test_io");
}
