// bedlam — reading a scene: libinih tokenises the INI text, one generic handler looks every key
// up in the key table (scene_keys.c) and writes it through the table's offsets.
//
// Debian's libinih does not pass line numbers to the handler, so the text is fed through our
// own line reader (ini_parse_stream): it counts lines, keeps the current line for messages and
// reads the section headers itself, so that headers longer than libinih's 50-character section
// buffer, empty sections and the header's line number are all known exactly.
#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file.h"
#include "scene/scene_internal.h"

enum { VALUE_SHOWN = 80, WHY_LEN = 256 };

#if defined(__GNUC__)
__attribute__((format(printf, 3, 0)))
#endif
static void
append_va(char *buf, size_t size, const char *format, va_list args)
{
    size_t used = strlen(buf);
    if (used + 1 < size)
        vsnprintf(buf + used, size - used, format, args);
}

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static void
append(char *buf, size_t size, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    append_va(buf, size, format, args);
    va_end(args);
}

void bdl_scene_fail(bdl_scene_parser *p, const bdl_scene_where *where, const char *format, ...)
{
    if (p->failed)
        return; // the first problem is the one reported
    p->failed = 1;
    char *out = p->err->message;
    size_t size = sizeof p->err->message;
    out[0] = '\0';
    if (where->line == BDL_LINE_SET)
        append(out, size, "--set:");
    else
        append(out, size, "%s:%d:", p->file,
               where->line > 0 ? where->line : (p->line > 0 ? p->line : 1));
    if (where->title)
        append(out, size, " [%s]", where->title);
    if (where->key)
        append(out, size, " %s", where->key);
    if (where->value) {
        // Long values are cut: the message must stay one readable line.
        size_t length = strlen(where->value);
        append(out, size, " = %.*s%s", VALUE_SHOWN, where->value,
               length > VALUE_SHOWN ? "..." : "");
    }
    append(out, size, "%s ", where->title || where->key || where->value ? ":" : "");
    va_list args;
    va_start(args, format);
    append_va(out, size, format, args);
    va_end(args);
    if (where->allowed) {
        char range[256];
        bdl_scene_key_range_text(where->allowed, range, sizeof range);
        append(out, size, "; allowed: %s", range);
        if (strcmp(where->allowed->unit, "-") != 0)
            append(out, size, " (%s)", where->allowed->unit);
    }
    for (char *c = out; *c; ++c)
        if (iscntrl((unsigned char)*c))
            *c = ' ';
}

// ---------------------------------------------------------------------------------------------
// Values. Each parser returns 1 on success or writes why it failed into `why` (WHY_LEN bytes).

static const char *skip_space(const char *s)
{
    while (*s && isspace((unsigned char)*s))
        ++s;
    return s;
}

static int parse_number(const char *text, double *out, char *why)
{
    const char *start = skip_space(text);
    if (!*start) {
        snprintf(why, WHY_LEN, "missing value");
        return 0;
    }
    char *end = NULL;
    errno = 0;
    double v = strtod(start, &end);
    if (end == start) {
        snprintf(why, WHY_LEN, "not a number");
        return 0;
    }
    const char *rest = skip_space(end);
    if (*rest) {
        snprintf(why, WHY_LEN, "unexpected '%.20s' after the number", rest);
        return 0;
    }
    if (!isfinite(v)) {
        snprintf(why, WHY_LEN, "not a finite number");
        return 0;
    }
    *out = v;
    return 1;
}

static int parse_vector(const char *text, bdl_vec3 *out, char *why)
{
    double components[3];
    int count = 0;
    const char *s = skip_space(text);
    while (*s) {
        char token[128];
        size_t length = 0;
        while (s[length] && !isspace((unsigned char)s[length]))
            ++length;
        if (count < 3) {
            snprintf(token, sizeof token, "%.*s", (int)length, s);
            char inner[WHY_LEN];
            if (length >= sizeof token || !parse_number(token, &components[count], inner)) {
                snprintf(why, WHY_LEN, "component %d '%.20s': %.200s", count + 1, token,
                         length >= sizeof token ? "too long" : inner);
                return 0;
            }
        }
        ++count;
        s = skip_space(s + length);
    }
    if (count != 3) {
        snprintf(why, WHY_LEN, "expected 3 numbers separated by spaces, got %d", count);
        return 0;
    }
    *out = bdl_v3(components[0], components[1], components[2]);
    return 1;
}

