// bedlam — drag laws: the interphase momentum-exchange coefficient of gas-solid flows.
//
// Every law gives beta [kg/(m^3 s)], the coefficient in the force per unit volume that the gas
// exerts on the solids, beta (u - v), for a voidage eps (solids fraction phi = 1 - eps),
// particle diameter d, slip speed |u - v| between the interstitial gas velocity u and the
// particle velocity v, gas density rho and viscosity mu. The force on one particle of volume
// V_p is then beta V_p / phi (u - v); bdl_drag_per_volume returns beta / phi, finite as phi -> 0,
// so a single particle in a large cell is handled without dividing zero by zero.
// Pressure-gradient (buoyancy) forces are separate ("model A" of Sanghishetty et al. 2024,
// supplement, eq. 4).
#ifndef BDL_DRAG_H
#define BDL_DRAG_H

#include "core/names.h"

#define BDL_DRAG_LAWS(X)                                                                           \
    X(DRAG_STOKES, "stokes", "Stokes: 3 pi mu d, no voidage correction")                           \
    X(DRAG_SCHILLER_NAUMANN, "schiller_naumann", "Schiller & Naumann (1935), single sphere")       \
    X(DRAG_WEN_YU, "wen_yu", "Wen & Yu (1966): eps^-2.65 times the single-sphere law")             \
    X(DRAG_ERGUN, "ergun", "Ergun (1952) packed bed")                                              \
    X(DRAG_GIDASPOW, "gidaspow",                                                                   \
      "Gidaspow / Ding & Gidaspow (1990): Ergun below eps 0.8, Wen-Yu above")                      \
    X(DRAG_SYAMLAL_OBRIEN, "syamlal_obrien", "Syamlal & O'Brien (1988), C and D adjustable")       \
    X(DRAG_DI_FELICE, "di_felice", "Di Felice (1994): eps^-chi(Re)")                               \
    X(DRAG_PATANKAR, "patankar",                                                                   \
      "Patankar & Joseph (2001), after Gibilaro et al. (1985): Cd eps^-1.8, Re at eps |u - v|")    \
    X(DRAG_BEETSTRA, "beetstra",                                                                   \
      "Beetstra, van der Hoef & Kuipers (2007), from lattice-Boltzmann")                           \
    X(DRAG_TENNETI, "tenneti", "Tenneti, Garg & Subramaniam (2011), from particle-resolved DNS")   \
    X(DRAG_HDF, "hdf",                                                                             \
      "HDF: Hoelzer & Sommerfeld (2008) x Di Felice (1994), Ergun cap where dense (Mahajan 2019)") \
    X(DRAG_STE, "ste",                                                                             \
      "STE: Sanjeevi et al. (2018) AR-4 rod x Tenneti et al. (2011) ratio (Mahajan 2019)")         \
    X(DRAG_STA, "sta",                                                                             \
      "STA: Sanjeevi et al. (2018) AR-4 rod x Tang et al. (2015) ratio (Mahajan 2019)")            \
    X(DRAG_TSUJI, "tsuji",                                                                         \
      "Tsuji et al. (1993), Sun (2007) eq. 7.30: Ergun to eps 0.8, above it eps^-2.7 and Cd 0.43")

typedef enum bdl_drag_law { BDL_DRAG_LAWS(BDL_ENUM_ITEM) BDL_DRAG_LAW_COUNT } bdl_drag_law;

/// Scene words ("wen_yu", ...; NULL-terminated) and one-line descriptions, indexed by law.
extern const char *const bdl_drag_law_names[];
extern const char *const bdl_drag_law_texts[];

typedef struct bdl_drag_params {
    double syamlal_c,
        syamlal_d; ///< Syamlal-O'Brien C and D (default 0.8, 2.65; Sun 2007, table 4.3)
} bdl_drag_params;

/// The defaults: C = 0.8, D = 2.65.
bdl_drag_params bdl_drag_default_params(void);

/// beta / phi [kg/(m^3 s)]: the drag on one particle is this times V_p (u - v).
double bdl_drag_per_volume(bdl_drag_law law, const bdl_drag_params *p, double eps, double d,
                           double slip, double rho, double mu);

/// The shape the drag laws see: a sphere (shaft 0) or a spherocylinder, and how it lies in the
/// slip. Sphere laws use the volume-equivalent diameter of a rod; the rod laws (hdf, ste, sta) its
/// orientation too (docs/theory-rods.md, "Drag").
typedef struct bdl_drag_shape {
    double diameter;  ///< d_p [m]
    double shaft;     ///< L_rod, the cylinder between the caps (tip to tip less d_p) [m]; 0: sphere
    double cos_theta; ///< cosine of the angle between the axis and the slip velocity
} bdl_drag_shape;

/// Sphericity phi, crosswise phi_perp and lengthwise phi_par (Hoelzer & Sommerfeld 2008, in
/// Mahajan's 2019 form: A_perp = pi d^2/4 + d L sin theta, A_par = pi d^2/4 + d L cos theta) and
/// volume-equivalent diameter d_e of a shape.
typedef struct bdl_drag_sphericity {
    double phi, phi_perp, phi_par, d_e;
} bdl_drag_sphericity;
bdl_drag_sphericity bdl_drag_sphericities(const bdl_drag_shape *s);

/// Hoelzer & Sommerfeld (2008) single-particle C_D at Re (log10 in the last term, as in the
/// original paper).
double bdl_drag_hs_cd(double re, const bdl_drag_sphericity *sp);
/// Sanjeevi, Kuipers & Padding (2018) single AR-4 spherocylinder C_D at Re, sin^2 theta blend.
double bdl_drag_sanjeevi_cd(double re, double sin2);
/// Voidage corrections at voidage eps and Re = eps rho d_e |slip| / mu: Di Felice's eps^(2-beta)
/// (log10 in beta), and the ratios g = F(eps, Re) / F(1, Re) of Tang et al. (2015) and Tenneti
/// et al. (2011).
double bdl_drag_di_felice_factor(double eps, double re);
double bdl_drag_tang_ratio(double eps, double re);
double bdl_drag_tenneti_ratio(double eps, double re);

/// As bdl_drag_per_volume for a particle of shape s (V_p its volume): the drag on it is this
/// times V_p (u - v).
double bdl_drag_shape_per_volume(bdl_drag_law law, const bdl_drag_params *p, double eps,
                                 const bdl_drag_shape *s, double slip, double rho, double mu);

/// beta [kg/(m^3 s)] = phi * bdl_drag_per_volume.
double bdl_drag_beta(bdl_drag_law law, const bdl_drag_params *p, double eps, double d, double slip,
                     double rho, double mu);

#endif
