// bedlam — private interface of the scene reader (scene_keys.c, scene_parse.c,
// scene_validate.c) and of its tests.
//
// Every key a scene file may contain is one row of bdl_scene_keys[]: its section, type, unit,
// default, allowed range, the struct field it fills and one line of documentation. The parser,
// the "did you mean" hints, the generic required/applicability checks and the documentation
// test all read that table, so a key is added in exactly one place.
#ifndef BDL_SCENE_INTERNAL_H
#define BDL_SCENE_INTERNAL_H

#include <stddef.h>

#include "scene/scene.h"

/// Kinds of sections. The first five are unnamed singletons that always exist.
typedef enum bdl_section_kind {
    BDL_SECTION_RUN = 0,
    BDL_SECTION_DOMAIN,
    BDL_SECTION_CONTACT,
    BDL_SECTION_OUTPUT,
    BDL_SECTION_GUARDS,
    BDL_SECTION_CAMERA,
    BDL_SECTION_GAS,
    BDL_SECTION_COUPLING,
    BDL_SECTION_PARCELS,
    BDL_SECTION_SOLIDS,
    BDL_SECTION_SPECIES,
    BDL_SECTION_PAIR,
    BDL_SECTION_WALL,
    BDL_SECTION_CREATE,
    BDL_SECTION_DIA, ///< [camera NAME]: the same word as [camera], with a name
    BDL_SECTION_SINK,
    BDL_SECTION_PHASE,    ///< [phase NAME]: a phase of a [solids] mixture
    BDL_SECTION_PARALLEL, ///< [parallel]: how a run is divided between MPI ranks
    BDL_SECTION_KIND_COUNT
} bdl_section_kind;

/// Static description of a section kind.
typedef struct bdl_section_info {
    const char *name;  ///< word in the header: "species"
    const char *usage; ///< header as documented: "species NAME"
    int name_count;    ///< names after the word: 0 (singleton), 1, or 2 (pair)
    int max_count;     ///< BDL_MAX_* limit (1 for singletons)
} bdl_section_info;

typedef enum bdl_key_type {
    BDL_KEY_NUMBER = 0, ///< double
    BDL_KEY_VECTOR,     ///< bdl_vec3, three numbers separated by spaces
    BDL_KEY_INT,        ///< int
    BDL_KEY_LONG,       ///< long
    BDL_KEY_U64,        ///< uint64_t
    BDL_KEY_BOOL,       ///< int 0/1 from true/false/yes/no/on/off/1/0
    BDL_KEY_ENUM,       ///< int index into enum_names (the C enums are declared in that order)
    BDL_KEY_AXES,       ///< int[3] from "none" or axis letters "x y"
    BDL_KEY_NAME,       ///< char[BDL_NAME_LEN], a section name reference
    BDL_KEY_PATH,       ///< char[BDL_PATH_LEN], resolved against the scene folder
} bdl_key_type;

typedef enum bdl_bound {
    BDL_BOUND_NONE = 0,
    BDL_BOUND_OPEN,   ///< strict: > lo, < hi
    BDL_BOUND_CLOSED, ///< inclusive: >= lo, <= hi
} bdl_bound;

/// `required` value meaning "always, whatever the selector says".
#define BDL_REQUIRED_ALWAYS 0xffffffffu

/// Where the key's value is stored.
typedef enum bdl_key_target {
    BDL_TARGET_STRUCT = 0, ///< offset into the section's struct (bdl_scene for singletons)
    BDL_TARGET_RECORD,     ///< offset into bdl_scene_section (values only needed while validating)
} bdl_key_target;

typedef struct bdl_scene_key {
    bdl_section_kind section;
    const char *name;
    bdl_key_type type;
    const char *unit; ///< SI unit, "-" for dimensionless
    bdl_key_target target;
    size_t offset;
    int has_flag; ///< 1: an int flag at flag_offset is set to 1 when the key is given
    size_t flag_offset;
    int normalise;     ///< vector keys: a direction, must be nonzero, stored as a unit vector
    double max_length; ///< vector keys: the largest length allowed (0: any)
    double def[3];     ///< default: numbers use def[0], enums the index; names/paths are ""
    const char *default_text; ///< overrides the text generated from def (docs and messages)
    bdl_bound lo_kind, hi_kind;
    double lo, hi;
    const char *const *enum_names; ///< NULL-terminated, for BDL_KEY_ENUM
    /// Name of an enum key of the same section that decides whether this key applies
    /// (e.g. "type" for wall keys); NULL when the key always applies.
    const char *selector;
    unsigned applies;  ///< bit (1u << selector value) per value where the key may be given
    unsigned required; ///< bits where the key is required, or BDL_REQUIRED_ALWAYS, or 0
    const char *doc;
} bdl_scene_key;