/// Integers in plain digits, or in a float notation that is exactly integral ("1e6").
static int parse_integer(const char *text, int is_unsigned, double *value, uint64_t *unsigned_value,
                         char *why)
{
    const char *start = skip_space(text);
    char *end = NULL;
    errno = 0;
    if (is_unsigned && *start != '-') {
        unsigned long long u = strtoull(start, &end, 10);
        if (end != start && !*skip_space(end) && errno == 0) {
            *unsigned_value = u;
            *value = (double)u;
            return 1;
        }
    } else {
        long long v = strtoll(start, &end, 10);
        if (end != start && !*skip_space(end) && errno == 0) {
            *value = (double)v;
            *unsigned_value = (uint64_t)v;
            return 1;
        }
    }
    double v;
    if (!parse_number(text, &v, why))
        return 0;
    if (v != floor(v) || fabs(v) > 9007199254740992.0) {
        snprintf(why, WHY_LEN, "not an integer");
        return 0;
    }
    *value = v;
    *unsigned_value = v >= 0 ? (uint64_t)v : 0;
    return 1;
}

static int parse_bool(const char *text, int *out, char *why)
{
    static const char *const words[] = {"true", "yes", "on", "1", "false", "no", "off", "0"};
    for (int i = 0; i < 8; ++i) {
        size_t n = strlen(words[i]);
        size_t k = 0;
        while (k < n && tolower((unsigned char)text[k]) == words[i][k])
            ++k;
        if (k == n && text[n] == '\0') {
            *out = i < 4;
            return 1;
        }
    }
    snprintf(why, WHY_LEN, "not a boolean");
    return 0;
}

static int parse_enum(const bdl_scene_key *key, const char *text, int *out, char *why)
{
    bdl_suggestion suggestion;
    bdl_suggest_init(&suggestion, text);
    for (int i = 0; key->enum_names[i]; ++i) {
        if (strcmp(text, key->enum_names[i]) == 0) {
            *out = i;
            return 1;
        }
        bdl_suggest_consider(&suggestion, key->enum_names[i]);
    }
    char hint[96];
    bdl_suggest_text(&suggestion, hint, sizeof hint);
    snprintf(why, WHY_LEN, "%s%s", *text ? "unknown choice" : "missing value", hint);
    return 0;
}

static int parse_axes(const char *text, int *axes, char *why)
{
    axes[0] = axes[1] = axes[2] = 0;
    if (strcmp(text, "none") == 0)
        return 1;
    const char *s = skip_space(text);
    if (!*s) {
        snprintf(why, WHY_LEN, "missing value");
        return 0;
    }
    while (*s) {
        size_t length = 0;
        while (s[length] && !isspace((unsigned char)s[length]) && s[length] != ',')
            ++length;
        const char *letter = length == 1 ? strchr("xyz", *s) : NULL;
        if (!letter || !*s) {
            snprintf(why, WHY_LEN, "unknown axis '%.*s'", (int)(length < 20 ? length : 20), s);
            return 0;
        }
        int axis = (int)(letter - "xyz");
        if (axes[axis]) {
            snprintf(why, WHY_LEN, "axis '%c' given twice", *s);
            return 0;
        }
        axes[axis] = 1;
        s += length;
        while (*s && (isspace((unsigned char)*s) || *s == ','))
            ++s;
    }
    return 1;
}

/// Section names: short, and free of '.' so that --set species.NAME.key stays unambiguous.
static int check_name(const char *name, char *why)
{
    if (!*name) {
        snprintf(why, WHY_LEN, "empty name");
        return 0;
    }
    if (strlen(name) >= BDL_NAME_LEN) {
        snprintf(why, WHY_LEN, "name '%.40s...' is longer than %d characters", name,
                 BDL_NAME_LEN - 1);
        return 0;
    }
    for (const char *c = name; *c; ++c) {
        if (!isalnum((unsigned char)*c) && *c != '_' && *c != '-') {
            snprintf(why, WHY_LEN,
                     "character '%c' not allowed in name '%s' (letters, digits, _ and - only)", *c,
                     name);
            return 0;
        }
    }
    return 1;
}

