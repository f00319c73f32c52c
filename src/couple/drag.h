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
    X(DRAG_BEETSTRA, "beetstra",                                                                   \
      "Beetstra, van der Hoef & Kuipers (2007), from lattice-Boltzmann")                           \
    X(DRAG_TENNETI, "tenneti", "Tenneti, Garg & Subramaniam (2011), from particle-resolved DNS")

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

/// beta [kg/(m^3 s)] = phi * bdl_drag_per_volume.
double bdl_drag_beta(bdl_drag_law law, const bdl_drag_params *p, double eps, double d, double slip,
                     double rho, double mu);

#endif
