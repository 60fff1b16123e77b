/**
 * @file penetration.h
 * @brief Analytical models of a rigid sphere penetrating a soft target
 *        ([Meng2021] chapter 4.2): Poncelet, Liu, Modified Clift-Gauvin;
 *        closed forms, ODE integration (GSL odeiv2) and coefficient fitting
 *        (GSL multifit_nlinear) by the thesis' two approaches.
 *
 * Equation of motion of a sphere of diameter d, mass M = rho_p pi d^3 / 6,
 * frontal area A = pi d^2 / 4, depth P(t), velocity V(t) = dP/dt:
 *     -M dV/dt = F(V),   P(0) = 0, V(0) = v0,
 * with the retarding force F of the model:
 *  - Poncelet (Eq. 4.1, 4.4, 4.5): F = B V^2 + C, B = rho_t pi d^2 C_d / 8,
 *    C = R pi d^2 / 4;
 *  - Liu (Eq. 4.8-4.9): F = 1/2 C_d rho_t A V^2 + C_v A V
 *    + A sigma0 [1 + (edot / edot0)^2], edot = V / d (the thesis prints
 *    F_I without rho_t; its fitted C_d ~ 0.4-0.8 only make sense with it);
 *  - Modified Clift-Gauvin (Eq. 4.10-4.11): F = 1/2 C_d^CG(Re) rho_t A V^2
 *    + A R, Re = rho_t V d / eta, valid for Re < 1e5.
 * The motion ends at T_f, when V = 0 (the models have no rebound);
 * P_max = P(T_f).  The experimental convention adds the nose, d/2 (Eq. 4.7).
 * Units SI.
 */
#ifndef SPALL_PENETRATION_H
#define SPALL_PENETRATION_H

#include <stddef.h>

struct spall_error;

/** The analytical penetration models. */
enum pen_model {
    PEN_PONCELET = 0, /**< Eq. 4.1: coefficients C_d, R */
    PEN_LIU = 1,      /**< Eq. 4.8: coefficients C_d, C_v, sigma0 (edot0 fixed) */
    PEN_MCG = 2       /**< Eq. 4.10: coefficients eta, R */
};

/** Reynolds number above which the Clift-Gauvin drag law is not valid. */
#define PEN_MCG_RE_MAX 1.0e5

/** A projectile/target pair and the model's coefficients (SI). */
struct pen_params {
    enum pen_model model;
    double d;      /**< projectile diameter [m] */
    double rho_p;  /**< projectile density [kg/m^3] */
    double rho_t;  /**< target density [kg/m^3] */
    double cd;     /**< drag coefficient C_d (Poncelet, Liu) */
    double R;      /**< strength resistance R [Pa] (Poncelet, MCG) */
    double cv;     /**< Liu viscous coefficient C_v [Pa s/m] */
    double sigma0; /**< Liu static resistance sigma0 [Pa] */
    double edot0;  /**< Liu reference strain rate [1/s] (edot = V/d) */
    double eta;    /**< MCG dynamic viscosity eta [Pa s] */
};

/** Results of one penetration. */
struct pen_result {
    double t_f;      /**< time at which V = 0 [s] */
    double p_max;    /**< P(T_f) without the nose [m] */
    double re_max;   /**< MCG: Reynolds number at v0 (its maximum); else 0 */
    int closed_form; /**< 1 if from a closed form, 0 if integrated */
};

/** Model name ("poncelet", "liu", "mcg") and the reverse look-up
 *  (also accepts "modified-cg"); returns SPALL_ERR_INPUT if unknown. */
const char *pen_model_name(enum pen_model m);
int pen_model_from_name(const char *name, enum pen_model *m, struct spall_error *err);

/** Check the parameters of the chosen model (finite, positive, Re), one
 *  line naming the first bad one; SPALL_ERR_INPUT / SPALL_ERR_PHYSICS. */
int pen_params_check(const struct pen_params *p, struct spall_error *err);

/** Projectile mass rho_p pi d^3 / 6 [kg]. */
double pen_mass(const struct pen_params *p);

/** Retarding force F(V) >= 0 for V >= 0 [N]. */
double pen_force(const struct pen_params *p, double v);

/** Clift-Gauvin drag coefficient (Eq. 4.11) at Reynolds number @p re > 0. */
double pen_cd_clift_gauvin(double re);

/** Poncelet in closed form (Eq. 4.2, 4.3, 4.6): T_f, P_max, and P(t), V(t)
 *  at @p n times @p t (P and V may be NULL; t > T_f gives P_max, 0).
 *  p->model must be PEN_PONCELET. */
int pen_poncelet(const struct pen_params *p, double v0, size_t n, const double *t, double *P,
                 double *V, struct pen_result *res, struct spall_error *err);

/** Closed form where one exists (Poncelet; Liu when its force, a quadratic
 *  a V^2 + b V + c, has 4ac > b^2), else the ODE integrated with GSL
 *  (rk8pd, relative tolerance 1e-12).  Fills @p res and, for n > 0, P(t),
 *  V(t) at the times @p t (ascending not required; t beyond T_f gives
 *  P_max, 0).  @p force_ode = 1 integrates even when a closed form exists
 *  (used to check one against the other). */
