#include "core/error.h"

static const char *const result_texts[BDL_RESULT_COUNT] = {
#define BDL_X_TEXT(name, text) text,
    BDL_RESULTS(BDL_X_TEXT)
#undef BDL_X_TEXT
};

const char *bdl_result_text(bdl_result r)
{
    if ((int)r < 0 || r >= BDL_RESULT_COUNT)
        return "unknown result";
    return result_texts[r];
}
