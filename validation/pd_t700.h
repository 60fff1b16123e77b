/**
 * @file pd_t700.h
 * @brief The one place holding the T700/epoxy UD lamina data used by the
 *        peridynamic lamina cases and examples ([PDLM2019]'s Table 1 was lost
 *        in extraction; these are typical values, digest "Benchmarks").
 *
 * Sources: Toray T700S data sheet and typical T700/epoxy UD prepreg values
 * (E1 = 125-135 GPa, E2 = 8-9 GPa, G12 = 4-5 GPa, nu12 = 0.3, rho = 1550,
 * digest of [PDLM2019]); G_Ic, G_IIc of epoxy-matrix CFRP (0.2-0.4 and
 * 0.6-1.0 kJ/m^2, same digest); translaminar (fiber) fracture toughness of
 * UD CFRP ~ 50-100 kJ/m^2 (Laffan, Pinho et al., Compos. Sci. Technol. 2012)
 * - we take 60 kJ/m^2.  The same numbers appear in examples/pd_lamina_*.
 */
#ifndef SPALL_VALIDATION_PD_T700_H
#define SPALL_VALIDATION_PD_T700_H

#define T700_RHO 1550.0    /* kg/m^3 */
#define T700_E1 130.0e9    /* Pa */
#define T700_E2 8.5e9      /* Pa */
#define T700_G12 4.5e9     /* Pa */
#define T700_NU12 0.3
#define T700_GIC 300.0     /* J/m^2, matrix mode I */
#define T700_GIIC 800.0    /* J/m^2, matrix mode II */
#define T700_GF 60.0e3     /* J/m^2, fiber (translaminar) */
#define T700_PLY 0.1e-3    /* m, UD-T700-100gsm ply thickness (~0.1 mm) */

/** The lamina as a YAML flow mapping (fiber angle appended by the caller). */
#define T700_YAML                                                                            \
    "{density: 1550, fiber_modulus: 130.0e9, transverse_modulus: 8.5e9, shear_modulus: "     \
    "4.5e9, major_poisson_ratio: 0.3, matrix_fracture_energy: 300, mode2_fracture_energy: " \
    "800, fiber_fracture_energy: 60.0e3"

#endif