extern const bdl_scene_key bdl_scene_keys[];
extern const int bdl_scene_key_count;
extern const bdl_section_info bdl_section_infos[BDL_SECTION_KIND_COUNT];

#define BDL_SCENE_KEY_CAPACITY 256
#define BDL_SCENE_MAX_SECTIONS                                                                     \
    (BDL_SECTION_SPECIES + BDL_MAX_SPECIES + BDL_MAX_PAIRS + BDL_MAX_WALLS + BDL_MAX_CREATES +     \
     BDL_MAX_DIA + BDL_MAX_SINKS + BDL_SOLIDS_PHASES)
/// Line number recorded for a value that came from a --set override.
#define BDL_LINE_SET (-1)
/// Longest line accepted in a scene file (characters, without the newline).
#define BDL_SCENE_MAX_LINE 4096
/// Largest scene file read (bytes): scenes are a few kilobytes; the bound keeps a huge file from
/// being read into memory whole.
#define BDL_SCENE_MAX_BYTES (16 << 20)

/// Parse-time record of one section: where it was written and which keys were given.
typedef struct bdl_scene_section {
    bdl_section_kind kind;
    int index; ///< into scene->species / pairs / walls / creates (0 for singletons)
    int line;  ///< header line; 0 if the section is not in the file (singletons)
    char title[2 * BDL_NAME_LEN + 16];    ///< "species glass", for messages
    char names[2][BDL_NAME_LEN];          ///< the names after the section word
    int key_line[BDL_SCENE_KEY_CAPACITY]; ///< per key (table index): 0 not given, line, or --set
    // Values held here rather than in bdl_scene (BDL_TARGET_RECORD keys):
    double gamma;                   ///< [wall] dimensionless peak acceleration A w^2 / g
    char species_ref[BDL_NAME_LEN]; ///< [create] species name, resolved while validating
} bdl_scene_section;

typedef struct bdl_scene_parser {
    bdl_scene *scene;
    bdl_scene_error *err;
    const char *file;                       ///< name used in messages
    const char *cursor;                     ///< next unread character of the text
    int line;                               ///< lines handed to libinih so far
    char line_text[BDL_SCENE_MAX_LINE + 4]; ///< the last line handed over (for messages)
    int failed;
    bdl_scene_section *current; ///< section the following keys belong to
    int section_count;
    bdl_scene_section sections[BDL_SCENE_MAX_SECTIONS];
} bdl_scene_parser;

/// Location and context of a message; every field may be left 0/NULL.
typedef struct bdl_scene_where {
    int line;          ///< > 0 file line, BDL_LINE_SET, or 0 = end of file
    const char *title; ///< section title without brackets
    const char *key;
    const char *value;
    const bdl_scene_key *allowed; ///< appends "; allowed: RANGE (UNIT)"
} bdl_scene_where;

/// Accumulates the closest candidate to a misspelt word.
typedef struct bdl_suggestion {
    const char *typed;
    const char *best;
    int best_score;
} bdl_suggestion;

// scene_keys.c
const bdl_scene_key *bdl_scene_key_find(bdl_section_kind kind, const char *name);
int bdl_scene_key_index(const bdl_scene_key *key);
const char *bdl_scene_key_type_name(bdl_key_type type);
void bdl_scene_key_range_text(const bdl_scene_key *key, char *buf, size_t size);
void bdl_scene_key_default_text(const bdl_scene_key *key, char *buf, size_t size);
void *bdl_scene_key_field(const bdl_scene_key *key, bdl_scene *scene, bdl_scene_section *section);
void bdl_scene_key_value_text(const bdl_scene_key *key, bdl_scene *scene,
                              bdl_scene_section *section, char *buf, size_t size);
void bdl_scene_apply_defaults(bdl_scene *scene, bdl_scene_section *section);
void bdl_suggest_init(bdl_suggestion *s, const char *typed);
void bdl_suggest_consider(bdl_suggestion *s, const char *candidate);
/// "; did you mean 'X'?" or "" when nothing is close.
void bdl_suggest_text(const bdl_suggestion *s, char *buf, size_t size);

// scene_parse.c
void bdl_scene_fail(bdl_scene_parser *p, const bdl_scene_where *where, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

// scene_validate.c
/// Cross-checks and derived values after the file and the overrides; 0 on failure.
int bdl_scene_validate(bdl_scene_parser *p);

#endif