static int resolve_path(const bdl_scene *scene, const char *text, char *out, char *why)
{
    if (!*text) {
        snprintf(why, WHY_LEN, "missing value");
        return 0;
    }
    int length;
    size_t dir_length = strlen(scene->dir);
    if (text[0] == '/' || strcmp(scene->dir, ".") == 0)
        length = snprintf(out, BDL_PATH_LEN, "%s", text);
    else
        length = snprintf(out, BDL_PATH_LEN, "%s%s%s", scene->dir,
                          dir_length > 0 && scene->dir[dir_length - 1] == '/' ? "" : "/", text);
    if (length < 0 || length >= BDL_PATH_LEN) {
        snprintf(why, WHY_LEN, "resolved path is longer than %d characters", BDL_PATH_LEN - 1);
        return 0;
    }
    return 1;
}

static int in_range(const bdl_scene_key *key, double v)
{
    if (key->lo_kind == BDL_BOUND_OPEN && !(v > key->lo))
        return 0;
    if (key->lo_kind == BDL_BOUND_CLOSED && !(v >= key->lo))
        return 0;
    if (key->hi_kind == BDL_BOUND_OPEN && !(v < key->hi))
        return 0;
    if (key->hi_kind == BDL_BOUND_CLOSED && !(v <= key->hi))
        return 0;
    return 1;
}

/// A vector within its key's bounds: each component's, or its length's (taken with hypot, so
/// that components near the largest double do not overflow to an infinite length).
static int store_vector(const bdl_scene_key *key, const char *text, bdl_vec3 *field, char *why)
{
    bdl_vec3 v;
    if (!parse_vector(text, &v, why))
        return 0;
    for (int a = 0; a < 3; ++a)
        if (!in_range(key, bdl_v3_comp(v, a))) {
            snprintf(why, WHY_LEN, "component %d (%g) out of range", a + 1, bdl_v3_comp(v, a));
            return 0;
        }
    const double length = hypot(hypot(v.x, v.y), v.z);
    if (key->max_length > 0.0 && !(length <= key->max_length)) {
        snprintf(why, WHY_LEN, "length %.3g out of range", length);
        return 0;
    }
    *field = v;
    return 1;
}

/// Parses `text` as the key's type, checks the range and stores it; 0 with `why` on failure.
static int store_value(bdl_scene_parser *p, const bdl_scene_key *key, bdl_scene_section *section,
                       const char *text, char *why)
{
    void *field = bdl_scene_key_field(key, p->scene, section);
    double number = 0.0;
    uint64_t unsigned_value = 0;
    switch (key->type) {
    case BDL_KEY_NUMBER:
        if (!parse_number(text, &number, why))
            return 0;
        break;
    case BDL_KEY_INT:
    case BDL_KEY_LONG:
    case BDL_KEY_U64:
        if (!parse_integer(text, key->type == BDL_KEY_U64, &number, &unsigned_value, why))
            return 0;
        break;
    case BDL_KEY_VECTOR:
        return store_vector(key, text, field, why);
    case BDL_KEY_BOOL:
        return parse_bool(text, field, why);
    case BDL_KEY_ENUM:
        return parse_enum(key, text, field, why);
    case BDL_KEY_AXES:
        return parse_axes(text, field, why);
    case BDL_KEY_NAME:
        if (!check_name(text, why))
            return 0;
        snprintf(field, BDL_NAME_LEN, "%s", text);
        return 1;
    case BDL_KEY_PATH:
        return resolve_path(p->scene, text, field, why);
    }
    // Integers are held as doubles on the way: a long beyond 2^53 would not be the one written.
    if (!in_range(key, number) || (key->type == BDL_KEY_INT && fabs(number) > 2147483647.0) ||
        (key->type == BDL_KEY_LONG && fabs(number) > 9007199254740992.0)) {
        snprintf(why, WHY_LEN, "out of range");
        return 0;
    }
    if (key->type == BDL_KEY_NUMBER)
        *(double *)field = number;
    else if (key->type == BDL_KEY_INT)
        *(int *)field = (int)number;
    else if (key->type == BDL_KEY_LONG)
        *(long *)field = (long)number;
    else
        *(uint64_t *)field = unsigned_value;
    return 1;
}

