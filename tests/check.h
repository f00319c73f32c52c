// bedlam — a tiny test harness: each test is an executable registered with ctest.
//
// CHECK records a failure and goes on; CHECK_CLOSE compares with a relative tolerance.
// Return bdl_test_summary() from main: it prints the count and gives the exit code.
#ifndef BDL_TEST_CHECK_H
#define BDL_TEST_CHECK_H

#include <math.h>
#include <stdio.h>

static int bdl_test_failures = 0;
static int bdl_test_checks = 0;

#define CHECK(cond)                                                                                \
    do {                                                                                           \
        ++bdl_test_checks;                                                                         \
        if (!(cond)) {                                                                             \
            ++bdl_test_failures;                                                                   \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);               \
        }                                                                                          \
    } while (0)

#define CHECK_MSG(cond, ...)                                                                       \
    do {                                                                                           \
        ++bdl_test_checks;                                                                         \
        if (!(cond)) {                                                                             \
            ++bdl_test_failures;                                                                   \
            fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond);               \
            fprintf(stderr, __VA_ARGS__);                                                          \
            fputc('\n', stderr);                                                                   \
        }                                                                                          \
    } while (0)

/// |actual - expected| <= rel * |expected| (or <= rel when expected is 0).
#define CHECK_CLOSE(actual, expected, rel)                                                         \
    do {                                                                                           \
        double a_ = (actual), e_ = (expected), r_ = (rel);                                         \
        double tol_ = e_ != 0.0 ? r_ * fabs(e_) : r_;                                              \
        ++bdl_test_checks;                                                                         \
        if (!(fabs(a_ - e_) <= tol_)) {                                                            \
            ++bdl_test_failures;                                                                   \
            fprintf(stderr,                                                                        \
                    "%s:%d: CHECK_CLOSE failed: %s = %.10g, expected %.10g (rel tol %g)\n",        \
                    __FILE__, __LINE__, #actual, a_, e_, r_);                                      \
        }                                                                                          \
    } while (0)

static inline int bdl_test_summary(const char *name)
{
    printf("%s: %d checks, %d failed\n", name, bdl_test_checks, bdl_test_failures);
    return bdl_test_failures == 0 ? 0 : 1;
}

#endif
