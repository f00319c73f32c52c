// bedlam — names: of things a scene defines, and of the values of its choices.
//
// Every choice a scene offers (a drag law, a wall kind, a colour mode) is one X-macro list
// beside the enum it generates, with a row per value: X(NAME, "word", "label"). The enum
// (BDL_NAME), the scene words the reader accepts and the labels logs and pictures show are all
// generated from that one list (sokol's _SG_LOG_ITEMS habit), so a value is added in one place:
//
//   #define BDL_SHAPES(X) X(SHAPE_SPHERE, "sphere", "sphere")
//   BDL_CHOICES(bdl_shape, BDL_SHAPES);         in the header: enum bdl_shape, bdl_shape_names
//   BDL_CHOICE_WORDS(bdl_shape, BDL_SHAPES);    in one source file: the words
#ifndef BDL_NAMES_H
#define BDL_NAMES_H

#include <stddef.h> // NULL, which ends the generated word lists

/// Longest name of a species, wall, creator or camera, with its terminator.
#define BDL_NAME_LEN 32
/// Longest path a scene refers to, with its terminator.
#define BDL_PATH_LEN 512

#define BDL_ENUM_ITEM(name, word, label)  BDL_##name,
#define BDL_ENUM_WORD(name, word, label)  word,
#define BDL_ENUM_LABEL(name, word, label) label,

/// Declares enum `type` from an X-macro list, and `type`_names: the scene words of its values in
/// enum order, NULL-terminated (defined by BDL_CHOICE_WORDS in one source file).
#define BDL_CHOICES(type, list)                                                                    \
    typedef enum type { list(BDL_ENUM_ITEM) } type;                                                \
    extern const char *const type##_names[]
#define BDL_CHOICE_WORDS(type, list) const char *const type##_names[] = {list(BDL_ENUM_WORD) NULL}

#endif