/// One `key = value` of `section`, from the file (line > 0) or from --set (BDL_LINE_SET).
static void apply_key(bdl_scene_parser *p, bdl_scene_section *section, const char *name,
                      const char *value, int line)
{
    bdl_scene_where where = {.line = line, .title = section->title, .key = name, .value = value};
    if (!*name) {
        bdl_scene_fail(p, &where, "missing key name before '='");
        return;
    }
    const bdl_scene_key *key = bdl_scene_key_find(section->kind, name);
    if (!key) {
        bdl_suggestion suggestion;
        bdl_suggest_init(&suggestion, name);
        for (int i = 0; i < bdl_scene_key_count; ++i)
            if (bdl_scene_keys[i].section == section->kind)
                bdl_suggest_consider(&suggestion, bdl_scene_keys[i].name);
        char hint[96];
        bdl_suggest_text(&suggestion, hint, sizeof hint);
        bdl_scene_fail(p, &where, "unknown key in [%s]%s", bdl_section_infos[section->kind].usage,
                       hint);
        return;
    }
    int index = bdl_scene_key_index(key);
    if (line != BDL_LINE_SET && section->key_line[index] != 0) {
        bdl_scene_fail(p, &where, "key given twice in this section (first at line %d)",
                       section->key_line[index]);
        return;
    }
    char why[WHY_LEN];
    if (!store_value(p, key, section, value, why)) {
        where.allowed = key;
        bdl_scene_fail(p, &where, "%s", why);
        return;
    }
    if (key->has_flag)
        *(int *)((char *)bdl_scene_key_field(key, p->scene, section) - key->offset +
                 key->flag_offset) = 1;
    section->key_line[index] = line;
}

// ---------------------------------------------------------------------------------------------
// Sections.

/// The section kind of a header word followed by `names` names ([camera] and [camera NAME] share
/// the word); the first kind with the word when none has that many names (for the message).
static int find_kind(const char *word, int names)
{
    int first = -1;
    for (int k = 0; k < BDL_SECTION_KIND_COUNT; ++k)
        if (strcmp(word, bdl_section_infos[k].name) == 0) {
            if (bdl_section_infos[k].name_count == names)
                return k;
            if (first < 0)
                first = k;
        }
    return first;
}

static void fail_unknown_section(bdl_scene_parser *p, int line, const char *title, const char *word)
{
    bdl_suggestion suggestion;
    bdl_suggest_init(&suggestion, word);
    char allowed[256] = "";
    for (int k = 0; k < BDL_SECTION_KIND_COUNT; ++k) {
        bdl_suggest_consider(&suggestion, bdl_section_infos[k].name);
        append(allowed, sizeof allowed, "%s%s", k ? ", " : "", bdl_section_infos[k].usage);
    }
    char hint[96];
    bdl_suggest_text(&suggestion, hint, sizeof hint);
    bdl_scene_fail(p, &(bdl_scene_where){.line = line, .title = title},
                   "unknown section '%s'%s; allowed: %s", word, hint, allowed);
}

static int same_names(const bdl_scene_section *s, bdl_section_kind kind,
                      char names[2][BDL_NAME_LEN])
{
    if (s->kind != kind)
        return 0;
    if (kind == BDL_SECTION_PAIR) // [pair a b] and [pair b a] are the same pair
        return (strcmp(s->names[0], names[0]) == 0 && strcmp(s->names[1], names[1]) == 0) ||
               (strcmp(s->names[0], names[1]) == 0 && strcmp(s->names[1], names[0]) == 0);
    return strcmp(s->names[0], names[0]) == 0;
}

static bdl_scene_section *find_section(bdl_scene_parser *p, bdl_section_kind kind,
                                       char names[2][BDL_NAME_LEN])
{
    for (int i = 0; i < p->section_count; ++i)
        if (same_names(&p->sections[i], kind, names))
            return &p->sections[i];
    return NULL;
}

