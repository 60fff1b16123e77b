/**
 * The error agreement's pieces that need no second rank (core/parallel/
 * comm.h; the ranks themselves: tests/cli/mpi_fault.sh): SPALL_FAULT's
 * site:rank list names exactly its sites on this rank (rank 0 without
 * mpirun), and an agreement on one rank hands the status through and
 * leaves the record as it was.
 */
#define _POSIX_C_SOURCE 200809L /* setenv, unsetenv */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "core/parallel/comm.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

static int fault_with(const char *spec, const char *site, struct spall_error *err)
{
    setenv("SPALL_FAULT", spec, 1);
    int rc = par_fault(site, err);
    unsetenv("SPALL_FAULT");
    return rc;
}

static void test_fault_sites(void **state)
{
    (void)state;
    struct spall_error err = {0};
    unsetenv("SPALL_FAULT");
    assert_int_equal(par_fault("frame", &err), SPALL_OK);
    assert_int_equal(fault_with("", "frame", &err), SPALL_OK);
    assert_int_equal(err.code, 0);
    /* the named site on this rank (0), in any position of the list */
    assert_int_equal(fault_with("frame:0", "frame", &err), SPALL_ERR_IO);
    assert_non_null(strstr(err.msg, "fault injected at 'frame' on rank 0"));
    spall_error_clear(&err);
    assert_int_equal(fault_with("deck:1,frame:0", "frame", &err), SPALL_ERR_IO);
    assert_int_equal(err.code, SPALL_ERR_IO);
    spall_error_clear(&err);
    /* another rank, another site, a prefix of the site, a malformed rank */
    assert_int_equal(fault_with("frame:1", "frame", &err), SPALL_OK);
    assert_int_equal(fault_with("deck:0", "frame", &err), SPALL_OK);
    assert_int_equal(fault_with("fram:0", "frame", &err), SPALL_OK);
    assert_int_equal(fault_with("frame:0x,frame", "frame", &err), SPALL_OK);
    assert_int_equal(fault_with("frame:", "frame", &err), SPALL_OK);
    assert_int_equal(fault_with("frames:0", "frame", &err), SPALL_OK);
    assert_int_equal(err.code, 0);
    /* a NULL record is allowed: the status alone */
    assert_int_equal(fault_with("restart:0", "restart", NULL), SPALL_ERR_IO);
}

static void test_agree_one_rank(void **state)
{
    (void)state;
    struct spall_error err = {0};
    assert_int_equal(par_agree(SPALL_OK, &err), SPALL_OK);
    spall_error_set(&err, SPALL_ERR_NOMEM, "out of memory");
    assert_int_equal(par_agree(SPALL_ERR_NOMEM, &err), SPALL_ERR_NOMEM);
    assert_int_equal(err.code, SPALL_ERR_NOMEM);
    assert_string_equal(err.msg, "out of memory");
    assert_int_equal(err.agreed, 0); /* one rank: nothing was exchanged */
    err.agreed = 1;
    spall_error_clear(&err);
    assert_int_equal(err.agreed, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fault_sites),
        cmocka_unit_test(test_agree_one_rank),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
