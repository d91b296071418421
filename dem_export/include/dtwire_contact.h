/* dtwire contact laws, C ABI (libdtwire_contact). Any DEM code written in C, C++, Fortran
 * (iso_c_binding) or Python (ctypes) can create a bond, advance it by generalised displacement
 * increments and read its forces. No C++ exception crosses this interface: functions report
 * failure by their return value and dtwire_contact_last_error() says why (per thread).
 *
 * Generalised kinematics, in the bond's local frame (x along the bond), SI units:
 *   0: axial displacement u [m]      <-> axial force N [N] (tension > 0)
 *   1, 2: shear displacements [m]    <-> shear forces V_y, V_z [N]
 *   3: torsion rotation [rad]        <-> torque T [N m]
 *   4, 5: bending rotations [rad]    <-> bending moments M_y, M_z [N m]
 * Laws: "thesis", "macro3d", "parallel_bond", "wirepm"; parameters in docs/dem_laws.md.
 *
 * macro3d's optional bending-axial parameters (both off by default: the law is then the same,
 * bit for bit, as without them):
 *   bending_axial_coupling [1]  kappa >= 0; > 0 makes the bending stiffness depend on N through
 *                               the chord stretch s = u + kappa L/24 |theta|^2 (L =
 *                               reference_length_m [m], then required; u is the CHORD elongation,
 *                               i.e. the change of the distance between the nodes):
 *                               N = k_a (s - u_p), M = k_m (theta - theta_p) + 2 (kappa L/24) N theta,
 *                               so elastically M = (k_m + kappa N L/12) theta; 1 = the geometric
 *                               (first-order beam-column) value. The compressive strength Nc_N is
 *                               then capped at 0.9 k_m / (2 kappa L/24).
 *   moment_hardening_ratio [1]  r_M >= 1: the moment capacity hardens from D sqrt(m_f) N0 to
 *                               r_M D sqrt(m_f) N0 (default Nult/N0, the thesis' tie to the axial
 *                               hardening).
 */
#ifndef DTWIRE_CONTACT_H
#define DTWIRE_CONTACT_H

#include <stddef.h>

#if defined(_WIN32)
#define DTWIRE_CONTACT_API __declspec(dllexport)
#else
#define DTWIRE_CONTACT_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dtwire_bond dtwire_bond; /* opaque */

typedef enum {
  DTWIRE_FAILURE_NONE = 0,
  DTWIRE_FAILURE_NECKING = 1,   /* tension-dominated */
  DTWIRE_FAILURE_SHEAR = 2,     /* shear/bending-dominated */
  DTWIRE_FAILURE_ELONGATION = 3 /* elongation limit (e.g. WirePM) */
} dtwire_failure_mode;

typedef struct {
  double external; /* work done on the bond [J] */
  double elastic;  /* stored [J] */
  double plastic;  /* dissipated by plastic flow [J] */
  double damage;   /* dissipated by damage and at break [J] */
} dtwire_energy;

/* Creates a bond of law `law_name` from `count` named parameters (names[i] = values[i]).
 * Returns NULL on error (unknown law, a name the law does not read, missing or invalid parameter). */
DTWIRE_CONTACT_API dtwire_bond* dtwire_bond_create(const char* law_name, const char* const* names,
                                                  const double* values, size_t count);
/* Copies a bond with its whole state; NULL on error. */
DTWIRE_CONTACT_API dtwire_bond* dtwire_bond_clone(const dtwire_bond* bond);
DTWIRE_CONTACT_API void dtwire_bond_destroy(dtwire_bond* bond); /* NULL is allowed */

/* Advances the bond by 6 displacement increments. Returns 0 on success, -1 on error. */
DTWIRE_CONTACT_API int dtwire_bond_update(dtwire_bond* bond, const double increments[6]);
/* Writes the 6 generalised forces. Returns 0 on success, -1 on error. */
DTWIRE_CONTACT_API int dtwire_bond_forces(const dtwire_bond* bond, double forces[6]);
DTWIRE_CONTACT_API int dtwire_bond_energy(const dtwire_bond* bond, dtwire_energy* energy);
/* 1 if broken, 0 if not, -1 on error. */
DTWIRE_CONTACT_API int dtwire_bond_broken(const dtwire_bond* bond);
/* A dtwire_failure_mode, or -1 on error. */
DTWIRE_CONTACT_API int dtwire_bond_failure_mode(const dtwire_bond* bond);

/* Message of the last error in this thread ("" if none). Valid until the next call that fails. */
DTWIRE_CONTACT_API const char* dtwire_contact_last_error(void);

#ifdef __cplusplus
}
#endif

#endif /* DTWIRE_CONTACT_H */