static int *section_counter(bdl_scene *scene, bdl_section_kind kind)
{
    switch (kind) {
    case BDL_SECTION_SPECIES:
        return &scene->species_count;
    case BDL_SECTION_PAIR:
        return &scene->pair_count;
    case BDL_SECTION_WALL:
        return &scene->wall_count;
    case BDL_SECTION_DIA:
        return &scene->dia_count;
    case BDL_SECTION_SINK:
        return &scene->sink_count;
    case BDL_SECTION_PHASE:
        return &scene->solids.phase_count;
    default:
        return &scene->create_count;
    }
}

/// Adds a named section with its defaults; the caller has checked names and limits.
static bdl_scene_section *add_section(bdl_scene_parser *p, bdl_section_kind kind,
                                      char names[2][BDL_NAME_LEN], int line)
{
    bdl_scene_section *s = &p->sections[p->section_count++];
    bdl_scene *scene = p->scene;
    memset(s, 0, sizeof *s);
    s->kind = kind;
    s->line = line;
    s->index = (*section_counter(scene, kind))++;
    memcpy(s->names, names, sizeof s->names);
    snprintf(s->title, sizeof s->title, "%s %s%s%s", bdl_section_infos[kind].name, names[0],
             kind == BDL_SECTION_PAIR ? " " : "", kind == BDL_SECTION_PAIR ? names[1] : "");
    if (kind == BDL_SECTION_SPECIES) {
        memset(&scene->species[s->index], 0, sizeof scene->species[0]);
        memcpy(scene->species[s->index].name, names[0], BDL_NAME_LEN);
        scene->line.species[s->index] = line;
    } else if (kind == BDL_SECTION_PAIR) {
        memset(&scene->pairs[s->index], 0, sizeof scene->pairs[0]);
        scene->line.pairs[s->index] = line;
    } else if (kind == BDL_SECTION_WALL) {
        memset(&scene->walls[s->index], 0, sizeof scene->walls[0]);
        memcpy(scene->walls[s->index].name, names[0], BDL_NAME_LEN);
        scene->line.walls[s->index] = line;
    } else if (kind == BDL_SECTION_SINK) {
        memset(&scene->sinks[s->index], 0, sizeof scene->sinks[0]);
        memcpy(scene->sinks[s->index].name, names[0], BDL_NAME_LEN);
    } else if (kind == BDL_SECTION_PHASE) {
        memset(&scene->solids.phases[s->index], 0, sizeof scene->solids.phases[0]);
        memcpy(scene->solids.phases[s->index].name, names[0], BDL_NAME_LEN);
    } else if (kind == BDL_SECTION_DIA) {
        memset(&scene->dias[s->index], 0, sizeof scene->dias[0]);
        memcpy(scene->dias[s->index].name, names[0], BDL_NAME_LEN);
        scene->dias[s->index].line = line;
    } else {
        memset(&scene->creates[s->index], 0, sizeof scene->creates[0]);
        memcpy(scene->creates[s->index].name, names[0], BDL_NAME_LEN);
        scene->line.creates[s->index] = line;
    }
    bdl_scene_apply_defaults(scene, s);
    return s;
}

/// Splits `text` at whitespace into at most 4 words (in place); returns the word count.
static int split_words(char *text, char *words[4])
{
    int count = 0;
    char *s = text;
    for (;;) {
        while (*s && isspace((unsigned char)*s))
            *s++ = '\0';
        if (!*s)
            return count;
        if (count < 4)
            words[count] = s;
        ++count;
        while (*s && !isspace((unsigned char)*s))
            ++s;
    }
}

