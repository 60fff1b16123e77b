/**
 * @file test_field_state.c
 * @brief The restart state registry (core/field_state.h): slots of every
 *        kind report their rows and data, names are unique, a load into a
 *        slot of another length is refused naming the slot, and a list
 *        slot's set_rows resizes the owner's storage; each slot records
 *        the layout a distributed checkpoint writes it by (pair lists from a
 *        neighbour search: offsets and resizable pair rows).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "core/bond_list.h"
#include "core/field_state.h"
#include "spall/error.h"

struct owner {
    int32_t *list;
    size_t n;
};

static size_t owner_rows(const void *ctx)
{
    return ((const struct owner *)ctx)->n;
}

static int owner_set_rows(void *ctx, size_t rows, struct spall_error *err)
{
    struct owner *o = ctx;
    int32_t *g = realloc(o->list, (rows ? rows : 1) * sizeof *g);
    if (!g)
        return spall_error_set(err, SPALL_ERR_NOMEM, "oom");
    o->list = g;
    o->n = rows;
    return SPALL_OK;
}

static void test_slots(void **state)
{
    (void)state;
    struct field_state *fs = NULL;
    struct spall_error err = {0};
    assert_int_equal(field_state_create(&fs, &err), 0);
    double *arr = calloc(10, sizeof *arr);
    assert_non_null(arr);
    arr[3] = 7.5;
    double t = 1.25;
    struct owner o = {.list = calloc(4, sizeof(int32_t)), .n = 4};
    assert_non_null(o.list);
    assert_int_equal(field_state_add_array(fs, "a", FIELD_F64, (void **)&arr, 5, 2, &err), 0);
    assert_int_equal(field_state_add_values(fs, "t", FIELD_F64, &t, 1, &err), 0);
    assert_int_equal(field_state_add_list(fs, "l", FIELD_I32, (void **)&o.list, 1, owner_rows,
                                          owner_set_rows, &o, &err),
                     0);
    /* duplicate names are a bug of the owner */
    assert_int_equal(field_state_add_values(fs, "t", FIELD_F64, &t, 1, &err), SPALL_ERR_INTERNAL);
    assert_non_null(strstr(err.msg, "'t' registered twice"));
    assert_int_equal(fs->n, 3);

    const struct field_state_slot *sa = field_state_find(fs, "a");
    assert_non_null(sa);
    assert_int_equal(field_state_slot_rows(sa), 5);
    assert_int_equal(sa->width, 2);
    assert_true(((double *)field_state_slot_data(sa))[3] == 7.5);
    /* the owner reallocates: the slot follows its pointer */
    double *moved = malloc(10 * sizeof *moved);
    assert_non_null(moved);
    memcpy(moved, arr, 10 * sizeof *moved);
    free(arr);
    arr = moved;
    assert_ptr_equal(field_state_slot_data(sa), arr);
    const struct field_state_slot *st = field_state_find(fs, "t");
    assert_ptr_equal(field_state_slot_data(st), &t);
    assert_int_equal(field_state_slot_rows(st), 1);
    assert_null(field_state_find(fs, "nope"));

    /* fixed lengths cannot change; lists can */
    assert_int_equal(field_state_slot_resize(sa, 5, &err), 0);
    assert_int_equal(field_state_slot_resize(sa, 6, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "state 'a' holds 6 rows in the checkpoint, 5 in this run"));
    const struct field_state_slot *sl = field_state_find(fs, "l");
    assert_int_equal(field_state_slot_rows(sl), 4);
    assert_int_equal(field_state_slot_resize(sl, 9, &err), 0);
    assert_int_equal(field_state_slot_rows(sl), 9);
    assert_ptr_equal(field_state_slot_data(sl), o.list);
    ((int32_t *)field_state_slot_data(sl))[8] = 42; /* the new room is the owner's */
    assert_int_equal(o.list[8], 42);

    assert_int_equal(field_state_type_size(FIELD_F64), 8);
    assert_int_equal(field_state_type_size(FIELD_I64), 8);
    assert_int_equal(field_state_type_size(FIELD_I32), 4);
    assert_int_equal(field_state_type_size(FIELD_U8), 1);
    field_state_destroy(&fs);
    assert_null(fs);
    free(arr);
    free(o.list);
}

/* The distributed writer (io/checkpoint_par.c) places rows by layout: per
 * owned particle at its global id, per half-bond at the serial bond-row
 * offset, values from rank 0; a slot in a run's own order cannot be placed. */
