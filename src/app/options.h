// bedlam — option tables: a subcommand's options as rows of a name, what the value is and the
// field of the subcommand's options struct it goes to, so that a parser is one loop over argv.
#ifndef BDL_OPTIONS_H
#define BDL_OPTIONS_H

#include <stddef.h>

#include "core/error.h"

typedef enum bdl_option_kind {
    BDL_OPTION_TEXT,   ///< const char *: the value as given
    BDL_OPTION_NUMBER, ///< double: atof of the value
    BDL_OPTION_LONG,   ///< long: atol of the value
    BDL_OPTION_INT,    ///< int: atoi of the value
    BDL_OPTION_SET,    ///< int set to 1; takes no value
    BDL_OPTION_CLEAR,  ///< int set to 0; takes no value
} bdl_option_kind;

typedef struct bdl_option {
    const char *name; ///< "--name"
    bdl_option_kind kind;
    size_t field; ///< offsetof the field in the options struct
} bdl_option;

#define BDL_OPTION_COUNT(table) (sizeof(table) / sizeof((table)[0]))

/// The row of `table` named `name`, or NULL.
const bdl_option *bdl_option_find(const bdl_option *table, size_t count, const char *name);

/// Sets the option of `table` named `name` in the options struct at `opts` from `value` (NULL
/// when the command line has no argument left). Returns the arguments it took: 2 for an option
/// with its value, 1 for a flag, 0 when the table has no such option or its value is missing.
int bdl_option_set(const bdl_option *table, size_t count, void *opts, const char *name,
                   const char *value);

/// The argument is --help or -h.
int bdl_option_is_help(const char *arg);

/// A subcommand's parser: its table, its usage, and what it does with the other arguments.
typedef struct bdl_option_parser {
    const bdl_option *table;
    size_t count;
    const char *usage; ///< printed on stdout for --help
    int long_help;     ///< only --help asks for help; -h is an argument like any other
    /// An argument the table does not take (at argv[i]): returns the arguments it took (>= 1),
    /// or 0 after printing why it refuses it.
    int (*other)(void *opts, int argc, char **argv, int i);
} bdl_option_parser;

/// Reads argv[first..argc) into the options struct at `opts`. --help (or -h) prints the usage
/// and ends the parse with *help set; BDL_ERR_ARGS when `other` refuses an argument.
bdl_result bdl_option_parse(const bdl_option_parser *parser, int argc, char **argv, int first,
                            void *opts, int *help);

#endif
