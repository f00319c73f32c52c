// docs/scene-format.md against the key table: every key is documented under its section with
// the type, unit, default and range the parser uses, no row documents a key that does not
// exist, and the complete example in the document is a valid scene.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "scene/scene.h"
#include "scene/scene_internal.h"

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = size >= 0 ? malloc((size_t)size + 1) : NULL;
    if (text) {
        size_t got = fread(text, 1, (size_t)size, f);
        text[got] = '\0';
    }
    fclose(f);
    return text;
}

/// The text under "## [usage]" up to the next "## " heading, as [*start, *end); 0 if absent.
static int find_section(const char *doc, const char *usage, const char **start, const char **end)
{
    char heading[64];
    snprintf(heading, sizeof heading, "\n## [%s]\n", usage);
    const char *s = strstr(doc, heading);
    if (!s)
        return 0;
    s += strlen(heading);
    const char *next = strstr(s, "\n## ");
    *start = s;
    *end = next ? next : s + strlen(s);
    return 1;
}

/// Copies the table cell `column` (0-based) of a "| a | b |" row into buf.
static void cell(const char *row, int column, char *buf, size_t size)
{
    const char *s = row;
    for (int i = 0; i <= column && s; ++i)
        s = strstr(s + 1, " | ");
    buf[0] = '\0';
    if (!s)
        return;
    s += 3;
    const char *e = strstr(s, " |");
    size_t n = e ? (size_t)(e - s) : strlen(s);
    snprintf(buf, size, "%.*s", (int)(n < size ? n : size - 1), s);
}

static void check_key(const bdl_scene_key *key, const char *start, const char *end)
{
    char marker[64];
    snprintf(marker, sizeof marker, "\n| `%s` |", key->name);
    const char *row = strstr(start, marker);
    const char *usage = bdl_section_infos[key->section].usage;
    CHECK_MSG(row && row < end, "key '%s' not documented under [%s]", key->name, usage);
    if (!row || row >= end)
        return;
    ++row;
    char expected[4][256], found[256];
    snprintf(expected[0], sizeof expected[0], "%s", bdl_scene_key_type_name(key->type));
    snprintf(expected[1], sizeof expected[1], "%s", key->unit);
    bdl_scene_key_default_text(key, expected[2], sizeof expected[2]);
    bdl_scene_key_range_text(key, expected[3], sizeof expected[3]);
    static const char *const columns[] = {"type", "unit", "default", "allowed"};
    for (int c = 0; c < 4; ++c) {
        cell(row, c, found, sizeof found);
        CHECK_MSG(strcmp(found, expected[c]) == 0,
                  "[%s] %s: documented %s '%s', the parser has '%s'\n  expected row: | `%s` | "
                  "%s | %s | %s | %s | %s |",
                  usage, key->name, columns[c], found, expected[c], key->name, expected[0],
                  expected[1], expected[2], expected[3], key->doc);
    }
}

/// Every "| `key` |" row of the section names a key of the table.
static void check_no_stale_rows(int kind, const char *start, const char *end)
{
    for (const char *s = strstr(start, "\n| `"); s && s < end; s = strstr(s + 1, "\n| `")) {
        char name[64] = "";
        sscanf(s, "\n| `%63[^`]", name);
        CHECK_MSG(bdl_scene_key_find((bdl_section_kind)kind, name) != NULL,
                  "docs document '%s' under [%s], which the parser does not know", name,
                  bdl_section_infos[kind].usage);
    }
}

static void check_example(const char *doc)
{
    const char *heading = strstr(doc, "\n## A complete example");
    const char *start = heading ? strstr(heading, "```ini\n") : NULL;
    const char *end = start ? strstr(start + 7, "\n```") : NULL;
    CHECK_MSG(start && end, "no ```ini block under '## A complete example'");
    if (!start || !end)
        return;
    start += 7;
    size_t length = (size_t)(end - start) + 1;
    char *text = malloc(length + 1);
    memcpy(text, start, length);
    text[length] = '\0';
    static bdl_scene scene;
    bdl_scene_error err = {{0}};
    bdl_result r = bdl_scene_load_string(text, "example", NULL, 0, &scene, &err);
    CHECK_MSG(r == BDL_OK, "the example scene does not load: %s", err.message);
    CHECK(scene.species_count >= 2 && scene.wall_count >= 3 && scene.create_count >= 3);
    free(text);
}

int main(void)
{
    char *doc = read_text("../docs/scene-format.md");
    CHECK_MSG(doc != NULL, "cannot read ../docs/scene-format.md");
    if (!doc)
        return bdl_test_summary("test_scene_docs");
    for (int kind = 0; kind < BDL_SECTION_KIND_COUNT; ++kind) {
        const char *start = NULL, *end = NULL;
        int found = find_section(doc, bdl_section_infos[kind].usage, &start, &end);
        CHECK_MSG(found, "no '## [%s]' heading", bdl_section_infos[kind].usage);
        if (!found)
            continue;
        for (int i = 0; i < bdl_scene_key_count; ++i)
            if ((int)bdl_scene_keys[i].section == kind)
                check_key(&bdl_scene_keys[i], start - 1, end);
        check_no_stale_rows(kind, start - 1, end);
    }
    check_example(doc);
    free(doc);
    return bdl_test_summary("test_scene_docs");
}