/// Handles a "[...]" header (`inner` is the text between the brackets).
static void open_section(bdl_scene_parser *p, char *inner, int line)
{
    char title[BDL_SCENE_MAX_LINE + 4];
    snprintf(title, sizeof title, "%s", inner);
    bdl_scene_where where = {.line = line, .title = title};
    char *words[4] = {NULL};
    int count = split_words(inner, words);
    if (count == 0) {
        bdl_scene_fail(p, &where, "empty section header");
        return;
    }
    int kind = find_kind(words[0], count - 1);
    if (kind < 0) {
        fail_unknown_section(p, line, title, words[0]);
        return;
    }
    const bdl_section_info *info = &bdl_section_infos[kind];
    if (count - 1 != info->name_count) {
        bdl_scene_fail(p, &where, "%s; write [%s]",
                       info->name_count == 0 ? "this section takes no name"
                                             : "wrong number of names after the section word",
                       info->usage);
        return;
    }
    char names[2][BDL_NAME_LEN] = {"", ""};
    for (int i = 0; i < info->name_count; ++i) {
        char why[WHY_LEN];
        if (!check_name(words[i + 1], why)) {
            bdl_scene_fail(p, &where, "%s", why);
            return;
        }
        snprintf(names[i], BDL_NAME_LEN, "%s", words[i + 1]);
    }
    bdl_scene_section *existing = find_section(p, (bdl_section_kind)kind, names);
    if (existing && existing->line > 0) {
        bdl_scene_fail(p, &where, "duplicate section (first at line %d)", existing->line);
        return;
    }
    if (info->name_count == 0) { // singletons exist from the start
        existing->line = line;
        p->current = existing;
        return;
    }
    if (*section_counter(p->scene, (bdl_section_kind)kind) >= info->max_count) {
        bdl_scene_fail(p, &where, "too many [%s] sections; at most %d", info->usage,
                       info->max_count);
        return;
    }
    p->current = add_section(p, (bdl_section_kind)kind, names, line);
}

/// Classifies a line the way libinih will and opens sections at their headers.
static void scan_line(bdl_scene_parser *p, const char *line)
{
    const char *start = skip_space(line);
    if (*start != '[')
        return;
    char inner[BDL_SCENE_MAX_LINE + 4];
    size_t length = 0;
    int was_space = 0;
    const char *c = start + 1;
    // libinih ends the header at the first ']' unless an inline comment starts before it.
    for (; *c && *c != ']'; ++c) {
        if (was_space && (*c == ';' || *c == '#'))
            break;
        was_space = isspace((unsigned char)*c);
        inner[length++] = *c;
    }
    inner[length] = '\0';
    if (*c != ']') {
        bdl_scene_fail(p, &(bdl_scene_where){.line = p->line}, "section header without ']'");
        return;
    }
    const char *rest = skip_space(c + 1);
    if (*rest && *rest != ';' && *rest != '#') {
        bdl_scene_fail(p, &(bdl_scene_where){.line = p->line, .title = inner},
                       "unexpected '%.20s' after ']'", rest);
        return;
    }
    open_section(p, inner, p->line);
}

// ---------------------------------------------------------------------------------------------
// libinih callbacks.

/// fgets-like reader over the in-memory text; counts lines and scans section headers.
static char *read_line(char *buffer, int size, void *stream)
{
    bdl_scene_parser *p = stream;
    if (p->failed || *p->cursor == '\0')
        return NULL;
    const char *newline = strchr(p->cursor, '\n');
    size_t length = newline ? (size_t)(newline - p->cursor) + 1 : strlen(p->cursor);
    p->line++;
    if (length + 1 > (size_t)size || length >= sizeof p->line_text) {
        bdl_scene_fail(p, &(bdl_scene_where){.line = p->line}, "line longer than %d characters",
                       BDL_SCENE_MAX_LINE);
        return NULL;
    }
    memcpy(buffer, p->cursor, length);
    buffer[length] = '\0';
    memcpy(p->line_text, buffer, length + 1);
    p->cursor += length;
    scan_line(p, buffer);
    return p->failed ? NULL : buffer;
}

static int handle_key(void *user, const char *section_name, const char *name, const char *value)
{
    bdl_scene_parser *p = user;
    (void)section_name; // the reader tracks sections itself (libinih truncates long names)
    if (p->failed)
        return 0;
    if (!p->current) {
        bdl_scene_fail(p, &(bdl_scene_where){.line = p->line, .key = name, .value = value},
                       "key outside any section; put it under a [section] header");
        return 0;
    }
    apply_key(p, p->current, name, value ? value : "", p->line);
    return !p->failed;
}

