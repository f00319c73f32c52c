// bedlam — option tables.
#include "app/options.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const bdl_option *bdl_option_find(const bdl_option *table, size_t count, const char *name)
{
    for (size_t k = 0; k < count; ++k)
        if (strcmp(name, table[k].name) == 0)
            return &table[k];
    return NULL;
}

int bdl_option_set(const bdl_option *table, size_t count, void *opts, const char *name,
                   const char *value)
{
    const bdl_option *opt = bdl_option_find(table, count, name);
    const int flag = opt && (opt->kind == BDL_OPTION_SET || opt->kind == BDL_OPTION_CLEAR);
    if (!opt || (!flag && !value))
        return 0;
    void *field = (char *)opts + opt->field;
    switch (opt->kind) {
    case BDL_OPTION_SET:
    case BDL_OPTION_CLEAR:
        *(int *)field = opt->kind == BDL_OPTION_SET;
        return 1;
    case BDL_OPTION_TEXT:
        *(const char **)field = value;
        break;
    case BDL_OPTION_NUMBER:
        *(double *)field = atof(value);
        break;
    case BDL_OPTION_LONG:
        *(long *)field = atol(value);
        break;
    case BDL_OPTION_INT:
        *(int *)field = atoi(value);
        break;
    }
    return 2;
}

int bdl_option_is_help(const char *arg)
{
    return strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0;
}

bdl_result bdl_option_parse(const bdl_option_parser *parser, int argc, char **argv, int first,
                            void *opts, int *help)
{
    *help = 0;
    for (int i = first, used; i < argc; i += used) {
        const char *a = argv[i], *value = i + 1 < argc ? argv[i + 1] : NULL;
        if (parser->long_help ? strcmp(a, "--help") == 0 : bdl_option_is_help(a)) {
            fputs(parser->usage, stdout);
            *help = 1;
            return BDL_OK;
        }
        used = bdl_option_set(parser->table, parser->count, opts, a, value);
        if (used == 0 && (used = parser->other(opts, argc, argv, i)) == 0)
            return BDL_ERR_ARGS;
    }
    return BDL_OK;
}