static void test_layouts(void **state)
{
    (void)state;
    struct field_state *fs = NULL;
    struct spall_error err = {0};
    assert_int_equal(field_state_create(&fs, &err), 0);
    size_t offset[4] = {0, 2, 5, 5}; /* three particles, the last one's row empty */
    struct bond_list bl = {.n = 3, .offset = offset};
    double *per_p = calloc(3 * 2, sizeof *per_p), *per_b = calloc(5, sizeof *per_b);
    uint8_t *loc = calloc(4, 1);
    double t = 0.0;
    assert_non_null(per_p);
    assert_non_null(per_b);
    assert_non_null(loc);
    assert_int_equal(field_state_add_particle_array(fs, "p", FIELD_F64, (void **)&per_p, 3, 2,
                                                    &err),
                     0);
    assert_int_equal(field_state_add_bond_array(fs, "b", FIELD_F64, (void **)&per_b, &bl, 1, &err),
                     0);
    assert_int_equal(field_state_add_array(fs, "l", FIELD_U8, (void **)&loc, 4, 1, &err), 0);
    assert_int_equal(field_state_add_values(fs, "t", FIELD_F64, &t, 1, &err), 0);
    const struct field_state_slot *sp = field_state_find(fs, "p"), *sb = field_state_find(fs, "b");
    assert_int_equal(sp->layout, FIELD_STATE_PARTICLE);
    assert_int_equal(field_state_slot_rows(sp), 3);
    assert_int_equal(sp->width, 2);
    assert_int_equal(sb->layout, FIELD_STATE_HALF_BOND);
    assert_ptr_equal(sb->bonds, &bl);
    assert_int_equal(field_state_slot_rows(sb), 5); /* offset[n]: every half-bond */
    assert_int_equal(field_state_find(fs, "l")->layout, FIELD_STATE_LOCAL);
    assert_int_equal(field_state_find(fs, "t")->layout, FIELD_STATE_GLOBAL);
    field_state_destroy(&fs);
    free(per_p);
    free(per_b);
    free(loc);
}

/* Values with a load hook (SPH's count of symmetry-plane images): global
 * like plain values, the hook told the checkpoint's count before a load
 * and free to refuse it. */
static int hook_loaded(void *ctx, size_t rows, struct spall_error *err)
{
    int *seen = ctx;
    if (rows != 1)
        return spall_error_set(err, SPALL_ERR_INPUT, "%zu values", rows);
    (*seen)++;
    return SPALL_OK;
}

static void test_values_hook(void **state)
{
    (void)state;
    struct field_state *fs = NULL;
    struct spall_error err = {0};
    assert_int_equal(field_state_create(&fs, &err), 0);
    int64_t v = 42;
    int seen = 0;
    assert_int_equal(field_state_add_values_hook(fs, "v", FIELD_I64, &v, 1, hook_loaded, &seen,
                                                 &err),
                     0);
    const struct field_state_slot *sv = field_state_find(fs, "v");
    assert_int_equal(sv->layout, FIELD_STATE_GLOBAL);
    assert_int_equal(field_state_slot_rows(sv), 1);
    assert_ptr_equal(field_state_slot_data(sv), &v);
    assert_int_equal(seen, 0); /* registering is no load */
    assert_int_equal(field_state_slot_resize(sv, 1, &err), 0);
    assert_int_equal(seen, 1);
    assert_int_equal(field_state_slot_resize(sv, 2, &err), SPALL_ERR_INPUT);
    assert_string_equal(err.msg, "2 values");
    assert_int_equal(seen, 1);
    field_state_destroy(&fs);
}

/* A pair list from a neighbour search (macro-particles, contact): its
 * offsets are placed per owned particle plus the total, its pairs by the
 * rows of the list itself, and a load resizes the pair arrays. */
static void test_pair_list(void **state)
{
    (void)state;
    struct field_state *fs = NULL;
    struct spall_error err = {0};
    assert_int_equal(field_state_create(&fs, &err), 0);
    size_t *offset = malloc(4 * sizeof *offset);
    assert_non_null(offset);
    offset[0] = 0;
    offset[1] = 3;
    offset[2] = 3;
    offset[3] = 4;
    struct bond_list bl = {.n = 3, .offset = offset};
    struct owner o = {.list = calloc(4, sizeof(int32_t)), .n = 4};
    assert_non_null(o.list);
    assert_int_equal(field_state_add_offsets(fs, "off", (void **)&offset, &bl, &err), 0);
    assert_int_equal(field_state_add_bond_list(fs, "pairs", FIELD_I32, (void **)&o.list, &bl, 1,
                                               owner_set_rows, &o, &err),
                     0);
    const struct field_state_slot *so = field_state_find(fs, "off");
    const struct field_state_slot *sl = field_state_find(fs, "pairs");
    assert_int_equal(so->layout, FIELD_STATE_OFFSETS);
    assert_int_equal(so->type, FIELD_I64);
    assert_int_equal(field_state_slot_rows(so), 4); /* n + 1 */
    assert_ptr_equal(so->bonds, &bl);
    assert_ptr_equal(field_state_slot_data(so), offset);
    assert_int_equal(sl->layout, FIELD_STATE_HALF_BOND);
    assert_int_equal(field_state_slot_rows(sl), 4); /* offset[n] at registration */
    assert_ptr_equal(sl->bonds, &bl);
    /* the offsets' length is fixed by the particles; the pairs' is not */
    assert_int_equal(field_state_slot_resize(so, 5, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "'off'"));
    assert_int_equal(field_state_slot_resize(sl, 9, &err), 0);
    assert_int_equal(o.n, 9);
    assert_ptr_equal(field_state_slot_data(sl), o.list);
    field_state_destroy(&fs);
    free(offset);
    free(o.list);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_slots),
                                       cmocka_unit_test(test_layouts),
                                       cmocka_unit_test(test_values_hook),
                                       cmocka_unit_test(test_pair_list)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
