/* Tests for src/core/parallel/h5.c: without mpirun the property lists keep the
 * serial driver, and a file written and read back through them round-trips
 * its data exactly. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/parallel/h5.h"

#include <stdio.h>
#include <unistd.h>

static void serial_lists_are_not_mpio(void **state)
{
    (void)state;
    assert_int_equal(parallel_h5_is_mpio(), 0);
    hid_t fapl = parallel_h5_fapl();
    hid_t dxpl = parallel_h5_dxpl();
    assert_true(fapl >= 0);
    assert_true(dxpl >= 0);
    /* The serial (sec2) driver, as a plain H5P_DEFAULT file would use. */
    assert_true(H5Pget_driver(fapl) == H5FD_SEC2);
    H5Pclose(dxpl);
    H5Pclose(fapl);
}

static void file_round_trip(void **state)
{
    (void)state;
    char path[64];
    snprintf(path, sizeof path, "test_parallel_h5_%ld.h5", (long)getpid());
    const double x[5] = {0.0, -1.5, 3.25e-9, 1e300, 7.0};
    double y[5] = {0};
    hsize_t n = 5;

    hid_t fapl = parallel_h5_fapl(), dxpl = parallel_h5_dxpl();
    assert_true(fapl >= 0 && dxpl >= 0);
    hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    assert_true(f >= 0);
    hid_t sp = H5Screate_simple(1, &n, NULL);
    hid_t ds = H5Dcreate2(f, "x", H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(ds >= 0);
    assert_true(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, dxpl, x) >= 0);
    H5Dclose(ds);
    H5Sclose(sp);
    assert_true(H5Fclose(f) >= 0);

    f = H5Fopen(path, H5F_ACC_RDONLY, fapl);
    assert_true(f >= 0);
    ds = H5Dopen2(f, "x", H5P_DEFAULT);
    assert_true(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, dxpl, y) >= 0);
    H5Dclose(ds);
    H5Fclose(f);
    H5Pclose(dxpl);
    H5Pclose(fapl);
    remove(path);
    assert_memory_equal(x, y, sizeof x);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(serial_lists_are_not_mpio),
        cmocka_unit_test(file_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