/// libinih's behaviour is configured through globals; set them before every parse so that
/// another user of the library in the process cannot change how scenes read.
static void configure_inih(void)
{
    ini_allow_multiline = false; // an indented line is a key of its own, not a continuation
    ini_allow_bom = true;
    ini_start_comment_prefixes = ";#";
    ini_allow_inline_comments = true;
    ini_inline_comment_prefixes = ";#";
    ini_use_stack = true;
    ini_max_line = BDL_SCENE_MAX_LINE + 3; // + '\r', '\n' and '\0'
    ini_allow_realloc = false;
    ini_stop_on_first_error = true; // report the first problem, not a cascade
    ini_allow_no_value = false;
}

// ---------------------------------------------------------------------------------------------
// --set overrides: "section.key=value", "section.NAME.key=value", "pair.A.B.key=value".

static char *trim(char *s)
{
    while (*s && isspace((unsigned char)*s))
        ++s;
    char *end = s + strlen(s);
    while (end > s && isspace((unsigned char)end[-1]))
        *--end = '\0';
    return s;
}

static void fail_no_such_section(bdl_scene_parser *p, bdl_section_kind kind, const char *title,
                                 const char *key, const char *value, const char *name)
{
    bdl_suggestion suggestion;
    bdl_suggest_init(&suggestion, name);
    for (int i = 0; i < p->section_count; ++i)
        if (p->sections[i].kind == kind)
            bdl_suggest_consider(&suggestion, p->sections[i].names[0]);
    char hint[96];
    bdl_suggest_text(&suggestion, hint, sizeof hint);
    bdl_scene_fail(
        p, &(bdl_scene_where){.line = BDL_LINE_SET, .title = title, .key = key, .value = value},
        "no such section in the scene (--set cannot create sections)%s", hint);
}

static void apply_override(bdl_scene_parser *p, const char *text)
{
    char copy[BDL_SCENE_MAX_LINE + 4];
    bdl_scene_where where = {.line = BDL_LINE_SET, .key = text};
    if (snprintf(copy, sizeof copy, "%s", text) >= (int)sizeof copy) {
        bdl_scene_fail(p, &where, "override longer than %d characters", BDL_SCENE_MAX_LINE);
        return;
    }
    char *equals = strchr(copy, '=');
    if (!equals) {
        bdl_scene_fail(p, &where, "expected section.key=value or section.NAME.key=value");
        return;
    }
    *equals = '\0';
    char *value = trim(equals + 1);
    char *words[5];
    int count = 0;
    for (char *s = trim(copy); count < 5; ++count) {
        words[count] = s;
        char *dot = strchr(s, '.');
        if (!dot) {
            ++count;
            break;
        }
        *dot = '\0';
        s = dot + 1;
    }
    int kind = find_kind(words[0], count - 2);
    if (kind < 0) {
        bdl_suggestion suggestion;
        bdl_suggest_init(&suggestion, words[0]);
        for (int k = 0; k < BDL_SECTION_KIND_COUNT; ++k)
            bdl_suggest_consider(&suggestion, bdl_section_infos[k].name);
        char hint[96];
        bdl_suggest_text(&suggestion, hint, sizeof hint);
        bdl_scene_fail(p, &where, "unknown section '%s'%s", words[0], hint);
        return;
    }
    const bdl_section_info *info = &bdl_section_infos[kind];
    if (count != info->name_count + 2) {
        bdl_scene_fail(p, &where, "expected %s%s.key=value", info->name,
                       info->name_count == 0 ? "" : (info->name_count == 1 ? ".NAME" : ".A.B"));
        return;
    }
    char names[2][BDL_NAME_LEN] = {"", ""};
    for (int i = 0; i < info->name_count; ++i)
        snprintf(names[i], BDL_NAME_LEN, "%s", words[i + 1]);
    bdl_scene_section *section = find_section(p, (bdl_section_kind)kind, names);
    if (!section) {
        char title[2 * BDL_NAME_LEN + 16];
        snprintf(title, sizeof title, "%s %s%s%s", info->name, names[0],
                 info->name_count == 2 ? " " : "", names[1]);
        fail_no_such_section(p, (bdl_section_kind)kind, title, words[count - 1], value, names[0]);
        return;
    }
    apply_key(p, section, words[count - 1], value, BDL_LINE_SET);
}

// ---------------------------------------------------------------------------------------------
// Entry points.

