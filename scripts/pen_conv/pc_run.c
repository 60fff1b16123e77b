/* scratch driver (pen-conv2): gelatin deck at dx1 = d/N with options,
 * string substitutions on the deck, stop rule of pen_sph_setup_run.
 * usage: pc_run N [key=val ...] [sub='old|new' ...]
 * keys: av_a av_b avlen xsph A B E nu fail hf (h_factor) rad (sphere radius add, in dx1)
 *       gap (in m) tend (s) width out (csv path) */
#include "validation/pen_sph_setup.h"
#include "validation/lattice_cases.h"
#include "core/fields.h"
#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "models/sph/sph.h"
#include "spall/error.h"
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int subst(char *buf, size_t len, const char *old, const char *nw)
{
    char *p = strstr(buf, old);
    if (!p) return -1;
    size_t lo = strlen(old), ln = strlen(nw), rest = strlen(p + lo);
    if (strlen(buf) - lo + ln + 1 > len) return -2;
    memmove(p + ln, p + lo, rest + 1);
    memcpy(p, nw, ln);
    return 0;
}

int main(int argc, char **argv)
{
    double N = atof(argv[1]);
    struct pen_sph_target t = pen_sph_target_gelatin(20e6);
    struct pen_sph_shot s = {7.38e-6, 1850.0, 1290.0};
    struct pen_sph_grid g = {.dx1_d = 1.0 / N, .width = 1.0, .depth = 1.0, .t_end = 320e-9,
                             .cavity_depth = 15e-6, .k_first_contact = 1};
    double hf = 1.3, rad = 0.0, stopv = 1, probe = 0;
    const char *out = NULL;
    char *subs[32]; int ns = 0;
    for (int a = 2; a < argc; a++) {
        char *eq = strchr(argv[a], '=');
        if (!eq) { fprintf(stderr, "bad arg %s\n", argv[a]); return 2; }
        *eq = 0; const char *k = argv[a]; const char *v = eq + 1; double x = atof(v);
        if (!strcmp(k, "av_a")) t.av_a = x; else if (!strcmp(k, "av_b")) t.av_b = x;
        else if (!strcmp(k, "avlen")) t.av_length = x; else if (!strcmp(k, "xsph")) t.xsph = x;
        else if (!strcmp(k, "A")) t.A = x; else if (!strcmp(k, "B")) t.B = x;
        else if (!strcmp(k, "E")) t.E = x; else if (!strcmp(k, "nu")) t.nu = x;
        else if (!strcmp(k, "fail")) t.fail = x; else if (!strcmp(k, "hf")) hf = x;
        else if (!strcmp(k, "rad")) rad = x; else if (!strcmp(k, "tend")) g.t_end = x;
        else if (!strcmp(k, "width")) g.width = x; else if (!strcmp(k, "out")) out = v;
        else if (!strcmp(k, "stop")) stopv = x;
        else if (!strcmp(k, "probe")) probe = x;
        else if (!strcmp(k, "sc")) g.surface_contact = (int)x;
        else if (!strcmp(k, "sub")) subs[ns++] = (char *)v;
        else { fprintf(stderr, "unknown key %s\n", k); return 2; }
    }
    struct spall_error err = {0};
    static char deck[16384];
    if (pen_sph_setup_deck(deck, sizeof deck, &t, &s, &g, &err)) { fprintf(stderr, "%s\n", err.msg); return 1; }
    char tmp[128];
    if (hf != 1.3) { snprintf(tmp, sizeof tmp, "h_factor: %g", hf); subst(deck, sizeof deck, "h_factor: 1.3", tmp); }
    double dx1 = s.d / N;
    if (rad != 0.0) {
        char old[64]; snprintf(old, sizeof old, "radius: %.9g", 0.5 * s.d);
        snprintf(tmp, sizeof tmp, "radius: %.9g", 0.5 * s.d + rad * dx1);
        if (subst(deck, sizeof deck, old, tmp)) { fprintf(stderr, "radius sub failed\n"); return 1; }
        /* keep the gap: move the centre up by the same amount */
        snprintf(old, sizeof old, "position: [0, %.9g]", 0.5 * s.d + pen_sph_setup_gap(&s));
        snprintf(tmp, sizeof tmp, "position: [0, %.9g]", 0.5 * s.d + rad * dx1 + pen_sph_setup_gap(&s));
        if (subst(deck, sizeof deck, old, tmp)) { fprintf(stderr, "pos sub failed\n"); return 1; }
    }
    for (int k = 0; k < ns; k++) {
        char *bar = strchr(subs[k], '|');
        if (!bar) return 2;
        *bar = 0;
        if (subst(deck, sizeof deck, subs[k], bar + 1)) { fprintf(stderr, "sub '%s' not found\n", subs[k]); return 1; }
    }
    if (getenv("PC_DECK")) fputs(deck, stderr);
    struct sim *sim = NULL;
    if (vlat_build("pc", deck, &sim, &err)) { fprintf(stderr, "%s\n", err.msg); return 1; }
    const struct impactor *im = &sim->rigid->im[0];
    const double R = im->radius, gap = pen_sph_setup_gap(&s), t_contact = gap / s.v0;
    const double e_in = 0.5 * im->mass * s.v0 * s.v0;
    FILE *f = out ? fopen(out, "w") : NULL;
    if (f) fprintf(f, "t_ns,P_um,V,F,D1_um\n");
    double pmax = -1, tpm = 0, marks[] = {25e-9, 50e-9, 100e-9, 150e-9, 200e-9, 250e-9, 300e-9};
    double pm[7]; int km = 0; for (int k = 0; k < 7; k++) pm[k] = NAN;
    double t0 = omp_get_wtime(), d1max = 0;
    double Pprev = 0, tprev = 0;
    while (!sim_done(sim)) {
        if (sim_step(sim, &err)) { fprintf(stderr, "%s\n", err.msg); break; }
        const double P = -(im->x[1] - R) , tc = sim->t - t_contact;
        /* P is the tip depth for the enlarged sphere too: tip = centre - R */
        while (km < 7 && tc >= marks[km]) {
            pm[km] = Pprev + (P - Pprev) * (marks[km] - tprev) / (tc - tprev);
            km++;
        }
        if (probe > 0) {
            static const double pt[] = {1e-9, 2e-9, 3.5e-9, 5e-9, 7.5e-9, 10e-9, 25e-9};
            static int kp = 0;
            if (kp < 7 && tc >= pt[kp]) {
                /* splash: gel above the initial surface (z > 0) */
                const struct particles *pp = sim->p;
                double ms = 0, pzs = 0, kes = 0, pzall = 0, keall = 0;
                for (size_t i = 0; i < pp->n_owned; i++) {
                    double mi = pp->mass[i], vr = pp->v[0][i], vz = pp->v[1][i];
                    pzall += mi * vz;
                    keall += 0.5 * mi * (vr * vr + vz * vz);
                    if (pp->x[1][i] > 0.0) {
                        ms += mi;
                        pzs += mi * vz;
                        kes += 0.5 * mi * (vr * vr + vz * vz);
                    }
                }
                printf("probe t=%.1fns P=%.3f V=%.1f splash: m/M=%.4f pz/(M v0)=%.4f KE/e_in=%.4f | gel pz/(M v0)=%.4f KE/e_in=%.4f\n",
                       tc * 1e9, P * 1e6, -im->v[1], ms / im->mass, pzs / (im->mass * s.v0), kes / e_in,
                       pzall / (im->mass * s.v0), keall / e_in);
                kp++;
            }
        }
        Pprev = P; tprev = tc;
        if (P > pmax) { pmax = P; tpm = tc; }
        double d1 = vlat_history(sim, "cavity_D1 [m]");
        if (d1 > d1max) d1max = d1;
        if (f && sim->step % 10 == 0)
            fprintf(f, "%.4f,%.5f,%.3f,%.5g,%.4f\n", tc * 1e9, P * 1e6, -im->v[1], im->f_pen[1], d1 * 1e6);
        if (stopv > 0 && tc > 0.0 && !(im->v[1] < 0.0)) break;
    }
    double secs = omp_get_wtime() - t0;
    sim_update_energy(sim);
    /* partition of the energy among the gel */
    const struct model *m = sim->model;
    const struct particles *p = sim->p;
    /* the model's per-particle state from the field registry */
    const double *e = field_stored_data(sim->fields, "internal_energy", 0);
    const double *rho = field_stored_data(sim->fields, "density", 0);
    const double *P = field_stored_data(sim->fields, "pressure", 0);
    const double *ep = field_stored_data(sim->fields, "plastic_strain", 0);
    const uint8_t *failed = field_stored_data(sim->fields, "failed", 0);
    const double *S[6];
    for (int c = 0; c < 6; c++)
        S[c] = field_stored_data(sim->fields, "deviatoric_stress", c);
    double Ei = 0, Ek = 0, Wp = 0, Edev = 0, Evol = 0;
    for (size_t i = 0; i < p->n_owned; i++) {
        const struct sph_material *mt = sph_material_get(m, p->material[i]);
        Ei += p->mass[i] * e[i];
        Ek += 0.5 * p->mass[i] * (p->v[0][i] * p->v[0][i] + p->v[1][i] * p->v[1][i]);
        Wp += sph_plastic_work(m, i);
        double S2 = 0;
        for (int c = 0; c < 3; c++) S2 += S[c][i] * S[c][i];
        S2 += 2 * S[3][i] * S[3][i];
        Edev += p->mass[i] / rho[i] * S2 / (4 * mt->G);
        Evol += p->mass[i] / rho[i] * P[i] * P[i] / (2 * mt->K);
    }
    /* plastic zone at rest (pen-conv3): the gelatin deck has no failure, so
     * the zone where the gel yielded (ep > 1 %) stands in for a "failed
     * zone": its volume (sum m/rho) and its radial reach at the cavity
     * depth 15 um (|z + 15 um| < 0.5 um), to see whether they scale with dx */
    double vpl = 0, rpl = 0, d1end = vlat_history(sim, "cavity_D1 [m]");
    size_t npl = 0;
    for (size_t i = 0; i < p->n_owned; i++) {
        if (!(ep[i] > 0.01)) continue;
        npl++;
        vpl += p->mass[i] / rho[i];
        if (fabs(p->x[1][i] + 15e-6) < 0.5e-6 && p->x[0][i] > rpl) rpl = p->x[0][i];
    }
    size_t nfail = 0;
    double vfail = 0;
    for (size_t i = 0; i < p->n_owned; i++)
        if (failed && failed[i]) {
            nfail++;
            vfail += p->mass[i] / rho[i];
        }
    printf("plastic(ep>0.01): n=%zu vol=%.4g r_reach(15um)=%.2f um D1end/2=%.2f um width=%.2f um | "
           "failed: n=%zu vol=%.4g\n",
           npl, vpl, rpl * 1e6, 0.5 * d1end * 1e6, (rpl - 0.5 * d1end) * 1e6, nfail, vfail);
    printf("N=%g n=%zu Pmax=%.3f t=%.1f P25=%.3f P50=%.3f P100=%.3f P150=%.3f P200=%.3f P250=%.3f P300=%.3f "
           "D1max=%.2f bal=%.4f | Ei=%.3f Wp=%.3f Edev=%.3f Evol=%.3f AVheat~%.3f Ekgel=%.3f (frac of e_in) secs=%.0f\n",
           N, p->n_owned, pmax * 1e6, tpm * 1e9, pm[0] * 1e6, pm[1] * 1e6, pm[2] * 1e6, pm[3] * 1e6, pm[4] * 1e6,
           pm[5] * 1e6, pm[6] * 1e6, d1max * 1e6, sim->energy.balance / e_in, Ei / e_in, Wp / e_in, Edev / e_in, Evol / e_in,
           (Ei - Wp - Edev - Evol) / e_in, Ek / e_in, secs);
    if (f) fclose(f);
    sim_destroy(&sim);
    return 0;
}