int pen_solve(const struct pen_params *p, double v0, size_t n, const double *t, double *P,
              double *V, int force_ode, struct pen_result *res, struct spall_error *err);

/** Which experimental data a fit uses (the thesis' approaches, sec. 4.2.2.2). */
enum pen_fit_kind {
    PEN_FIT_TRAJECTORY = 0, /**< (a): one P(t) curve, fixed d and v0 */
    PEN_FIT_POINTS = 1      /**< (b): many (d, v0, P_max) points */
};

/** Maximum number of fitted coefficients (Liu: 3). */
#define PEN_FIT_MAX_COEF 3

/** Data and settings of a fit.  Arrays are borrowed. */
struct pen_fit_input {
    enum pen_fit_kind kind;
    struct pen_params base; /**< model, densities, fixed coefficients, initial guesses;
                                 for (a) also d */
    double v0;              /**< (a): impact velocity */
    size_t n;               /**< number of data rows */
    const double *t;        /**< (a): times [s] */
    const double *P;        /**< (a): depths [m] */
    const double *d;        /**< (b): diameters [m] */
    const double *v0s;      /**< (b): impact velocities [m/s] */
    const double *pmax;     /**< (b): measured maximum depths [m] */
    int nose;               /**< (b): measured depths include the nose d/2 (Eq. 4.7) */
};

/** Result of a fit: coefficients in the model's order (Poncelet: C_d, R;
 *  Liu: C_d, C_v, sigma0; MCG: eta, R), their standard errors and 95 %
 *  confidence intervals (Student t, from the covariance of the fit done in
 *  log-coefficients, so the intervals are asymmetric and positive). */
struct pen_fit_result {
    int n_coef;
    const char *names[PEN_FIT_MAX_COEF];
    double value[PEN_FIT_MAX_COEF];
    double std_err[PEN_FIT_MAX_COEF];
    double ci_lo[PEN_FIT_MAX_COEF];
    double ci_hi[PEN_FIT_MAX_COEF];
    /** correlation of the (log) coefficients: near +-1 means the data
     *  cannot separate the two (e.g. Liu's C_v from P_max points alone) */
    double corr[PEN_FIT_MAX_COEF][PEN_FIT_MAX_COEF];
    double rms;       /**< root-mean-square residual [m] ((a)) or [1] (P_max/d, (b)) */
    double max_abs;   /**< largest |residual|, same unit */
    double chisq;     /**< sum of squared residuals */
    int dof;          /**< n - n_coef */
    int iterations;
    int converged;    /**< 1 if GSL reported convergence */
    struct pen_params fitted; /**< base with the fitted coefficients */
};

/** Fit the model's coefficients with gsl_multifit_nlinear (trust region,
 *  Levenberg-Marquardt).  Residuals: (a) P_model(t_i) - P_i [m];
 *  (b) (P_model,max - P_max,i) / d_i (the thesis' normalised depth).
 *  @p residuals (may be NULL) receives the n residuals at the solution. */
int pen_fit(const struct pen_fit_input *in, struct pen_fit_result *out, double *residuals,
            struct spall_error *err);

/** Columns of a numeric CSV file read by pen_csv_read. */
struct pen_csv {
    size_t n_rows, n_cols;
    char **names;  /**< column names from the header */
    double *data;  /**< row-major n_rows x n_cols */
};

/** Read a CSV file: a header line of column names, then numeric rows;
 *  lines starting with '#' and blank lines are skipped.  Errors name the
 *  file and line.  Free with pen_csv_free. */
int pen_csv_read(const char *path, struct pen_csv *csv, struct spall_error *err);
/** Index of column @p name (case-sensitive), or -1. */
int pen_csv_column(const struct pen_csv *csv, const char *name);
void pen_csv_free(struct pen_csv *csv);

/** Settings of the cavity measurement ([Meng2021] sec. 4.4.2.2, Fig. 4.17-4.18). */
struct pen_cavity_opts {
    double axis_x, axis_y; /**< shot line: x = axis_x, y = axis_y, along z */
    double depth;          /**< slab centre, below the surface z = surface [m] (15 um in Fig. 4.17) */
    double surface;        /**< z of the undisturbed target surface [m] */
    double slab;           /**< slab thickness [m] (a few particle spacings) */
    int sectors;           /**< angular sectors (>= 4); 0: 16 */
};

/** Cavity diameters at one depth from particle positions (one frame):
 *  D1, the empty cavity, from the particles nearest the axis whatever
 *  their state; D2, the cavity including failed particles, from the
 *  nearest intact ones (the thesis' D1 and D2, Fig. 4.18).  In each
 *  angular sector the cavity radius is the smallest r - dx/2 (dx: the
 *  particle's spacing, its extent) of the slab's particles, floored at 0;
 *  D = 2 x the median over the sectors, so a single stray particle on the
 *  axis does not close the cavity.  A sector without particles counts as
 *  infinitely open.  @p failed may be NULL (no failed particles: D2 = D1),
 *  @p dx may be NULL (point particles).  Sets *d1 = *d2 = 0 if no particle
 *  lies in the slab. */
int pen_cavity_diameters(size_t n, const double *x, const double *y, const double *z,
                         const double *dx, const unsigned char *failed,
                         const struct pen_cavity_opts *o, double *d1, double *d2,
                         struct spall_error *err);

#endif