static bdl_result load_text(const char *text, const char *name, const char *dir,
                            const char *const *overrides, int override_count, bdl_scene *scene,
                            bdl_scene_error *err)
{
    err->message[0] = '\0';
    bdl_scene_parser *p = calloc(1, sizeof *p);
    if (!p) {
        snprintf(err->message, sizeof err->message, "%s: out of memory reading the scene", name);
        return BDL_ERR_NOMEM;
    }
    bdl_scene_defaults(scene);
    snprintf(scene->dir, sizeof scene->dir, "%s", dir);
    p->scene = scene;
    p->err = err;
    p->file = name;
    p->cursor = text;
    if ((unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB &&
        (unsigned char)text[2] == 0xBF)
        p->cursor += 3; // UTF-8 byte order mark
    // The unnamed sections always exist, so --set run.end_time=1 works without a [run] header.
    for (int kind = 0; kind < BDL_SECTION_KIND_COUNT; ++kind) {
        if (bdl_section_infos[kind].name_count != 0)
            continue;
        bdl_scene_section *s = &p->sections[p->section_count++];
        s->kind = (bdl_section_kind)kind;
        snprintf(s->title, sizeof s->title, "%s", bdl_section_infos[kind].name);
    }
    configure_inih();
    int status = ini_parse_stream(read_line, p, handle_key, p);
    if (status > 0)
        bdl_scene_fail(p, &(bdl_scene_where){.line = status, .value = NULL},
                       "cannot parse '%.60s': expected [section], key = value, or a comment",
                       trim(p->line_text));
    else if (status < 0)
        bdl_scene_fail(p, &(bdl_scene_where){.line = 1}, "the INI reader failed (%d)", status);
    for (int i = 0; i < override_count && !p->failed; ++i)
        apply_override(p, overrides[i]);
    if (!p->failed)
        bdl_scene_validate(p);
    bdl_result result = p->failed ? BDL_ERR_SCENE : BDL_OK;
    free(p);
    return result;
}

bdl_result bdl_scene_load_string(const char *text, const char *name, const char *const *overrides,
                                 int override_count, bdl_scene *scene, bdl_scene_error *err)
{
    return load_text(text, name ? name : "<string>", ".", overrides, override_count, scene, err);
}

bdl_result bdl_scene_load(const char *path, const char *const *overrides, int override_count,
                          bdl_scene *scene, bdl_scene_error *err)
{
    bdl_scene_defaults(scene);
    if (strlen(path) >= BDL_PATH_LEN) {
        snprintf(err->message, sizeof err->message, "%.80s...: path longer than %d characters",
                 path, BDL_PATH_LEN - 1);
        return BDL_ERR_SCENE;
    }
    // Asked before opening: a FIFO would block the reader and /dev/zero would never end.
    char why[WHY_LEN];
    long bytes = 0;
    if (bdl_check_regular_file(path, &bytes, why, sizeof why) != BDL_OK) {
        snprintf(err->message, sizeof err->message, "%s %s; a scene is read from a file", path,
                 why);
        return BDL_ERR_SCENE;
    }
    if (bytes > BDL_SCENE_MAX_BYTES) {
        snprintf(err->message, sizeof err->message,
                 "%s: %ld bytes; a scene file is at most %d bytes of text", path, bytes,
                 BDL_SCENE_MAX_BYTES);
        return BDL_ERR_SCENE;
    }
    size_t length = 0;
    errno = 0;
    char *text = bdl_read_file(path, &length);
    if (!text) {
        snprintf(err->message, sizeof err->message, "%s: cannot read the scene file: %s", path,
                 strerror(errno));
        return BDL_ERR_SCENE;
    }
    if (strlen(text) != length) {
        int line = 1;
        for (const char *c = text; *c; ++c)
            line += *c == '\n';
        snprintf(err->message, sizeof err->message, "%s:%d: NUL byte in the file: not a text file",
                 path, line);
        free(text);
        return BDL_ERR_SCENE;
    }
    // The folder of the file anchors relative paths in the scene ([create] file).
    char dir[BDL_PATH_LEN];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else
        slash[slash == dir ? 1 : 0] = '\0';
    bdl_result result = load_text(text, path, dir, overrides, override_count, scene, err);
    snprintf(scene->path, sizeof scene->path, "%s", path);
    free(text);
    return result;
}
